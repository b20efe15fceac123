// A recipe fit on its own thread (fit_runner.h).

#include "fit_runner.h"

#include <exception>
#include <functional>
#include <utility>

namespace paintlab::gui {

FitRunner::FitRunner(QObject* parent) : BackgroundJob(parent) {
    qRegisterMetaType<paintlab::fit::FitProgress>("paintlab::fit::FitProgress");
    qRegisterMetaType<std::shared_ptr<const paintlab::fit::FitResult>>(
        "std::shared_ptr<const paintlab::fit::FitResult>");
}

bool FitRunner::start(fit::FitProblem problem) {
    if (running()) return false;
    try {
        fit::validateFitProblem(problem);
    } catch (const std::exception& e) {
        emit failed(QString::fromStdString(e.what()));
        return true;
    }
    return startJob([this, problem = std::move(problem)](const std::atomic<bool>& cancel) {
        // Progress is thinned to what the eye can follow: the cost curve and
        // bar need no more than ~20 updates a second.
        long last = -1;
        const fit::FitProgressCallback progress = [this, &cancel, &last](const fit::FitProgress& p) {
            if (p.evaluations - last >= 4 || p.fraction >= 1.0) {
                last = p.evaluations;
                post([this, p]() { emit progressed(p); });
            }
            return !cancel.load();
        };
        std::function<void()> deliver;
        try {
            auto result = std::make_shared<const fit::FitResult>(fit::fitRecipe(problem, progress));
            deliver = [this, result]() { emit finished(result); };
        } catch (const fit::FitCancelled&) {
            deliver = [this]() { emit cancelled(); };
        } catch (const std::exception& e) {
            deliver = [this, message = QString::fromStdString(e.what())]() { emit failed(message); };
        }
        return deliver;
    });
}

}  // namespace paintlab::gui
