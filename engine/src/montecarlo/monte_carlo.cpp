#include "paintlab/engine/montecarlo/monte_carlo.h"

#include "flake_tile.h"
#include "mc_random.h"
#include "mc_stack.h"
#include "mc_walk.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fresnel.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <variant>

namespace paintlab::mc {

namespace {

using Clock = std::chrono::steady_clock;

// Sums over the paths of one chunk: per estimator sum x and sum x^2 (each
// path's total contribution is one independent sample).
struct ChunkSums {
    std::int64_t paths = 0;
    double albedo = 0.0;
    double albedo2 = 0.0;
    std::vector<double> f;
    std::vector<double> f2;
};

Estimate estimate(double sum, double sum2, std::int64_t n) {
    if (n <= 0) return {};
    const double dn = static_cast<double>(n);
    const double mean = sum / dn;
    const double var = n > 1 ? std::max(0.0, (sum2 / dn - mean * mean)) * dn / (dn - 1.0) : 0.0;
    return {mean, std::sqrt(var / dn)};
}

struct Job {
    std::size_t band = 0;
    std::size_t incidence = 0;
};

class IncidenceRunner {
public:
    IncidenceRunner(const PaintStack& stack, const IncidenceRequest& request, const McSettings& settings,
                    std::span<const LayerFlakes> explicit_flakes, double tile_side_um, std::uint64_t band,
                    std::uint64_t incidence)
        : m_stack(stack), m_settings(settings), m_explicit(explicit_flakes), m_tile_side_um(tile_side_um),
          m_band(band), m_incidence(incidence) {
        if (settings.histogram_cone_deg > 0.0) {
            const double alpha = settings.histogram_cone_deg * std::numbers::pi / 180.0;
            for (const auto& wo : request.wo)
                m_bins.push_back(
                    {{wo.x, wo.y, wo.z},
                     std::cos(alpha),
                     std::numbers::pi * std::sin(alpha) * std::sin(alpha) * std::max(wo.z, 1e-9)});
            m_exits = m_bins.size();
        } else {
            for (const auto& wo : request.wo) m_chains.push_back(exitChain(stack, wo));
            m_exits = m_chains.size();
        }
        const Direction& wi = request.wi;
        const double n1 = stack.slices.front().n;
        const double mu_i = std::clamp(wi.z, 0.0, 1.0);
        m_specular =
            std::abs(n1 - stack.ambient_n) < 1e-12 ? 0.0 : fresnelDielectric(mu_i, n1 / stack.ambient_n);
        m_entry_weight = mu_i > 0.0 ? 1.0 - m_specular : 0.0;
        // The beam travels along -wi; refracted into the top binder.
        const double ratio = stack.ambient_n / n1;
        m_v_in = {-wi.x * ratio, -wi.y * ratio, 0.0};
        m_v_in.z = -std::sqrt(std::max(0.0, 1.0 - m_v_in.x * m_v_in.x - m_v_in.y * m_v_in.y));
    }

    double specular() const { return m_specular; }
    std::size_t exitCount() const { return m_exits; }

