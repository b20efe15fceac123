#include "paintlab/engine/montecarlo/monte_carlo.h"

#include "flake_tile.h"
#include "mc_engine.h"
#include "mc_random.h"

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

// Statistics of the paths of one chunk or batch per sample-vector entry
// (mc_engine.h): mean and sum of squared deviations M2, merged by Chan et
// al.'s pairwise update (each path's total contribution is one independent
// sample). Unlike sum x^2 / n - mean^2 this keeps a zero-variance estimate
// (every path the same) exactly zero.
struct Sums {
    std::int64_t paths = 0;
    std::vector<double> mean;
    std::vector<double> m2;

    explicit Sums(std::size_t entries = 0) : mean(entries, 0.0), m2(entries, 0.0) {}
    void add(const Sums& other) {
        if (other.paths == 0) return;
        const auto na = static_cast<double>(paths);
        const auto nb = static_cast<double>(other.paths);
        const double n = na + nb;
        for (std::size_t k = 0; k < mean.size(); ++k) {
            const double delta = other.mean[k] - mean[k];
            mean[k] += delta * nb / n;
            m2[k] += other.m2[k] + delta * delta * na * nb / n;
        }
        paths += other.paths;
    }
};

constexpr std::size_t kEscaped = 0;
constexpr std::size_t kTransmitted = 1;
constexpr std::size_t kFirstExit = 2;
constexpr std::uint64_t kConnectionStream = 0x636f6e6e656374ULL;  // "connect"

class JobRunner {
public:
    JobRunner(const McEngine::Band& band, const JobSpec& job, const McSettings& settings, double tile_side_um,
              std::uint64_t band_key, std::uint64_t incidence_key)
        : m_band(band), m_settings(settings), m_tile_side_um(tile_side_um), m_band_key(band_key),
          m_incidence_key(incidence_key) {
        const PaintStack& stack = band.stack;
        if (settings.histogram_cone_deg > 0.0) {
            const double alpha = settings.histogram_cone_deg * std::numbers::pi / 180.0;
            for (const auto& wo : job.wo)
                m_bins.push_back({{wo.x, wo.y, wo.z},
                                  std::cos(alpha),
                                  std::numbers::pi * std::sin(alpha) * std::sin(alpha) * std::max(wo.z, 1e-9),
                                  2.0 * std::numbers::pi * (1.0 - std::cos(alpha))});
        } else {
            for (const auto& wo : job.wo) m_chains.push_back(exitChain(stack, wo));
        }
        m_exits = job.wo.size();
        const Direction& wi = job.wi;
        const double n1 = stack.slices.front().n;
        const double mu_i = std::clamp(wi.z, 0.0, 1.0);
        m_specular =
            std::abs(n1 - stack.ambient_n) < 1e-12 ? 0.0 : fresnelDielectric(mu_i, n1 / stack.ambient_n);
        m_entry_weight = mu_i > 0.0 ? 1.0 - m_specular : 0.0;
        // The beam travels along -wi; refracted into the top binder.
        const double ratio = stack.ambient_n / n1;
        m_v_in = {-wi.x * ratio, -wi.y * ratio, 0.0};
        m_v_in.z = -std::sqrt(std::max(0.0, 1.0 - m_v_in.x * m_v_in.x - m_v_in.y * m_v_in.y));
        if (!job.cell_upper_mu.empty() && job.orders > 0 && m_entry_weight > 0.0) {
            m_cells.upper_mu = job.cell_upper_mu;
            m_cells.orders = job.orders;
            m_cells.top_eta = n1 / stack.ambient_n;
            const double s = std::hypot(wi.x, wi.y);
            m_cells.cos_in = s > 0.0 ? -wi.x / s : 1.0;
            m_cells.sin_in = s > 0.0 ? -wi.y / s : 0.0;
            m_cells.offset = m_exits;  // in f_out, which starts at kFirstExit
            for (std::size_t c = 0; c < job.cell_upper_mu.size(); ++c) {
                const double lo = job.cell_lower_mu[c];
                const double hi = job.cell_upper_mu[c];
                m_cells.scale.push_back(1.0 / (std::numbers::pi * (hi * hi - lo * lo) * m_entry_weight));
            }
            m_projected = m_cells.scale.size() * static_cast<std::size_t>(job.orders);
        }
        m_connections = settings.connections && settings.explicit_flakes && !m_bins.empty() &&
                        !band.explicit_flakes.empty() && m_entry_weight > 0.0;
        m_histogram_classes = settings.histogram_classes;
        if (m_connections) m_histogram_classes &= ~(kClassBeamFlake | kClassSmooth);
        m_connection_fraction = std::clamp(settings.connection_fraction, 1e-3, 1.0);
        buildViews(settings);
    }

