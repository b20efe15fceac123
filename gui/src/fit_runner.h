#pragma once
// A recipe fit (engine fit/fit.h) off the GUI thread: one fit at a time on
// its own thread, its progress (stage, evaluations, best cost) delivered on
// the GUI thread, cancellable at every model evaluation. A cancelled or
// failed fit changes nothing; a finished one hands its result over once.
// Destroying the runner cancels the fit and waits for its thread.

#include "background_job.h"

#include "paintlab/engine/fit/fit.h"

#include <QString>

#include <memory>

namespace paintlab::gui {

class FitRunner : public BackgroundJob {
    Q_OBJECT
public:
    explicit FitRunner(QObject* parent = nullptr);

    // Starts the fit; false if one is running. The problem is validated on
    // the GUI thread first: a bad one emits failed() at once.
    bool start(fit::FitProblem problem);
    // cancel(), running(), wait(): BackgroundJob's.

signals:
    void progressed(const paintlab::fit::FitProgress& progress);
    void finished(std::shared_ptr<const paintlab::fit::FitResult> result);
    void failed(const QString& message);
    void cancelled();
};

}  // namespace paintlab::gui
