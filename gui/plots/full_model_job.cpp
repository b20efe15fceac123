#include "full_model_job.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/montecarlo/mc_table.h"
#include "paintlab/engine/recipe.h"

#include <exception>
#include <utility>

namespace paintlab::gui {

namespace {

// The settings of the CLI's `mc --table --explicit-flakes --seconds S`
// (cli/src/mc_command.cpp): 5 degree cones, the engine's other defaults.
mc::McSettings fullModelSettings(double budget_seconds) {
    mc::McSettings s;
    s.explicit_flakes = true;
    s.histogram_cone_deg = 5.0;
    s.max_paths = 1000000000;  // the time budget decides
    s.max_seconds = budget_seconds;
    // Every (band, node) runs at least one round, and the preview grid has
    // ~250 of them: the engine's 16 x 1024-path rounds made that ~20 s on 2
    // cores whatever the budget. 8 x 128 paths (one chunk per batch, ~5 ms)
    // keep a short budget short and cancel() quick.
    s.chunk_paths = 128;
    s.chunks_per_round = 8;
    return s;
}

}  // namespace

FullModelJob::FullModelJob(QObject* parent) : QObject(parent) { m_pool.setMaxThreadCount(1); }

FullModelJob::~FullModelJob() {
    if (m_cancel) m_cancel->store(true);
    m_pool.clear();  // runs not yet started
    m_pool
        .waitForDone();  // the running one stops at its next progress call; its posted result dies with this
}

void FullModelJob::cancel() {
    // A queued run is not removed from the pool: it sees the flag at once and
    // reports cancelled(), so busy() always ends.
    if (m_cancel) m_cancel->store(true);
}

void FullModelJob::start(const Recipe& recipe, double budget_seconds) {
    cancel();  // the running run stops at its next round; this one starts after it on the single thread
    auto cancel_flag = std::make_shared<std::atomic<bool>>(false);
    m_cancel = cancel_flag;
    const quint64 generation = ++m_generation;
    m_busy = true;
    m_pool.start([this, recipe, budget_seconds, cancel_flag, generation]() {
        Result result;
        QString error;
        bool was_cancelled = false;
        int last_percent = -1;
        // Called on this thread only (runMonteCarlo calls it between rounds).
        const ProgressCallback on_progress = [&](double fraction) {
            if (cancel_flag->load()) return false;
            const int percent = static_cast<int>(100.0 * fraction);
            if (percent != last_percent) {
                last_percent = percent;
                QMetaObject::invokeMethod(
                    this,
                    [this, percent, generation]() {
                        if (generation == m_generation) emit this->progress(percent);
                    },
                    Qt::QueuedConnection);
            }
            return true;
        };
        try {
            if (!cancel_flag->load()) {
                mc::McTable table = mc::tabulateMonteCarlo(recipe, presetSettings(Preset::Preview),
                                                           fullModelSettings(budget_seconds), on_progress);
                result.paths = table.total_paths;
                result.seconds = table.seconds;
                result.brdf = std::make_shared<const LayeredBrdf>(std::move(table.brdf));
            } else {
                was_cancelled = true;
            }
        } catch (const std::exception& e) {
            if (cancel_flag->load())
                was_cancelled = true;  // Error("cancelled") from our callback
            else
                error = QString::fromUtf8(e.what());
        } catch (...) {  // nothing may escape a pool task
            error = QStringLiteral("the full model failed with an unknown error");
        }
        QMetaObject::invokeMethod(
            this,
            [this, result = std::move(result), error, was_cancelled, generation]() {
                if (generation != m_generation) return;  // a newer request replaced this one
                m_busy = false;
                if (was_cancelled)
                    emit cancelled();
                else if (!error.isEmpty())
                    emit failed(error);
                else
                    emit finished(result);
            },
            Qt::QueuedConnection);
    });
}

}  // namespace paintlab::gui
