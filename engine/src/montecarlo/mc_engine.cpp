#include "mc_engine.h"

#include "mc_bottom.h"

#include "mc_job_runner.h"
#include "mc_statistics.h"

#include "paintlab/engine/error.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <string>

namespace paintlab::mc {

namespace {

using Clock = std::chrono::steady_clock;

// A budgeted round's share of the job's time left.
constexpr double kRoundShare = 0.5;
// Paths per chunk of the pilot round behind an error target (the budget a safety net).
constexpr std::int64_t kPilotChunkPaths = 16;
// Behind an error target, the first round after the first rates' paths are
// dropped is a full round divided by this, and so is the stop rule's
// minimum of kept paths: a quarter
// round made the three-layer demo (1 % in 300-2,000 paths a job) keep
// 4,096; the sixteenth kept its errors as honest (docs/PERFORMANCE.md).
constexpr std::int64_t kFirstTargetRoundDivisor = 16;
// The largest weight of a path at the first rates kept beside the adapted
// ones (McEngine::run): the rate model's forecast from ~1k paths is rough,
// so they never count for more than an adapted path.
constexpr double kMaxFirstWeight = 1.0;
// Behind an error target, while a job looks short, a round is at most this
// many times the paths at the adapted rates so far (McEngine::run).
constexpr std::int64_t kRoundGrowth = 2;

// The estimates of a job from its batches' sums: over the batches' means
// when the batches trace different tiles, else over paths. `first`: per
// batch the paths at the first rates kept beside the later ones (empty:
// none), each weighing `first_weight` against a later path.
JobResult finish(const JobRunner& runner, const std::vector<Sums>& batches, const std::vector<Sums>& first,
                 double first_weight, bool over_batches, double seconds) {
    const std::size_t entries = runner.entries();
    Sums later(entries);
    Sums early(entries);
    for (const auto& b : batches) later.add(b);
    for (const auto& b : first) early.add(b);
    std::vector<double> weights;
    std::vector<std::vector<double>> batch_means;
    for (std::size_t k = 0; k < batches.size(); ++k) {
        const auto n_later = static_cast<double>(batches[k].paths);
        const double n_early = k < first.size() ? first_weight * static_cast<double>(first[k].paths) : 0.0;
        if (!(n_later + n_early > 0.0)) continue;
        std::vector<double> mean(batches[k].mean);
        if (n_early > 0.0)
            for (std::size_t e = 0; e < entries; ++e)
                mean[e] = (n_later * batches[k].mean[e] + n_early * first[k].mean[e]) / (n_later + n_early);
        weights.push_back(n_later + n_early);
        batch_means.push_back(std::move(mean));
    }
    const bool use_batches = over_batches && weights.size() >= 2;
    const auto n_later = static_cast<double>(later.paths);
    const double n_early = first_weight * static_cast<double>(early.paths);
    std::vector<double> column(weights.size());
    auto entry = [&](std::size_t k) {
        if (use_batches) {
            for (std::size_t b = 0; b < weights.size(); ++b) column[b] = batch_means[b][k];
            return batchMeansEstimate(column, weights);
        }
        const Estimate l = pooledEstimate(later.mean[k], later.m2[k], later.paths);
        if (!(n_early > 0.0)) return l;
        // The weighted mean of the two sets of paths and its error.
        const Estimate e = pooledEstimate(early.mean[k], early.m2[k], early.paths);
        const double w = n_later + n_early;
        return Estimate{(n_later * l.mean + n_early * e.mean) / w,
                        std::hypot(n_later * l.std_error, n_early * e.std_error) / w};
    };
    JobResult r;
    IncidenceResult& inc = r.incidence;
    inc.specular = runner.specular();
    inc.albedo = entry(kEscaped);
    inc.albedo.mean += inc.specular;  // exact, no variance
    inc.transmittance = entry(kTransmitted);
    for (std::size_t k = 0; k < runner.exitCount(); ++k) inc.brdf_per_sr.push_back(entry(kFirstExit + k));
    for (std::size_t k = kFirstExit + runner.exitCount(); k < runner.estimateEntries(); ++k)
        r.projection.push_back(entry(k));
    inc.paths = later.paths + (n_early > 0.0 ? early.paths : 0);
    inc.seconds = seconds;
    r.weighted_paths = n_later + n_early;
    r.batch_weights = std::move(weights);
    r.batch_means = std::move(batch_means);
    return r;
}

// The stop rule's target (McSettings::target_rel_error, target_abs_error_per_sr).
struct ErrorTarget {
    double rel = 0.0;
    double abs_per_sr = 0.0;
};

// The stop rule's error: the largest standard error over its tolerance of the
// albedo (relative), every f and the projection's order-0 entries (relative,
// or the absolute floor where that is larger); 1 or less: converged.
double worstErrorRatio(const JobResult& r, const ErrorTarget& target, int orders) {
    const auto ratio = [&target](const Estimate& e, double floor) {
        const double tolerance = std::max(target.rel * std::abs(e.mean), floor);
        return tolerance > 0.0 ? e.std_error / tolerance : 0.0;  // a zero estimate without a floor: exact
    };
    const IncidenceResult& inc = r.incidence;
    double worst = ratio(inc.albedo, 0.0);
    for (const auto& e : inc.brdf_per_sr) worst = std::max(worst, ratio(e, target.abs_per_sr));
    for (std::size_t k = 0; k < r.projection.size(); k += static_cast<std::size_t>(std::max(1, orders)))
        worst = std::max(worst, ratio(r.projection[k], target.abs_per_sr));
    return worst;
}

bool converged(const JobResult& r, const ErrorTarget& target, int orders) {
    return target.rel > 0.0 && worstErrorRatio(r, target, orders) <= 1.0;
}

// Behind an error target: the paths a job needs in all, as its estimates so
// far predict them (errors fall as 1 / sqrt(paths)), 10 % over so that a
// round seldom ends just short. NaN without an estimate yet.
double predictedPaths(const JobResult& current, const ErrorTarget& target, int orders) {
    const double ratio = worstErrorRatio(current, target, orders);
    return current.weighted_paths * 1.1 * ratio * ratio;
}

// Behind an error target: the paths of the next round, those predicted less
// those kept, within [first_round / 4, full_round]. The first round after
// the pilot is `first_round`: the stop rule reads the batches' spread only
// from there on (fixed rounds of a full round's paths had run the paints
// that converge within one well past the target).
std::int64_t targetRoundPaths(double predicted, std::int64_t kept, std::int64_t first_round,
                              std::int64_t full_round) {
    if (kept <= 0) return first_round;
    const double needed = predicted - static_cast<double>(kept);
    const std::int64_t min_round = std::max<std::int64_t>(1, first_round / 4);
    if (!(needed < static_cast<double>(full_round))) return full_round;  // NaN too
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(needed), min_round, full_round);
}

}  // namespace