    // Explicit flakes: every tile is traced at tile_views azimuths of the
    // incidence plane (McSettings): view m of batch b turns the beam, the
    // exit cones and the projection's azimuth origin by psi = 2 pi (m + o_b) / M
    // about the normal (o_b a fixed random offset per batch), so the tile is
    // seen as if turned by -psi. Otherwise one view, not turned.
    void buildViews(const McSettings& settings) {
        const bool turn = settings.explicit_flakes && !m_band.explicit_flakes.empty();
        m_view_count = turn ? static_cast<std::size_t>(std::max(1, settings.tile_views)) : 1;
        const std::size_t batch_count = turn ? m_band.explicit_flakes.size() : 1;
        m_views.assign(batch_count, std::vector<View>(m_view_count));
        tbb::parallel_for(std::size_t{0}, batch_count * m_view_count, [&](std::size_t index) {
            const std::size_t b = index / m_view_count;
            const std::size_t m = index % m_view_count;
            std::uint64_t key = settings.seed ^ (0x746f726e ^ b);  // "torn"
            const double offset =
                m_view_count > 1 ? static_cast<double>(splitMix64(key) >> 11U) * 0x1.0p-53 : 0.0;
            const double psi = 2.0 * std::numbers::pi * (static_cast<double>(m) + offset) /
                               static_cast<double>(m_view_count);
            const double c = std::cos(psi);
            const double sn = std::sin(psi);
            const auto turned = [c, sn](const Vec3& a) {
                return Vec3{c * a.x - sn * a.y, sn * a.x + c * a.y, a.z};
            };
            View& view = m_views[b][m];
            view.v_in = turned(m_v_in);
            view.bins = m_bins;
            for (auto& bin : view.bins) bin.wo = turned(bin.wo);
            view.cells = m_cells;
            const Vec3 in = turned({m_cells.cos_in, m_cells.sin_in, 0.0});
            view.cells.cos_in = in.x;
            view.cells.sin_in = in.y;
            if (m_connections)
                view.glints = glintSets(m_band.stack, m_band.explicit_flakes[b], view.v_in, view.bins);
        });
    }

    double specular() const { return m_specular; }
    std::size_t exitCount() const { return m_exits; }
    std::size_t entries() const { return kFirstExit + m_exits + m_projected; }

