// A recipe fit on its own thread (fit_runner.h).

#include "fit_runner.h"

#include <QMetaObject>
#include <QPointer>
#include <QThread>

#include <exception>

namespace paintlab::gui {

FitRunner::FitRunner(QObject* parent) : QObject(parent) {
    qRegisterMetaType<paintlab::fit::FitProgress>("paintlab::fit::FitProgress");
    qRegisterMetaType<std::shared_ptr<const paintlab::fit::FitResult>>(
        "std::shared_ptr<const paintlab::fit::FitResult>");
}

FitRunner::~FitRunner() {
    cancel();
    if (m_thread != nullptr) {
        m_thread->wait();
        delete m_thread;
    }
}

bool FitRunner::start(fit::FitProblem problem) {
    if (m_thread != nullptr) return false;
    try {
        fit::validateFitProblem(problem);
    } catch (const std::exception& e) {
        emit failed(QString::fromStdString(e.what()));
        return true;
    }
    m_cancel = std::make_shared<std::atomic<bool>>(false);
    QPointer<FitRunner> self(this);
    m_thread = QThread::create([self, cancel = m_cancel, problem = std::move(problem)]() {
        // Progress is thinned to what the eye can follow: the cost curve and
        // bar need no more than ~20 updates a second.
        auto last = std::make_shared<long>(-1);
        const fit::FitProgressCallback progress = [self, cancel, last](const fit::FitProgress& p) {
            if (p.evaluations - *last >= 4 || p.fraction >= 1.0) {
                *last = p.evaluations;
                QMetaObject::invokeMethod(
                    self.data(),
                    [self, p]() {
                        if (self) emit self->progressed(p);
                    },
                    Qt::QueuedConnection);
            }
            return !cancel->load();
        };
        std::function<void()> deliver;
        try {
            auto result = std::make_shared<const fit::FitResult>(fit::fitRecipe(problem, progress));
            deliver = [self, result]() {
                if (self) emit self->finished(result);
            };
        } catch (const fit::FitCancelled&) {
            deliver = [self]() {
                if (self) emit self->cancelled();
            };
        } catch (const std::exception& e) {
            deliver = [self, message = QString::fromStdString(e.what())]() {
                if (self) emit self->failed(message);
            };
        }
        QMetaObject::invokeMethod(
            self.data(),
            [self, deliver]() {
                if (!self) return;
                self->threadDone();
                deliver();
            },
            Qt::QueuedConnection);
    });
    m_thread->start(QThread::LowPriority);
    return true;
}

void FitRunner::cancel() {
    if (m_cancel) m_cancel->store(true);
}

void FitRunner::wait() {
    if (m_thread != nullptr) m_thread->wait();
}

void FitRunner::threadDone() {
    if (m_thread == nullptr) return;
    m_thread->wait();
    delete m_thread;
    m_thread = nullptr;
    m_cancel.reset();
}

}  // namespace paintlab::gui