double largestRelativeError(const JobResult& r, int orders) {
    return worstErrorRatio(r, ErrorTarget{1.0, 0.0}, orders);
}

McEngine::McEngine(const Recipe& recipe, const McSettings& settings, const std::function<bool()>& keep_going)
    : m_recipe(recipe), m_settings(settings), m_batches(std::max(1, settings.batches)) {
    if (settings.explicit_flakes && !(settings.histogram_cone_deg > 0.0))
        throw InputError("", "histogram_cone_deg",
                         "explicit flakes need the histogram estimator (a cone > 0)");
    if (!settings.explicit_flakes) return;
    // Explicit flakes: per batch one tile per layer with flakes, the same for
    // every band, built in parallel (each tile has its own seed and Embree device).
    std::vector<std::vector<FlakeGeometry>> geometries;
    std::vector<double> tops;
    double depth = 0.0;
    for (const auto& layer : recipe.layers) {
        geometries.push_back(layerFlakeGeometries(layer));
        tops.push_back(depth);
        depth += layer.thickness_um;
    }
    const std::size_t layers = recipe.layers.size();
    m_tiles.resize(static_cast<std::size_t>(m_batches));
    for (auto& tiles : m_tiles) tiles.resize(layers);
    m_tilts.assign(static_cast<std::size_t>(m_batches), std::vector<TiltIndex>(layers));
    m_groups.assign(static_cast<std::size_t>(m_batches), std::vector<FlakeGroups>(layers));
    m_last_flake.clear();
    for (std::size_t l = 0; l < layers; ++l)
        m_last_flake.push_back(lastFlakeLaw(geometries[l], tops[l], tops[l] + recipe.layers[l].thickness_um,
                                            settings.flake_polygon_sides));
    std::atomic<bool> stop{false};
    const auto build_tiles = [&] {
        tbb::parallel_for(std::size_t{0}, m_tiles.size() * layers, [&](std::size_t index) {
            const std::size_t k = index / layers;
            const std::size_t l = index % layers;
            if (geometries[l].empty()) return;
            // Batch 0 keeps the single tile's seed of earlier versions.
            const std::uint64_t tile_seed =
                settings.seed ^ (0x9e3779b97f4a7c15ULL * (l + 1)) ^ (0xd1b54a32d192ed03ULL * k);
            m_tiles[k][l] =
                std::make_unique<FlakeTile>(geometries[l], tops[l], tops[l] + recipe.layers[l].thickness_um,
                                            tile_seed, settings.tile_flakes, settings.max_tile_flakes,
                                            settings.reject_overlaps, &stop, settings.flake_polygon_sides);
            if (settings.connections && settings.glint_azimuths) {
                m_tilts[k][l] = tiltIndex(*m_tiles[k][l]);
                if (settings.delta_walks && settings.first_flake_walks)
                    m_groups[k][l] = flakeGroups(*m_tiles[k][l], m_tilts[k][l], tops[l],
                                                 tops[l] + recipe.layers[l].thickness_um);
            }
        });
    };
    if (keep_going) {
        // The build runs on a helper thread (which joins TBB's arena like this
        // one would, so both cores still build) while this thread asks
        // keep_going: a cancel then lands within ~20 ms plus Embree's
        // monitor interval, not after the whole set-up.
        auto built = std::async(std::launch::async, build_tiles);
        while (built.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready)
            if (!stop.load() && !keep_going()) stop.store(true);
        try {
            built.get();  // rethrows the build's error
        } catch (const std::exception&) {
            if (!stop.load()) throw;  // a real failure; a cancelled tile's Error is ours
        }
        if (stop.load()) throw Error("Monte Carlo: cancelled");
    } else {
        build_tiles();
    }
    for (const auto& tiles : m_tiles)
        for (const auto& tile : tiles)
            if (tile) m_tile_side_um = std::max(m_tile_side_um, tile->sideUm());
}

