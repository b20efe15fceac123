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
        } catch (...) {  // nothing may escape a pool task: the program would end
            error = QStringLiteral("the plot computation failed with an unknown error");
        }
        QMetaObject::invokeMethod(
            this,
            [this, apply = std::move(apply), error]() {
                // Still "running" while the result is delivered: work that a
                // slot of applied()/failed() asks for waits as pending instead
                // of starting beside the next job.
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
                    m_running = false;
                    emit becameIdle();
                }
            },
            Qt::QueuedConnection);
    });
}

}  // namespace paintlab::gui
