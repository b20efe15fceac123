// One job on a thread of its own (background_job.h).

#include "background_job.h"

#include <QMetaObject>
#include <QPointer>
#include <QThread>

#include <utility>

namespace paintlab::gui {

BackgroundJob::BackgroundJob(QObject* parent) : QObject(parent) {}

BackgroundJob::~BackgroundJob() {
    cancel();
    if (m_thread != nullptr) {
        m_thread->wait();
        delete m_thread;
    }
}

bool BackgroundJob::startJob(Work work) {
    if (m_thread != nullptr) return false;
    m_cancel = std::make_shared<std::atomic<bool>>(false);
    QPointer<BackgroundJob> self(this);
    m_thread = QThread::create([self, cancel = m_cancel, work = std::move(work)]() {
        std::function<void()> deliver = work(*cancel);
        QMetaObject::invokeMethod(
            self.data(),
            [self, deliver = std::move(deliver)]() {
                if (!self) return;
                self->threadDone();
                if (deliver) deliver();
            },
            Qt::QueuedConnection);
    });
    m_thread->start(QThread::LowPriority);
    return true;
}

void BackgroundJob::post(std::function<void()> f) {
    QPointer<BackgroundJob> self(this);
    QMetaObject::invokeMethod(
        this,
        [self, f = std::move(f)]() {
            if (self) f();
        },
        Qt::QueuedConnection);
}

void BackgroundJob::cancel() {
    if (m_cancel) m_cancel->store(true);
}

void BackgroundJob::wait() {
    if (m_thread != nullptr) m_thread->wait();
}

void BackgroundJob::threadDone() {
    if (m_thread == nullptr) return;
    m_thread->wait();
    delete m_thread;
    m_thread = nullptr;
    m_cancel.reset();
}

}  // namespace paintlab::gui