    Sums runChunk(std::size_t batch, std::int64_t first_path, std::int64_t paths) const {
        // Sums of deviations from the first path's sample (exact for constant samples), then mean and M2.
        std::vector<double> shift(entries(), 0.0);
        std::vector<double> s1(entries(), 0.0);
        std::vector<double> s2(entries(), 0.0);
        std::vector<double> sample(entries());
        const std::span<double> f(sample.data() + kFirstExit, sample.size() - kFirstExit);
        const std::span<const LayerFlakes> explicit_flakes =
            m_band.explicit_flakes.empty() ? std::span<const LayerFlakes>{} : m_band.explicit_flakes[batch];
        const std::vector<View>& views = m_views[std::min(batch, m_views.size() - 1)];
        for (std::int64_t p = first_path; p < first_path + paths; ++p) {
            std::fill(sample.begin(), sample.end(), 0.0);
            if (m_entry_weight > 0.0) {
                const View& view = views[static_cast<std::size_t>(p) % m_view_count];
                const PathContext context{m_band.stack,
                                          m_chains,
                                          view.bins,
                                          explicit_flakes,
                                          WalkSettings{m_settings.max_events, m_settings.roulette_weight,
                                                       m_histogram_classes, m_connections,
                                                       1.0 / m_connection_fraction},
                                          m_projected > 0 ? &view.cells : nullptr,
                                          view.glints};
                PathRng rng(m_settings.seed, m_band_key, m_incidence_key, static_cast<std::uint64_t>(p));
                // The connections' own stream: the walk draws the same numbers with or without them.
                PathRng connection_rng(m_settings.seed ^ kConnectionStream, m_band_key, m_incidence_key,
                                       static_cast<std::uint64_t>(p));
                const double x = rng.uniform() * m_tile_side_um;
                const double y = rng.uniform() * m_tile_side_um;
                // Connections on a random share of the paths (all when the fraction is 1).
                const bool connect = m_connections && (m_connection_fraction >= 1.0 ||
                                                       connection_rng.uniform() < m_connection_fraction);
                const PathOutcome out = tracePath(context, view.v_in, m_entry_weight, x, y, rng, f,
                                                  connect ? &connection_rng : nullptr);
                sample[kEscaped] = out.escaped;
                sample[kTransmitted] = out.transmitted;
            }
            if (p == first_path) shift = sample;
            for (std::size_t k = 0; k < sample.size(); ++k) {
                const double d = sample[k] - shift[k];
                s1[k] += d;
                s2[k] += d * d;
            }
        }
        Sums sums(entries());
        sums.paths = paths;
        if (paths <= 0) return sums;
        const auto n = static_cast<double>(paths);
        for (std::size_t k = 0; k < sample.size(); ++k) {
            sums.mean[k] = shift[k] + s1[k] / n;
            sums.m2[k] = std::max(0.0, s2[k] - s1[k] * s1[k] / n);
        }
        return sums;
    }

private:
    const McEngine::Band& m_band;
    const McSettings& m_settings;
    double m_tile_side_um = 1.0;
    std::uint64_t m_band_key;
    std::uint64_t m_incidence_key;
    std::vector<ExitChain> m_chains;
    std::vector<HistogramBin> m_bins;
    FourierCells m_cells;
    std::size_t m_exits = 0;
    std::size_t m_projected = 0;
    double m_specular = 0.0;
    double m_entry_weight = 0.0;
    Vec3 m_v_in;
    bool m_connections = false;
    unsigned m_histogram_classes = kAllClasses;
    struct View {
        Vec3 v_in;
        std::vector<HistogramBin> bins;
        FourierCells cells;
        std::vector<GlintSet> glints;  // per bin (connections)
    };
    std::vector<std::vector<View>> m_views;  // [batch][view]
    std::size_t m_view_count = 1;
    double m_connection_fraction = 1.0;
};

// The estimates of a job from its batches' sums: over the batches' means
// when the batches trace different tiles, else over paths.
JobResult finish(const JobRunner& runner, const std::vector<Sums>& batches, bool over_batches,
                 double seconds) {
    Sums total(runner.entries());
    for (const auto& b : batches) total.add(b);
    std::vector<std::int64_t> paths;
    std::vector<std::vector<double>> batch_means;
    for (const auto& b : batches)
        if (b.paths > 0) {
            paths.push_back(b.paths);
            batch_means.push_back(b.mean);
        }
    const bool use_batches = over_batches && paths.size() >= 2;
    std::vector<double> column(paths.size());
    auto entry = [&](std::size_t k) {
        if (!use_batches) return pooledEstimate(total.mean[k], total.m2[k], total.paths);
        for (std::size_t b = 0; b < paths.size(); ++b) column[b] = batch_means[b][k];
        return batchMeansEstimate(column, paths);
    };
    JobResult r;
    IncidenceResult& inc = r.incidence;
    inc.specular = runner.specular();
    inc.albedo = entry(kEscaped);
    inc.albedo.mean += inc.specular;  // exact, no variance
    inc.transmittance = entry(kTransmitted);
    for (std::size_t k = 0; k < runner.exitCount(); ++k) inc.brdf_per_sr.push_back(entry(kFirstExit + k));
    for (std::size_t k = kFirstExit + runner.exitCount(); k < runner.entries(); ++k)
        r.projection.push_back(entry(k));
    inc.paths = total.paths;
    inc.seconds = seconds;
    r.batch_paths = std::move(paths);
    r.batch_means = std::move(batch_means);
    return r;
}