McEngine::~McEngine() = default;

McEngine::Band McEngine::band(double wavelength_nm) const {
    Band band{buildPaintStack(m_recipe, wavelength_nm, m_settings.slices), {}};
    // Before the tiles take the flakes out of their slices: the bottom begins below the last flake.
    if (m_settings.bottom_operator) attachBottomOperator(band.stack, m_recipe, m_settings.slices);
    if (!m_settings.explicit_flakes) return band;
    // The tiles replace the continuum flakes of their layers.
    for (auto& slice : band.stack.slices)
        if (m_tiles[0][static_cast<std::size_t>(slice.layer)]) slice.flakes.clear();
    std::vector<std::vector<FlakeKind>> kinds;
    for (std::size_t l = 0; l < m_recipe.layers.size(); ++l)
        kinds.push_back(m_tiles[0][l] ? layerFlakeKinds(m_recipe.layers[l], wavelength_nm)
                                      : std::vector<FlakeKind>{});
    for (std::size_t b = 0; b < m_tiles.size(); ++b) {
        std::vector<LayerFlakes> layers;
        for (std::size_t l = 0; l < m_tiles[b].size(); ++l) {
            const TiltIndex& tilts = m_tilts[b][l];
            const FlakeGroups& groups = m_groups[b][l];
            // The chain connections assume independently placed flakes (last_flake.h).
            const bool mirrors =
                !kinds[l].empty() && std::none_of(kinds[l].begin(), kinds[l].end(),
                                                  [](const FlakeKind& k) { return k.interference; });
            const bool auto_on = mirrors ? m_settings.mirror_chain_connections
                                         : !kinds[l].empty() && m_settings.interference_chain_connections;
            const bool last_on = m_settings.last_flake_connections || auto_on;
            const bool cavity_on = m_settings.cavity_connections || auto_on;
            const bool law = (last_on || cavity_on) && !m_settings.reject_overlaps &&
                             l < m_last_flake.size() && !m_last_flake[l].kinds.empty();
            // The drawn cavity chains pay on mirror flakes only (CavityForms).
            const bool drawn = mirrors ? m_settings.cavity_forms.drawn
                                       : m_settings.cavity_forms.drawn_on_interference_flakes;
            layers.push_back({m_tiles[b][l].get(), kinds[l], tilts.order.empty() ? nullptr : &tilts,
                              groups.flakes.empty() ? nullptr : &groups, law ? &m_last_flake[l] : nullptr,
                              law && last_on, law && cavity_on, law && cavity_on && drawn, drawn});
        }
        band.explicit_flakes.push_back(std::move(layers));
    }
    return band;
}

