#include "latest_job.h"

#include <exception>
#include <utility>

namespace paintlab::gui {

LatestJob::LatestJob(QObject* parent) : QObject(parent) { m_pool.setMaxThreadCount(1); }

LatestJob::~LatestJob() {
    m_pending.reset();
    m_pool.waitForDone();  // its queued result is discarded with this object
}

void LatestJob::run(Work work) {
    if (m_running) {
        m_pending = std::move(work);
        return;
    }
    start(std::move(work));
}

void LatestJob::start(Work work) {
    m_running = true;
    m_pool.start([this, work = std::move(work)]() {
        Apply apply;
        QString error;
        try {
            apply = work();
        } catch (const std::exception& e) {
            error = QString::fromUtf8(e.what());
        }
        QMetaObject::invokeMethod(
            this,
            [this, apply = std::move(apply), error]() {
                m_running = false;
                if (!error.isEmpty()) {
                    emit failed(error);
                } else if (apply) {
                    apply();
                    emit applied();
                }
                if (m_pending) {
                    Work next = std::move(*m_pending);
                    m_pending.reset();
                    start(std::move(next));
                } else {
                    emit becameIdle();
                }
            },
            Qt::QueuedConnection);
    });
}

}  // namespace paintlab::gui
