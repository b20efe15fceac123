#pragma once
// A recipe fit (engine fit/fit.h) off the GUI thread: one fit at a time on
// its own thread, its progress (stage, evaluations, best cost) delivered on
// the GUI thread, cancellable at every model evaluation. A cancelled or
// failed fit changes nothing; a finished one hands its result over once.
// Destroying the runner cancels the fit and waits for its thread.

#include "paintlab/engine/fit/fit.h"

#include <QObject>
#include <QString>

#include <atomic>
#include <memory>

class QThread;

namespace paintlab::gui {

class FitRunner : public QObject {
    Q_OBJECT
public:
    explicit FitRunner(QObject* parent = nullptr);
    ~FitRunner() override;
    FitRunner(const FitRunner&) = delete;
    FitRunner& operator=(const FitRunner&) = delete;
    FitRunner(FitRunner&&) = delete;
    FitRunner& operator=(FitRunner&&) = delete;

    // Starts the fit; false if one is running. The problem is validated on
    // the GUI thread first: a bad one emits failed() at once.
    bool start(fit::FitProblem problem);
    void cancel();
    bool running() const { return m_thread != nullptr; }
    // Waits for the running fit's thread (tests, shutdown); its signal is still delivered.
    void wait();

signals:
    void progressed(const paintlab::fit::FitProgress& progress);
    void finished(std::shared_ptr<const paintlab::fit::FitResult> result);
    void failed(const QString& message);
    void cancelled();

private:
    void threadDone();

    QThread* m_thread = nullptr;
    std::shared_ptr<std::atomic<bool>> m_cancel;
};

}  // namespace paintlab::gui