JobResult McEngine::run(const Band& band, std::uint64_t band_key, std::uint64_t incidence_key,
                        const JobSpec& job, double budget_seconds,
                        const std::function<bool(double)>& progress) const {
    const auto job_start = Clock::now();
    JobRunner runner(band, job, m_settings, m_tile_side_um, band_key, incidence_key);
    const std::int64_t max_paths = std::max<std::int64_t>(1, m_settings.max_paths);
    // Small runs: chunks small enough that every batch gets paths (rounded
    // down: rounded up, 400 paths in 64 batches made 58 chunks of 7).
    const std::int64_t chunk =
        std::max<std::int64_t>(1, std::min<std::int64_t>(m_settings.chunk_paths, max_paths / m_batches));
    std::vector<Sums> batches(static_cast<std::size_t>(m_batches),
                              Sums(runner.entries(), runner.coneStats()));
    const bool over_batches = m_settings.explicit_flakes && m_batches > 1;
    std::int64_t next_chunk = 0;  // chunks started: chunk k goes to batch k % batches
    std::int64_t started = 0;     // paths started: the next chunk's first path index
    JobResult current;
    Sums seen(runner.entries(), runner.coneStats());  // every path so far, for the adaptive rates
    bool pilot_dropped = false;
    // Behind an error target the first rates' round is split at adapt()'s
    // paths: those before only set the weight of the rest (kept beside the
    // later paths in first_batches) and are dropped. The paths left of the
    // round, from the split until they run (0 otherwise).
    std::int64_t first_round_rest = 0;
    std::vector<Sums> first_batches;
    double first_weight = 0.0;
    const std::int64_t full_round = chunk * std::max(1, m_settings.chunks_per_round);
    // Behind an error target: the first round after the pilot, and the paths the stop rule waits for.
    const std::int64_t first_target_round = std::max<std::int64_t>(1, full_round / kFirstTargetRoundDivisor);
    const auto paths_start = Clock::now();  // the pace leaves out the estimators' set-up above
    const ErrorTarget error_target{m_settings.target_rel_error, m_settings.target_abs_error_per_sr};
    while (started < max_paths) {
        // One round of chunks in parallel; summed in chunk order (deterministic).
        const std::int64_t remaining = max_paths - started;
        std::int64_t round_chunk = chunk;
        std::int64_t round_chunks =
            std::min<std::int64_t>(std::max(1, m_settings.chunks_per_round), (remaining + chunk - 1) / chunk);
        const bool target = m_settings.target_rel_error > 0.0;
        if (budget_seconds > 0.0 || target) {
            // A time budget: the stop is checked between rounds only, and a
            // path's cost varies ~100x between paints and between the normal
            // and the oblique incidence (whose reverse walks run a deep white
            // coat's diffusion again). So a pilot round, then rounds sized to
            // the time left at the pace measured; runs with a path count alone
            // keep their fixed chunks. When the budget is the stop rule, the
            // pilot is one path per chunk, each round at most twice the paths
            // so far (a pace read off few long-tailed paths cannot commit the
            // whole budget) and half the time left (kRoundShare: the pace of a
            // shared machine drifts within a job, and only the rounds after an
            // overrun can absorb it). Behind an error target the budget is a
            // safety net, and the rounds are sized to the paths the errors so
            // far predict (targetRoundPaths).
            std::int64_t paths = round_chunks * (target ? std::min(chunk, kPilotChunkPaths) : 1);
            if (started > 0) {
                double cap = static_cast<double>(remaining);
                if (budget_seconds > 0.0) {
                    const double elapsed = std::chrono::duration<double>(Clock::now() - job_start).count();
                    const double seconds_per_path =
                        std::chrono::duration<double>(Clock::now() - paths_start).count() /
                        static_cast<double>(started);
                    const double affordable = std::max(0.0, budget_seconds - elapsed) / seconds_per_path;
                    // Not one more path within the budget (unless the pilot's paths were just dropped).
                    if (affordable < 1.0 && current.incidence.paths > 0) break;
                    cap = std::min(cap, affordable);
                    if (!target)
                        cap = std::min({cap, kRoundShare * affordable, 2.0 * static_cast<double>(started)});
                }
                const double budget_cap = cap;
                const double predicted = predictedPaths(current, error_target, job.orders);
                if (target)
                    cap = std::min(cap, static_cast<double>(targetRoundPaths(
                                            predicted, static_cast<std::int64_t>(current.weighted_paths),
                                            first_target_round, full_round)));
                if (target && pilot_dropped) {
                    // The first round at the adapted rates is short (the rates
                    // adapt again on their own paths), and while the job looks
                    // short (its prediction within a full round) a round at most
                    // kRoundGrowth times the adapted paths so far: a few kept paths
                    // predict heavy-tailed jobs poorly, and such a prediction had
                    // sent the three-layer demo's jobs 3-5 times past their need.
                    std::int64_t adapted = 0;
                    for (const auto& b : batches) adapted += b.paths;
                    if (adapted == 0)
                        cap = std::min(cap, static_cast<double>(first_target_round));
                    else if (predicted < static_cast<double>(full_round))
                        cap = std::min(cap, static_cast<double>(kRoundGrowth * adapted));
                }
                paths = std::max<std::int64_t>(1, static_cast<std::int64_t>(cap));
                if (first_round_rest > 0) {
                    // The rest of the first rates' round as planned.
                    paths =
                        std::max<std::int64_t>(1, static_cast<std::int64_t>(std::min(
                                                      static_cast<double>(first_round_rest), budget_cap)));
                    first_round_rest = 0;
                } else if (target && !pilot_dropped && runner.coneStats() > 0 &&
                           started < JobRunner::kPathsToAdapt && started + paths > JobRunner::kPathsToAdapt) {
                    first_round_rest = started + paths - JobRunner::kPathsToAdapt;
                    paths = JobRunner::kPathsToAdapt - started;
                }
            }
            round_chunks = std::min(round_chunks, std::max<std::int64_t>(1, paths));
            round_chunk = std::clamp<std::int64_t>((paths + round_chunks - 1) / round_chunks, 1, chunk);
            round_chunks = std::min<std::int64_t>(round_chunks, (remaining + round_chunk - 1) / round_chunk);
        }
        std::vector<Sums> sums(static_cast<std::size_t>(round_chunks));
        tbb::parallel_for(std::int64_t{0}, round_chunks, [&](std::int64_t c) {
            const std::int64_t index = next_chunk + c;
            const std::int64_t first = started + c * round_chunk;
            sums[static_cast<std::size_t>(c)] = runner.runChunk(
                static_cast<std::size_t>(index % m_batches), first, std::min(round_chunk, max_paths - first));
        });
        for (std::int64_t c = 0; c < round_chunks; ++c)
            batches[static_cast<std::size_t>((next_chunk + c) % m_batches)].add(
                sums[static_cast<std::size_t>(c)]);
        next_chunk += round_chunks;
        started = std::min(max_paths, started + round_chunks * round_chunk);
        const double elapsed = std::chrono::duration<double>(Clock::now() - job_start).count();
        bool dropped_now = false;
        if (runner.coneStats() > 0) {
            for (const auto& c : sums) seen.add(c);
            // The paths before the first adaptation ran at the first round's
            // rates, whose variance can be many times the adapted one (the
            // demo's flop: next-event connections on 1/8 of the paths at the
            // unboosted chance, then boosted up to 64 times). Behind an error
            // target, the first adapt()'s paths only forecast (the rate
            // model, mc_rates.h) the relative variance per path that the
            // adapted rates will give over theirs, and are dropped; the rest
            // of the round is kept beside the later paths with that ratio as
            // each path's weight (the inverse-variance weight, set before
            // those paths ran: unbiased). Without the split, every path
            // before the first adaptation is dropped. Either only while they
            // are a small part of the job.
            const bool may_drop =
                started * 8 <= max_paths && (budget_seconds <= 0.0 || elapsed * 8.0 <= budget_seconds);
            if (first_round_rest > 0) {  // the round before the split's rest
                const double ratio = runner.forecastVarianceRatio(seen);
                if (may_drop) {
                    first_weight = std::isfinite(ratio) ? std::clamp(ratio, 0.0, kMaxFirstWeight) : 0.0;
                    for (auto& b : batches) b = Sums(runner.entries(), runner.coneStats());
                    dropped_now = true;
                }
            } else if (runner.adapt(seen) && !pilot_dropped) {
                pilot_dropped = true;
                if (may_drop) {
                    if (first_weight > 0.0) first_batches = batches;
                    for (auto& b : batches) b = Sums(runner.entries(), runner.coneStats());
                    dropped_now = first_batches.empty();
                }
            }
        }
        current = finish(runner, batches, first_batches, first_weight, over_batches, elapsed);
        const bool out_of_time = budget_seconds > 0.0 && elapsed >= budget_seconds;
        if (progress) {
            double fraction = std::min(1.0, static_cast<double>(started) / static_cast<double>(max_paths));
            if (budget_seconds > 0.0) fraction = std::max(fraction, std::min(1.0, elapsed / budget_seconds));
            if (!progress(fraction)) throw Error("Monte Carlo: cancelled");
        }
        // The stop rule reads the spread of the batches: only once every batch has paths
        // (a spread over a few batches of one chunk each is itself too uncertain to stop on),
        // and not before one full round's paths (a budget's first rounds are small: an
        // error read off a few dozen paths could stop the job on a low draw), or
        // behind an error target the first round's kept paths.
        bool every_batch = true;
        for (std::size_t k = 0; over_batches && k < batches.size(); ++k)
            every_batch = every_batch &&
                          (batches[k].paths > 0 || (k < first_batches.size() && first_batches[k].paths > 0));
        const bool enough = target ? current.incidence.paths >= std::min(max_paths, first_target_round)
                                   : started >= std::min(max_paths, full_round);
        if (out_of_time ||
            (!dropped_now && every_batch && enough && converged(current, error_target, job.orders)))
            break;
    }
    current.incidence.account = runner.account();
    return current;
}

BandsInTurn::BandsInTurn(const McEngine& engine, std::vector<double> wavelengths_nm)
    : m_engine(engine), m_wavelengths_nm(std::move(wavelengths_nm)),
      m_group(static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()))) {}

const McEngine::Band& BandsInTurn::band(std::size_t b) {
    if (m_built.empty() || b < m_first || b >= m_first + m_built.size()) {
        if (b >= m_wavelengths_nm.size()) throw Error("Monte Carlo: no band " + std::to_string(b));
        m_first = b;
        const std::size_t count = std::min(m_group, m_wavelengths_nm.size() - b);
        m_built.assign(count, {});
        tbb::parallel_for(std::size_t{0}, count,
                          [&](std::size_t k) { m_built[k] = m_engine.band(m_wavelengths_nm[b + k]); });
    }
    return m_built[b - m_first];
}

}  // namespace paintlab::mc
