#include "paintlab/engine/montecarlo/monte_carlo.h"

#include "mc_engine.h"
#include "run_deadline.h"

#include <tbb/global_control.h>

#include <chrono>
#include <memory>
#include <variant>

namespace paintlab::mc {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

McResult runMonteCarlo(const Recipe& recipe, std::span<const double> wavelengths_nm,
                       std::span<const IncidenceRequest> requests, const McSettings& settings,
                       const ProgressCallback& progress) {
    const auto start = Clock::now();
    // Jobs run band by band; the same incidence in each band is one kind.
    std::vector<std::size_t> kinds;
    for (std::size_t b = 0; b < wavelengths_nm.size(); ++b)
        for (std::size_t i = 0; i < requests.size(); ++i) kinds.push_back(i);
    RunDeadline deadline(settings.max_seconds, std::move(kinds));
    std::unique_ptr<tbb::global_control> threads;
    if (settings.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        static_cast<std::size_t>(settings.threads));
    std::function<bool()> keep_going;
    if (progress) keep_going = [&progress] { return progress(0.0); };
    const McEngine engine(recipe, settings, keep_going);
    McResult result;
    result.wavelengths_nm.assign(wavelengths_nm.begin(), wavelengths_nm.end());
    result.bands.resize(wavelengths_nm.size());
    const std::size_t jobs = wavelengths_nm.size() * requests.size();
    std::size_t jobs_done = 0;
    BandsInTurn bands(engine, {wavelengths_nm.begin(), wavelengths_nm.end()});
    for (std::size_t b = 0; b < wavelengths_nm.size(); ++b) {
        const McEngine::Band& band = bands.band(b);
        for (std::size_t i = 0; i < requests.size(); ++i) {
            const JobSpec job{requests[i].wi, requests[i].wo, {}, {}, 0};
            std::function<bool(double)> job_progress;
            if (progress)
                job_progress = [&](double fraction) {
                    return progress((static_cast<double>(jobs_done) + fraction) / static_cast<double>(jobs));
                };
            JobResult r = engine.run(band, b, i, job, deadline.nextJobBudget(), job_progress);
            deadline.jobDone(r.incidence.seconds, largestRelativeError(r, job.orders));
            result.total_paths += r.incidence.paths;
            result.bands[b].push_back(std::move(r.incidence));
            ++jobs_done;
        }
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

std::vector<std::string> estimatorLimitations(const Recipe& recipe) {
    std::vector<std::string> notes;
    for (const auto& layer : recipe.layers)
        for (const auto& component : layer.components) {
            double spread = -1.0;
            if (const auto* m = std::get_if<MirrorFlake>(&component)) spread = m->orientation_spread_deg;
            if (const auto* i = std::get_if<InterferenceFlake>(&component))
                spread = i->orientation_spread_deg;
            if (spread == 0.0)
                notes.push_back("layer '" + layer.name + "', flake '" + componentName(component) +
                                "': orientation spread 0 makes its reflection a delta; f misses light whose "
                                "last bounce is such a flake (albedo exact)");
        }
    if (std::holds_alternative<MetalSubstrate>(recipe.substrate))
        notes.emplace_back("metal substrate: its unscattered mirror image of the beam is a delta, not in f "
                           "(in the albedo); the fast model carries it on its table's diagonal");
    return notes;
}

}  // namespace paintlab::mc