// The stop rule's error target: the albedo, every f and the projection's order-0 entries.
bool converged(const JobResult& r, double target, int orders) {
    if (!(target > 0.0)) return false;
    const IncidenceResult& inc = r.incidence;
    if (inc.albedo.relError() > target) return false;
    for (const auto& e : inc.brdf_per_sr)
        if (e.relError() > target) return false;
    for (std::size_t k = 0; k < r.projection.size(); k += static_cast<std::size_t>(std::max(1, orders)))
        if (r.projection[k].relError() > target) return false;
    return true;
}

}  // namespace

Estimate pooledEstimate(double mean, double m2, std::int64_t n) {
    if (n <= 0) return {};
    const auto dn = static_cast<double>(n);
    const double var = n > 1 ? m2 / (dn - 1.0) : 0.0;
    return {mean, std::sqrt(var / dn)};
}

Estimate batchMeansEstimate(std::span<const double> batch_means, std::span<const std::int64_t> batch_paths) {
    double total = 0.0;
    std::int64_t n = 0;
    for (std::size_t b = 0; b < batch_means.size(); ++b) {
        total += batch_means[b] * static_cast<double>(batch_paths[b]);
        n += batch_paths[b];
    }
    if (n <= 0) return {};
    const auto dn = static_cast<double>(n);
    const double mean = total / dn;
    const auto k = static_cast<double>(batch_means.size());
    if (k < 2.0) return {mean, 0.0};
    double var = 0.0;
    for (std::size_t b = 0; b < batch_means.size(); ++b) {
        const double d = (batch_means[b] - mean) * static_cast<double>(batch_paths[b]) / dn;
        var += d * d;
    }
    return {mean, std::sqrt(var * k / (k - 1.0))};
}

McEngine::McEngine(const Recipe& recipe, const McSettings& settings)
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
    tbb::parallel_for(std::size_t{0}, m_tiles.size() * layers, [&](std::size_t index) {
        const std::size_t k = index / layers;
        const std::size_t l = index % layers;
        if (geometries[l].empty()) return;
        // Batch 0 keeps the single tile's seed of earlier versions.
        const std::uint64_t tile_seed =
            settings.seed ^ (0x9e3779b97f4a7c15ULL * (l + 1)) ^ (0xd1b54a32d192ed03ULL * k);
        m_tiles[k][l] = std::make_unique<FlakeTile>(
            geometries[l], tops[l], tops[l] + recipe.layers[l].thickness_um, tile_seed, settings.tile_flakes,
            settings.max_tile_flakes, settings.reject_overlaps);
    });
    for (const auto& tiles : m_tiles)
        for (const auto& tile : tiles)
            if (tile) m_tile_side_um = std::max(m_tile_side_um, tile->sideUm());
}

McEngine::~McEngine() = default;

McEngine::Band McEngine::band(double wavelength_nm) const {
    Band band{buildPaintStack(m_recipe, wavelength_nm, m_settings.slices), {}};
    if (!m_settings.explicit_flakes) return band;
    // The tiles replace the continuum flakes of their layers.
    for (auto& slice : band.stack.slices)
        if (m_tiles[0][static_cast<std::size_t>(slice.layer)]) slice.flakes.clear();
    std::vector<std::vector<FlakeKind>> kinds;
    for (std::size_t l = 0; l < m_recipe.layers.size(); ++l)
        kinds.push_back(m_tiles[0][l] ? layerFlakeKinds(m_recipe.layers[l], wavelength_nm)
                                      : std::vector<FlakeKind>{});
    for (const auto& tiles : m_tiles) {
        std::vector<LayerFlakes> layers;
        for (std::size_t l = 0; l < tiles.size(); ++l) layers.push_back({tiles[l].get(), kinds[l]});
        band.explicit_flakes.push_back(std::move(layers));
    }
    return band;
}