    ChunkSums runChunk(std::int64_t first_path, std::int64_t paths) const {
        ChunkSums sums;
        sums.f.assign(m_exits, 0.0);
        sums.f2.assign(m_exits, 0.0);
        std::vector<double> f(m_exits);
        const PathContext context{m_stack, m_chains, m_bins, m_explicit,
                                  WalkSettings{m_settings.max_events, m_settings.roulette_weight}};
        for (std::int64_t p = first_path; p < first_path + paths; ++p) {
            std::fill(f.begin(), f.end(), 0.0);
            double escaped = 0.0;
            if (m_entry_weight > 0.0) {
                PathRng rng(m_settings.seed, m_band, m_incidence, static_cast<std::uint64_t>(p));
                const double x = rng.uniform() * m_tile_side_um;
                const double y = rng.uniform() * m_tile_side_um;
                escaped = tracePath(context, m_v_in, m_entry_weight, x, y, rng, f);
            }
            sums.albedo += escaped;
            sums.albedo2 += escaped * escaped;
            for (std::size_t k = 0; k < f.size(); ++k) {
                sums.f[k] += f[k];
                sums.f2[k] += f[k] * f[k];
            }
        }
        sums.paths = paths;
        return sums;
    }

private:
    const PaintStack& m_stack;
    const McSettings& m_settings;
    std::span<const LayerFlakes> m_explicit;
    double m_tile_side_um = 1.0;
    std::uint64_t m_band;
    std::uint64_t m_incidence;
    std::vector<ExitChain> m_chains;
    std::vector<HistogramBin> m_bins;
    std::size_t m_exits = 0;
    double m_specular = 0.0;
    double m_entry_weight = 0.0;
    Vec3 m_v_in;
};

IncidenceResult finish(const IncidenceRunner& runner, const ChunkSums& total, double seconds) {
    IncidenceResult r;
    r.specular = runner.specular();
    r.albedo = estimate(total.albedo, total.albedo2, total.paths);
    r.albedo.mean += r.specular;  // exact, no variance
    for (std::size_t k = 0; k < total.f.size(); ++k)
        r.brdf_per_sr.push_back(estimate(total.f[k], total.f2[k], total.paths));
    r.paths = total.paths;
    r.seconds = seconds;
    return r;
}

bool converged(const IncidenceResult& r, double target) {
    if (!(target > 0.0)) return false;
    if (r.albedo.relError() > target) return false;
    return std::all_of(r.brdf_per_sr.begin(), r.brdf_per_sr.end(),
                       [target](const Estimate& e) { return e.relError() <= target; });
}

}  // namespace

McResult runMonteCarlo(const Recipe& recipe, std::span<const double> wavelengths_nm,
                       std::span<const IncidenceRequest> requests, const McSettings& settings,
                       const ProgressCallback& progress) {
    const auto start = Clock::now();
    std::unique_ptr<tbb::global_control> threads;
    if (settings.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        static_cast<std::size_t>(settings.threads));
    McResult result;
    result.wavelengths_nm.assign(wavelengths_nm.begin(), wavelengths_nm.end());
    result.bands.resize(wavelengths_nm.size());
    const std::size_t jobs = wavelengths_nm.size() * requests.size();
    const double job_budget =
        settings.max_seconds > 0.0 ? settings.max_seconds / static_cast<double>(jobs) : 0.0;
    const std::int64_t chunk = std::max(1, settings.chunk_paths);
    const std::int64_t max_paths = std::max<std::int64_t>(1, settings.max_paths);
    if (settings.explicit_flakes && !(settings.histogram_cone_deg > 0.0))
        throw InputError("", "histogram_cone_deg",
                         "explicit flakes need the histogram estimator (a cone > 0)");
    // Explicit flakes: one tile per layer with flakes, the same for every band.
    std::vector<std::unique_ptr<FlakeTile>> tiles(recipe.layers.size());
    double tile_side_um = 1.0;
    if (settings.explicit_flakes) {
        double depth = 0.0;
        for (std::size_t l = 0; l < recipe.layers.size(); ++l) {
            const auto geometries = layerFlakeGeometries(recipe.layers[l]);
            if (!geometries.empty()) {
                tiles[l] =
                    std::make_unique<FlakeTile>(geometries, depth, depth + recipe.layers[l].thickness_um,
                                                settings.seed ^ (0x9e3779b97f4a7c15ULL * (l + 1)),
                                                settings.tile_flakes, settings.max_tile_flakes);
                tile_side_um = std::max(tile_side_um, tiles[l]->sideUm());
            }
            depth += recipe.layers[l].thickness_um;
        }
    }
    std::size_t jobs_done = 0;
    for (std::size_t b = 0; b < wavelengths_nm.size(); ++b) {
        PaintStack stack = buildPaintStack(recipe, wavelengths_nm[b], settings.slices);
        std::vector<LayerFlakes> explicit_flakes;
        if (settings.explicit_flakes) {
            // The tiles replace the continuum flakes of their layers.
            for (auto& slice : stack.slices)
                if (tiles[static_cast<std::size_t>(slice.layer)]) slice.flakes.clear();
            for (std::size_t l = 0; l < recipe.layers.size(); ++l)
                explicit_flakes.push_back(
                    {tiles[l].get(), tiles[l] ? layerFlakeKinds(recipe.layers[l], wavelengths_nm[b])
                                              : std::vector<FlakeKind>{}});
        }
        for (std::size_t i = 0; i < requests.size(); ++i) {
            const auto job_start = Clock::now();
            const IncidenceRunner runner(stack, requests[i], settings, explicit_flakes, tile_side_um, b, i);
            ChunkSums total;
            total.f.assign(runner.exitCount(), 0.0);
            total.f2.assign(runner.exitCount(), 0.0);
            std::int64_t next_path = 0;
            IncidenceResult current;
            while (next_path < max_paths) {
                // One round of chunks in parallel; summed in chunk order (deterministic).
                const std::int64_t remaining = max_paths - next_path;
                const std::int64_t round_chunks = std::min<std::int64_t>(
                    std::max(1, settings.chunks_per_round), (remaining + chunk - 1) / chunk);
                std::vector<ChunkSums> sums(static_cast<std::size_t>(round_chunks));
                tbb::parallel_for(std::int64_t{0}, round_chunks, [&](std::int64_t c) {
                    const std::int64_t first = next_path + c * chunk;
                    sums[static_cast<std::size_t>(c)] =
                        runner.runChunk(first, std::min(chunk, max_paths - first));
                });
                for (const auto& s : sums) {
                    total.paths += s.paths;
                    total.albedo += s.albedo;
                    total.albedo2 += s.albedo2;
                    for (std::size_t k = 0; k < s.f.size(); ++k) {
                        total.f[k] += s.f[k];
                        total.f2[k] += s.f2[k];
                    }
                }
                next_path += round_chunks * chunk;
                const double elapsed = std::chrono::duration<double>(Clock::now() - job_start).count();
                current = finish(runner, total, elapsed);
                const bool out_of_time = job_budget > 0.0 && elapsed >= job_budget;
                if (progress) {
                    double fraction =
                        static_cast<double>(std::min(next_path, max_paths)) / static_cast<double>(max_paths);
                    if (job_budget > 0.0) fraction = std::max(fraction, std::min(1.0, elapsed / job_budget));
                    if (!progress((static_cast<double>(jobs_done) + fraction) / static_cast<double>(jobs)))
                        throw Error("Monte Carlo: cancelled");
                }
                if (out_of_time || converged(current, settings.target_rel_error)) break;
            }
            result.total_paths += current.paths;
            result.bands[b].push_back(std::move(current));
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