JobResult McEngine::run(const Band& band, std::uint64_t band_key, std::uint64_t incidence_key,
                        const JobSpec& job, double budget_seconds,
                        const std::function<bool(double)>& progress) const {
    const auto job_start = Clock::now();
    const JobRunner runner(band, job, m_settings, m_tile_side_um, band_key, incidence_key);
    const std::int64_t max_paths = std::max<std::int64_t>(1, m_settings.max_paths);
    // Small runs: chunks small enough that every batch gets paths.
    const std::int64_t chunk = std::max<std::int64_t>(
        1, std::min<std::int64_t>(m_settings.chunk_paths, (max_paths + m_batches - 1) / m_batches));
    std::vector<Sums> batches(static_cast<std::size_t>(m_batches), Sums(runner.entries()));
    const bool over_batches = m_settings.explicit_flakes && m_batches > 1;
    std::int64_t next_chunk = 0;
    JobResult current;
    while (next_chunk * chunk < max_paths) {
        // One round of chunks in parallel; summed in chunk order (deterministic).
        const std::int64_t remaining = max_paths - next_chunk * chunk;
        const std::int64_t round_chunks =
            std::min<std::int64_t>(std::max(1, m_settings.chunks_per_round), (remaining + chunk - 1) / chunk);
        std::vector<Sums> sums(static_cast<std::size_t>(round_chunks));
        tbb::parallel_for(std::int64_t{0}, round_chunks, [&](std::int64_t c) {
            const std::int64_t index = next_chunk + c;
            const std::int64_t first = index * chunk;
            sums[static_cast<std::size_t>(c)] = runner.runChunk(static_cast<std::size_t>(index % m_batches),
                                                                first, std::min(chunk, max_paths - first));
        });
        for (std::int64_t c = 0; c < round_chunks; ++c)
            batches[static_cast<std::size_t>((next_chunk + c) % m_batches)].add(
                sums[static_cast<std::size_t>(c)]);
        next_chunk += round_chunks;
        const double elapsed = std::chrono::duration<double>(Clock::now() - job_start).count();
        current = finish(runner, batches, over_batches, elapsed);
        const bool out_of_time = budget_seconds > 0.0 && elapsed >= budget_seconds;
        if (progress) {
            double fraction =
                std::min(1.0, static_cast<double>(next_chunk * chunk) / static_cast<double>(max_paths));
            if (budget_seconds > 0.0) fraction = std::max(fraction, std::min(1.0, elapsed / budget_seconds));
            if (!progress(fraction)) throw Error("Monte Carlo: cancelled");
        }
        if (out_of_time || converged(current, m_settings.target_rel_error, job.orders)) break;
    }
    return current;
}

McResult runMonteCarlo(const Recipe& recipe, std::span<const double> wavelengths_nm,
                       std::span<const IncidenceRequest> requests, const McSettings& settings,
                       const ProgressCallback& progress) {
    const auto start = Clock::now();
    std::unique_ptr<tbb::global_control> threads;
    if (settings.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        static_cast<std::size_t>(settings.threads));
    const McEngine engine(recipe, settings);
    McResult result;
    result.wavelengths_nm.assign(wavelengths_nm.begin(), wavelengths_nm.end());
    result.bands.resize(wavelengths_nm.size());
    const std::size_t jobs = wavelengths_nm.size() * requests.size();
    const double job_budget =
        settings.max_seconds > 0.0 ? settings.max_seconds / static_cast<double>(jobs) : 0.0;
    std::size_t jobs_done = 0;
    for (std::size_t b = 0; b < wavelengths_nm.size(); ++b) {
        const McEngine::Band band = engine.band(wavelengths_nm[b]);
        for (std::size_t i = 0; i < requests.size(); ++i) {
            const JobSpec job{requests[i].wi, requests[i].wo, {}, {}, 0};
            std::function<bool(double)> job_progress;
            if (progress)
                job_progress = [&](double fraction) {
                    return progress((static_cast<double>(jobs_done) + fraction) / static_cast<double>(jobs));
                };
            JobResult r = engine.run(band, b, i, job, job_budget, job_progress);
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
