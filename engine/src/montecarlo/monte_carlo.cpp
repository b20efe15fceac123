#include "paintlab/engine/montecarlo/monte_carlo.h"

#include "chain_promise.h"
#include "first_flake.h"
#include "flake_tile.h"
#include "mc_engine.h"
#include "mc_random.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fresnel.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <memory>
#include <numbers>
#include <variant>

namespace paintlab::mc {

namespace {

using Clock = std::chrono::steady_clock;

// Per exit cone, what the adaptive connection fractions (JobRunner::adapt)
// need besides the per-path entries: the raw next-event score of the paths
// that ran it (unweighted by the fraction), the raw glint samples, and costs.
struct ConeStats {
    // Over every path (Sums::paths of them), with or without connections:
    double nee_rate = 0.0;  // sum of their rates x (the cost's unit)
    double nee_s1 = 0.0;    // sum of the weighted scores Y (E[Y] = E[X])
    double nee_s2 = 0.0;    // sum of x Y^2 (E[x Y^2] = E[X^2] at x <= 1)
    double glint_samples = 0.0;
    double glint_s1 = 0.0;
    double glint_s2 = 0.0;
    double glint_rays = 0.0;
    double reverse_samples = 0.0;
    double reverse_s1 = 0.0;
    double reverse_s2 = 0.0;
    double reverse_cost = 0.0;   // microseconds on the reference machine (the cost model below)
    double delta_samples = 0.0;  // delta-chain walks (shared by every cone: same count in each)
    double delta_s1 = 0.0;
    double delta_s2 = 0.0;
    double delta_cost = 0.0;
    void add(const ConeStats& o) {
        delta_samples += o.delta_samples;
        delta_s1 += o.delta_s1;
        delta_s2 += o.delta_s2;
        delta_cost += o.delta_cost;
        reverse_samples += o.reverse_samples;
        reverse_s1 += o.reverse_s1;
        reverse_s2 += o.reverse_s2;
        reverse_cost += o.reverse_cost;
        nee_rate += o.nee_rate;
        nee_s1 += o.nee_s1;
        nee_s2 += o.nee_s2;
        glint_samples += o.glint_samples;
        glint_s1 += o.glint_s1;
        glint_s2 += o.glint_s2;
        glint_rays += o.glint_rays;
    }
};

void addElementwise(std::vector<double>& to, const std::vector<double>& from) {
    if (to.size() < from.size()) to.resize(from.size(), 0.0);
    for (std::size_t i = 0; i < from.size(); ++i) to[i] += from[i];
}

// Statistics of the paths of one chunk or batch per sample-vector entry
// (mc_engine.h): mean and sum of squared deviations M2, merged by Chan et
// al.'s pairwise update (each path's total contribution is one independent
// sample). Unlike sum x^2 / n - mean^2 this keeps a zero-variance estimate
// (every path the same) exactly zero.
struct Sums {
    std::int64_t paths = 0;
    std::vector<double> mean;
    std::vector<double> m2;
    std::vector<ConeStats> cones;  // adaptive fractions only
    double walk_cost = 0.0;        // free paths + tile intersections of the walks
    double nee_cost = 0.0;         // the next-event and flake-image connections' cost (the model's µs)
    double nee_attempts = 0.0;
    // First-flake walks (first_flake.h), per proposal key: how many were drawn
    // from it, and per key and cone the sum of (f P_G / A_G)^2, f the walk's
    // estimate (JobRunner::learnFirstFlakeProposal).
    std::vector<double> first_count;
    std::vector<double> first_s2;  // [key * cones + k]

    explicit Sums(std::size_t entries = 0, std::size_t cone_count = 0)
        : mean(entries, 0.0), m2(entries, 0.0), cones(cone_count) {}
    void add(const Sums& other) {
        for (std::size_t k = 0; k < cones.size() && k < other.cones.size(); ++k) cones[k].add(other.cones[k]);
        addElementwise(first_count, other.first_count);
        addElementwise(first_s2, other.first_s2);
        walk_cost += other.walk_cost;
        nee_cost += other.nee_cost;
        nee_attempts += other.nee_attempts;
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
// Paths per chunk of a budgeted job's first round, which measures the pace.
constexpr std::int64_t kPilotChunkPaths = 16;
constexpr std::uint64_t kConnectionStream = 0x636f6e6e656374ULL;  // "connect"
constexpr std::uint64_t kGlintStream = 0x676c696e74ULL;           // "glint"
constexpr std::uint64_t kReverseStream = 0x72657665727365ULL;     // "reverse"
constexpr std::uint64_t kDeltaStream = 0x64656c7461ULL;           // "delta"
// Reverse walks per path and cone: at most (so that sample j of a chunk has a unique stream).
constexpr double kMaxReverseRate = 4.0;
constexpr double kMinReverseRate = 1.0 / 256.0;
// Delta-chain walks per path (the same bound).
constexpr double kMaxDeltaRate = 4.0;
constexpr double kMinDeltaRate = 1.0 / 64.0;
// First-flake walks: the weight, in draws, of the mean over all keys in a key's learned weight.
constexpr double kFirstFlakePrior = 64.0;

// Whether a delta chain can begin other than at an explicit flake: an index
// step inside the paint (an internal reflection of the beam) or a mirror-like
// substrate. Otherwise the first-flake walks hold every delta chain and the
// uniform delta-chain walks are not run.
bool otherDeltaStarts(const PaintStack& stack) {
    for (std::size_t j = 0; j + 1 < stack.slices.size(); ++j)
        if (std::abs(stack.slices[j].n - stack.slices[j + 1].n) >= 1e-12) return true;
    return stack.substrate == SubstrateKind::Metal || stack.substrate == SubstrateKind::Transparent;
}

// Bounds of the adaptive fractions: next-event rate (the share of paths up to
// 1, beyond it the boost of every collision's chance), glint samples per path.
constexpr double kMinFraction = 1.0 / 64.0;
constexpr double kMaxNeeRate = 64.0;
constexpr double kMaxGlintRate = 4.0;
constexpr double kMinGlintRate = 1.0 / 64.0;
// Their cost model (thread-microseconds on the reference machine): per path
// (walk or delta-chain walk), per free path or tile intersection of a walk, per
// next-event attempt or intersection, per unit of a flake-image connection's
// work (reflectedBeams: a shadow ray or 64 candidate flakes tested), per glint
// sample and per intersection of its traces. Fitted 2026-12-03 (2 vCPU EPYC,
// docs/PERFORMANCE.md) to the four parts' measured times in the 16 jobs (8
// bands, two seeds) of two stop-rule runs of the pearlescent demo (residuals
// within 7 %). Those of 2026-12-02 made a
// next-event step 3x too dear against a walk step and a flake image's unit
// of work 8x too cheap, which set the rates far from the cheapest.
constexpr double kCostPerPath = 0.32;
constexpr double kCostPerWalkStep = 0.135;
constexpr double kCostPerNeeStep = 0.134;
constexpr double kCostPerImageRay = 3.6;
constexpr double kCostPerGlint = 1.2;
constexpr double kCostPerGlintRay = 0.13;

// One rate of a cone's variance model (JobRunner::adapt): its variance
// coefficient (the variance it adds per path is variance / x at rate x), the
// cost per unit of rate, and its bounds.
struct RateTerm {
    double variance = 0.0;
    double cost = 1.0;
    double lo = 0.0;
    double hi = 1.0;
};

// The cheapest rates (least sum x_t cost_t) with sum variance_t / x_t <= budget:
// x_t proportional to sqrt(variance_t / cost_t) (Lagrange), those beyond a bound
// held at it and the rest solved again for what is left; every rate at its top
// when the budget cannot be met; at its bottom a term without variance.
std::array<double, 3> cheapestRates(const std::array<RateTerm, 3>& terms, double budget) {
    std::array<double, 3> x{};
    std::array<bool, 3> held{};
    for (std::size_t t = 0; t < 3; ++t) {
        held[t] = !(terms[t].variance > 0.0);
        x[t] = held[t] ? terms[t].lo : terms[t].hi;
    }
    if (!(budget > 0.0)) return x;
    for (int pass = 0; pass < 4; ++pass) {
        double left = budget;
        double sum = 0.0;
        for (std::size_t t = 0; t < 3; ++t) {
            if (held[t])
                left -= terms[t].variance / x[t];
            else
                sum += std::sqrt(terms[t].variance * terms[t].cost);
        }
        if (!(sum > 0.0)) break;
        if (!(left > 0.0)) {
            for (std::size_t t = 0; t < 3; ++t)
                if (!held[t]) x[t] = terms[t].hi;
            break;
        }
        bool changed = false;
        for (std::size_t t = 0; t < 3; ++t) {
            if (held[t]) continue;
            x[t] = std::sqrt(terms[t].variance / terms[t].cost) * sum / left;
            if (x[t] > terms[t].hi || x[t] < terms[t].lo) {
                x[t] = std::clamp(x[t], terms[t].lo, terms[t].hi);
                held[t] = true;
                changed = true;
            }
        }
        if (!changed) break;
    }
    return x;
}

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
        const double nee_rate = std::clamp(settings.connection_fraction, 1e-3, kMaxNeeRate);
        m_azimuths = m_connections && settings.glint_azimuths;
        m_adaptive = m_azimuths && settings.adaptive_fractions;
        m_nee_fraction.assign(m_exits, nee_rate);
        m_glint_rate.assign(m_exits, m_connection_fraction);
        m_reverse = m_azimuths && settings.reverse_walks && (settings.connection_parts & 4U) != 0U;
        m_nee_on = (settings.connection_parts & 1U) != 0U;
        m_glints_on = (settings.connection_parts & 2U) != 0U;
        m_delta = m_azimuths && settings.delta_walks && (settings.connection_parts & 8U) != 0U;
        m_delta_rate = std::clamp(settings.delta_rate, kMinDeltaRate, kMaxDeltaRate);
        m_first_flake = m_delta && settings.first_flake_walks && !band.explicit_flakes.empty() &&
                        std::any_of(band.explicit_flakes[0].begin(), band.explicit_flakes[0].end(),
                                    [](const LayerFlakes& lf) { return lf.groups != nullptr; });
        m_uniform_delta = m_delta && (!m_first_flake || otherDeltaStarts(stack));
        // The cone weights come from the adaptive model; without it the tables would stay unused.
        if (m_delta && m_adaptive && settings.chain_promise) buildChainPromise();
        m_reverse_rate.assign(m_exits, std::clamp(settings.reverse_rate, kMinReverseRate, kMaxReverseRate));
        m_diagnostics = m_adaptive ? m_exits : 0;
        m_walk.max_events = settings.max_events;
        m_walk.roulette_weight = settings.roulette_weight;
        m_walk.histogram_classes = m_histogram_classes;
        m_walk.reflected_beams = m_reverse && settings.reflected_beams;
        m_walk.top_images = m_reverse && settings.top_images;
        m_walk.flake_images = m_azimuths && settings.flake_images && (settings.connection_parts & 16U) != 0U;
        m_walk.cone_direct = m_nee_on;
        m_walk.histogram_other = settings.histogram_other & (m_reverse ? ~4U : ~0U) & (m_delta ? ~1U : ~0U) &
                                 (m_walk.reflected_beams ? ~8U : ~0U) & (m_walk.top_images ? ~16U : ~0U) &
                                 (m_walk.flake_images ? ~(32U | 64U) : ~0U);
        m_walk.connections = m_connections;
        m_walk.connection_weight = 1.0 / m_connection_fraction;
        m_walk.split_branches = settings.explicit_flakes && settings.split_branches;
        buildViews(settings);
        if (m_azimuths) {
            m_azimuth_glints.resize(band.explicit_flakes.size());
            tbb::parallel_for(std::size_t{0}, band.explicit_flakes.size(), [&](std::size_t b) {
                m_azimuth_glints[b] = azimuthGlintSets(stack, band.explicit_flakes[b], m_v_in, m_bins);
            });
        }
    }

    // The delta walks' promise tables (chain_promise.h) in the frame of the
    // unturned beam (every view turns beam and cones together): the cones'
    // axes refracted into the first tiled layer's binder, the broadest
    // orientation law of its flakes and their largest R near the normal
    // (a paint with several tiled layers gets the first's: the promise only
    // steers the roulette, which stays unbiased).
    void buildChainPromise() {
        const PaintStack& stack = m_band.stack;
        const std::span<const LayerFlakes> layers = m_band.explicit_flakes.front();
        const auto tiled = std::find_if(stack.slices.begin(), stack.slices.end(), [&](const Slice& s) {
            return static_cast<std::size_t>(s.layer) < layers.size() &&
                   layers[static_cast<std::size_t>(s.layer)].tile != nullptr;
        });
        const double lateral = std::hypot(m_v_in.x, m_v_in.y);
        if (tiled == stack.slices.end() || !(lateral > 0.0)) return;
        double kappa = std::numeric_limits<double>::infinity();
        double reflectance = 0.0;
        for (const FlakeKind& kind : layers[static_cast<std::size_t>(tiled->layer)].kinds) {
            if (!kind.orientation.isDelta()) kappa = std::min(kappa, kind.orientation.kappa());
            reflectance = std::max(reflectance, kind.R(0.9));
        }
        if (!std::isfinite(kappa)) return;  // mirror-like flakes: no density to weigh by
        const double bx = m_v_in.x / lateral;
        const double by = m_v_in.y / lateral;
        const double ratio = stack.ambient_n / tiled->n;
        std::vector<Vec3> cones;
        for (const HistogramBin& bin : m_bins) {
            const double wx = bin.wo.x * ratio;
            const double wy = bin.wo.y * ratio;
            const double z = std::sqrt(std::max(0.0, 1.0 - wx * wx - wy * wy));
            cones.push_back({wx * bx + wy * by, wy * bx - wx * by, z});
        }
        m_promise = ChainPromise(cones, kappa, reflectance);
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
            if (m_connections && !settings.glint_azimuths)
                view.glints = glintSets(m_band.stack, m_band.explicit_flakes[b], view.v_in, view.bins);
        });
    }

    double specular() const { return m_specular; }
    std::size_t exitCount() const { return m_exits; }
    // The estimates' entries end here; then, with adaptive fractions, the
    // histogram's part of f per exit (a diagnostic for adapt()).
    std::size_t estimateEntries() const { return kFirstExit + m_exits + m_projected; }
    std::size_t entries() const { return estimateEntries() + m_diagnostics; }
    std::size_t coneStats() const { return m_adaptive ? m_exits : 0; }

    // The glint samples of one chunk (glint_azimuths): per exit k,
    // S_k = floor(rate_k paths + xi) samples (E[S_k] = rate_k paths), the flake
    // pick stratified over them (sample j in stratum j of the cumulative
    // weight) and the polygon's fan triangle by a random permutation of the
    // strata (Latin hypercube); sample j is added to path j paths / S_k with
    // weight 1 / rate_k, so the chunk's mean is sum_j value_j / (rate_k paths),
    // unbiased (E[sum_j value_j | S_k] = S_k G). Returns the per-path additions
    // [local path][exit] and fills the cone statistics.
    std::vector<double> chunkGlints(std::size_t batch, std::int64_t first_path, std::int64_t paths,
                                    std::vector<ConeStats>& cones) const {
        std::vector<double> added(static_cast<std::size_t>(paths) * m_exits, 0.0);
        if (!m_azimuths || !m_glints_on || paths <= 0) return added;
        const std::span<const LayerFlakes> tiles = m_band.explicit_flakes[batch];
        const std::vector<AzimuthGlintSet>& sets = m_azimuth_glints[batch];
        PathRng rng(m_settings.seed ^ kGlintStream, m_band_key, m_incidence_key,
                    static_cast<std::uint64_t>(first_path));
        std::vector<std::size_t> permutation;
        for (std::size_t k = 0; k < m_exits; ++k) {
            if (!(sets[k].total() > 0.0)) continue;
            const double rate = m_glint_rate[k];
            const auto count =
                static_cast<std::int64_t>(std::floor(rate * static_cast<double>(paths) + rng.uniform()));
            if (count <= 0) continue;
            permutation.resize(static_cast<std::size_t>(count));
            for (std::size_t j = 0; j < permutation.size(); ++j) permutation[j] = j;
            for (std::size_t j = permutation.size(); j > 1; --j)
                std::swap(permutation[j - 1],
                          permutation[static_cast<std::size_t>(rng.uniform() * static_cast<double>(j))]);
            const auto strata = static_cast<double>(count);
            std::int64_t rays = 0;
            for (std::int64_t j = 0; j < count; ++j) {
                GlintUniforms u;
                u.pick = (static_cast<double>(j) + rng.uniform()) / strata;
                u.psi = rng.uniform();
                u.choose = rng.uniform();
                u.u1 =
                    (static_cast<double>(permutation[static_cast<std::size_t>(j)]) + rng.uniform()) / strata;
                u.u2 = rng.uniform();
                u.u3 = rng.uniform();
                const double value = azimuthGlintSample(m_band.stack, tiles, sets[k], m_bins[k], u, &rays);
                const auto path = static_cast<std::size_t>(
                    std::min<std::int64_t>(paths - 1, (2 * j + 1) * paths / (2 * count)));
                added[path * m_exits + k] += value / rate;
                if (!cones.empty()) {
                    cones[k].glint_s1 += value;
                    cones[k].glint_s2 += value * value;
                }
            }
            if (!cones.empty()) {
                cones[k].glint_samples += strata;
                cones[k].glint_rays += static_cast<double>(rays);
            }
        }
        return added;
    }

    // The reverse walks of one chunk (reverse_walks; mc_walk.h, traceReversePath):
    // per exit k, S_k = floor(rate_k paths + xi) walks, each from a direction
    // uniform in the cone of a view (walk j of the chunk at view first_path + j)
    // and a point uniform on the tile, its estimate (Omega / Omega_proj) w_z
    // f(w, wi) added to path j paths / S_k with weight 1 / rate_k (unbiased as
    // the glints). Adds to `added` [local path][exit] and fills the cone statistics.
    void chunkReverse(std::size_t batch, std::int64_t first_path, std::int64_t paths,
                      std::vector<double>& added, std::vector<ConeStats>& cones) const {
        if (!m_reverse || paths <= 0) return;
        const std::span<const LayerFlakes> tiles = m_band.explicit_flakes[batch];
        const std::vector<View>& views = m_views[std::min(batch, m_views.size() - 1)];
        const PaintStack& stack = m_band.stack;
        const double n1 = stack.slices.front().n;
        WalkSettings walk = m_walk;
        walk.connections = false;
        const PathContext context{stack, {}, {}, tiles, walk, nullptr, {}, {}, {}};
        for (std::size_t k = 0; k < m_exits; ++k) {
            const std::uint64_t stream = m_settings.seed ^ kReverseStream ^ (0x9e3779b97f4a7c15ULL * (k + 1));
            PathRng count_rng(stream, m_band_key, m_incidence_key, static_cast<std::uint64_t>(first_path));
            const double rate = m_reverse_rate[k];
            const auto count = static_cast<std::int64_t>(
                std::floor(rate * static_cast<double>(paths) + count_rng.uniform()));
            double s1 = 0.0;
            double s2 = 0.0;
            double cost = 0.0;
            for (std::int64_t j = 0; j < count; ++j) {
                // Sample j of the chunk: index 4 first_path + j < 4 (first_path + paths), unique per job.
                const auto index = static_cast<std::uint64_t>(4 * first_path + j);
                PathRng rng(stream, m_band_key, m_incidence_key, index);
                PathRng connection_rng(stream ^ kConnectionStream, m_band_key, m_incidence_key, index);
                const View& view = views[static_cast<std::size_t>(first_path + j) % m_view_count];
                const HistogramBin& bin = view.bins[k];
                const double u1 = rng.uniform();
                const Vec3 w = sampleInCone(bin, u1, rng.uniform());
                const double x = rng.uniform() * m_tile_side_um;
                const double y = rng.uniform() * m_tile_side_um;
                double value = 0.0;
                if (w.z > 0.0) {
                    const double entry = 1.0 - fresnelDielectric(w.z, n1 / stack.ambient_n);
                    Vec3 v;
                    if (entry > 0.0 && refractPlanar({-w.x, -w.y, -w.z}, stack.ambient_n, n1, v)) {
                        const ReverseOutcome out =
                            traceReversePath(context, v, entry, x, y,
                                             {-view.v_in.x, -view.v_in.y, -view.v_in.z}, rng, connection_rng);
                        value = out.f * w.z * bin.solid_angle / bin.projected_solid_angle;
                        cost += kCostPerPath + kCostPerWalkStep * static_cast<double>(out.walk_steps) +
                                kCostPerNeeStep * static_cast<double>(out.nee_steps) +
                                kCostPerImageRay * static_cast<double>(out.image_rays);
                    }
                }
                const auto path = static_cast<std::size_t>(
                    std::min<std::int64_t>(paths - 1, (2 * j + 1) * paths / (2 * count)));
                added[path * m_exits + k] += value / rate;
                s1 += value;
                s2 += value * value;
            }
            if (!cones.empty()) {
                cones[k].reverse_samples += static_cast<double>(count);
                cones[k].reverse_s1 += s1;
                cones[k].reverse_s2 += s2;
                cones[k].reverse_cost += cost;
            }
        }
    }

    // One first-flake walk (first_flake.h) of a delta-chain sample: f_out is set
    // to its estimate per cone; with adaptive fractions its group's statistics
    // go into `sums` for the learned draw. Returns its cost (the model's µs).
    double firstFlakeWalk(const PathContext& context, const FirstFlakeTable& table, const Vec3& v_in,
                          PathRng& rng, std::vector<double>& f_out, Sums& sums) const {
        const double u_group = rng.uniform();
        const double u_flake = rng.uniform();
        const double u1 = rng.uniform();
        const double u2 = rng.uniform();
        const double u3 = rng.uniform();
        const FirstFlakeDraw draw =
            drawFirstFlake(context.explicit_flakes, table, u_group, u_flake, u1, u2, u3);
        std::fill(f_out.begin(), f_out.end(), 0.0);
        const PathOutcome out = traceFromFirstFlake(context, v_in, m_entry_weight, draw, rng, f_out);
        if (draw.key >= 0 && !sums.cones.empty()) {
            const auto key = static_cast<std::size_t>(draw.key);
            if (sums.first_count.size() <= key) sums.first_count.resize(key + 1, 0.0);
            if (sums.first_s2.size() < (key + 1) * m_exits) sums.first_s2.resize((key + 1) * m_exits, 0.0);
            sums.first_count[key] += 1.0;
            for (std::size_t k = 0; k < m_exits; ++k) {
                const double scaled = f_out[k] / draw.area_over_probability;  // f P_G / A_G
                sums.first_s2[key * m_exits + k] += scaled * scaled;
            }
        }
        return kCostPerPath + kCostPerWalkStep * static_cast<double>(out.events + out.rays);
    }

    // The delta-chain walks of one chunk (delta_walks; mc_walk.h, traceDeltaChains):
    // S = floor(rate paths + xi) samples, each a forward walk without collisions
    // from a point uniform on the tile at view first_path + j (only for the chains
    // that do not begin at a flake when the first-flake walks run, and only if
    // the paint has such chains: otherDeltaStarts) plus a first-flake walk;
    // their escapes of class Other into every cone added to path j paths / S
    // with weight 1 / rate.
    void chunkDelta(std::size_t batch, std::int64_t first_path, std::int64_t paths,
                    std::vector<double>& added, Sums& sums) const {
        std::vector<ConeStats>& cones = sums.cones;
        if (!m_delta || paths <= 0) return;
        const std::span<const LayerFlakes> tiles = m_band.explicit_flakes[batch];
        const std::vector<View>& views = m_views[std::min(batch, m_views.size() - 1)];
        WalkSettings walk = m_walk;
        walk.connections = false;
        walk.roulette_weight = m_settings.delta_roulette_weight;
        if (m_promise.ready()) {
            walk.chain_promise = &m_promise;
            walk.promise_threshold = m_settings.chain_promise_threshold;
            walk.promise_floor = m_settings.chain_promise_floor;
        }
        PathRng count_rng(m_settings.seed ^ kDeltaStream, m_band_key, m_incidence_key,
                          static_cast<std::uint64_t>(first_path));
        const auto count = static_cast<std::int64_t>(
            std::floor(m_delta_rate * static_cast<double>(paths) + count_rng.uniform()));
        walk.skip_beam_flake_reflections = m_first_flake;
        std::vector<double> f(m_exits);
        std::vector<double> f_first(m_exits);
        std::vector<FirstFlakeTable> tables(m_first_flake ? m_view_count : 0);
        for (std::int64_t j = 0; j < count; ++j) {
            // Walk j of the chunk: index 4 first_path + j < 4 (first_path + paths), unique per job (rate <=
            // 4).
            PathRng rng(m_settings.seed ^ kDeltaStream ^ 0x5bd1e995ULL, m_band_key, m_incidence_key,
                        static_cast<std::uint64_t>(4 * first_path + j));
            const std::size_t view_index = static_cast<std::size_t>(first_path + j) % m_view_count;
            const View& view = views[view_index];
            const double x = rng.uniform() * m_tile_side_um;
            const double y = rng.uniform() * m_tile_side_um;
            const PathContext context{m_band.stack, {}, view.bins, tiles, walk, nullptr, {}, {}, {}};
            std::fill(f.begin(), f.end(), 0.0);
            double cost = 0.0;
            if (m_uniform_delta) {
                const PathOutcome out = traceDeltaChains(context, view.v_in, m_entry_weight, x, y, rng, f);
                cost += kCostPerPath + kCostPerWalkStep * static_cast<double>(out.events + out.rays);
            }
            if (m_first_flake) {
                FirstFlakeTable& table = tables[view_index];
                if (table.cumulative.empty()) table = firstFlakeTable(tiles, view.v_in, m_first_proposal);
                cost += firstFlakeWalk(context, table, view.v_in, rng, f_first, sums);
                for (std::size_t k = 0; k < m_exits; ++k) f[k] += f_first[k];
            }
            const auto path = static_cast<std::size_t>(
                std::min<std::int64_t>(paths - 1, (2 * j + 1) * paths / (2 * count)));
            for (std::size_t k = 0; k < m_exits; ++k) {
                added[path * m_exits + k] += f[k] / m_delta_rate;
                if (cones.empty()) continue;
                cones[k].delta_samples += 1.0;
                cones[k].delta_s1 += f[k];
                cones[k].delta_s2 += f[k] * f[k];
                cones[k].delta_cost += cost;
            }
        }
    }

    Sums runChunk(std::size_t batch, std::int64_t first_path, std::int64_t paths) const {
        // Sums of deviations from the first path's sample (exact for constant samples), then mean and M2.
        std::vector<double> shift(entries(), 0.0);
        std::vector<double> s1(entries(), 0.0);
        std::vector<double> s2(entries(), 0.0);
        std::vector<double> sample(entries());
        Sums sums(entries(), coneStats());
        const std::span<double> f(sample.data() + kFirstExit, sample.size() - kFirstExit);
        const std::span<const LayerFlakes> explicit_flakes =
            m_band.explicit_flakes.empty() ? std::span<const LayerFlakes>{} : m_band.explicit_flakes[batch];
        const std::vector<View>& views = m_views[std::min(batch, m_views.size() - 1)];
        std::vector<double> glints = chunkGlints(batch, first_path, paths, sums.cones);
        chunkReverse(batch, first_path, paths, glints, sums.cones);
        std::vector<double> delta(m_delta ? glints.size() : 0, 0.0);
        chunkDelta(batch, first_path, paths, delta, sums);
        std::vector<double> nee(m_azimuths ? m_exits : 0);
        std::vector<double> nee_weights(m_azimuths ? m_exits : 0);
        std::vector<double> nee_boost(m_azimuths ? m_exits : 0);
        for (std::int64_t p = first_path; p < first_path + paths; ++p) {
            std::fill(sample.begin(), sample.end(), 0.0);
            if (m_entry_weight > 0.0) {
                const View& view = views[static_cast<std::size_t>(p) % m_view_count];
                PathRng rng(m_settings.seed, m_band_key, m_incidence_key, static_cast<std::uint64_t>(p));
                // The connections' own stream: the walk draws the same numbers with or without them.
                PathRng connection_rng(m_settings.seed ^ kConnectionStream, m_band_key, m_incidence_key,
                                       static_cast<std::uint64_t>(p));
                const double x = rng.uniform() * m_tile_side_um;
                const double y = rng.uniform() * m_tile_side_um;
                // Connections on a random share of the paths (all when the fraction is 1); with
                // glint_azimuths per exit cone: cone k when u < its rate x_k (nested shares),
                // and beyond x_k = 1 on every path, each pigment collision's chance raised x_k times.
                bool connect = false;
                if (m_azimuths) {
                    const double u = connection_rng.uniform();
                    for (std::size_t k = 0; k < m_exits; ++k) {
                        const double share = std::min(1.0, m_nee_fraction[k]);
                        nee_weights[k] = (m_nee_on || m_walk.flake_images) && u < share ? 1.0 / share : 0.0;
                        nee_boost[k] = std::max(1.0, m_nee_fraction[k]);
                        connect = connect || nee_weights[k] > 0.0;
                    }
                    std::fill(nee.begin(), nee.end(), 0.0);
                } else {
                    connect = m_connections && (m_connection_fraction >= 1.0 ||
                                                connection_rng.uniform() < m_connection_fraction);
                }
                const PathContext context{m_band.stack, m_chains,
                                          view.bins,    explicit_flakes,
                                          m_walk,       m_projected > 0 ? &view.cells : nullptr,
                                          view.glints,  nee_weights,
                                          nee,          nee_boost};
                const PathOutcome out = tracePath(context, view.v_in, m_entry_weight, x, y, rng, f,
                                                  connect ? &connection_rng : nullptr);
                sample[kEscaped] = out.escaped;
                sample[kTransmitted] = out.transmitted;
                sums.walk_cost += static_cast<double>(out.events + out.rays);
                sums.nee_cost += kCostPerNeeStep * static_cast<double>(out.nee_rays + out.nee_attempts) +
                                 kCostPerImageRay * static_cast<double>(out.image_rays);
                sums.nee_attempts += static_cast<double>(out.nee_attempts);
                if (m_azimuths) {
                    const auto local = static_cast<std::size_t>(p - first_path);
                    for (std::size_t k = 0; k < m_exits; ++k) {
                        if (m_diagnostics > 0) sample[estimateEntries() + k] = f[k];  // the histogram's part
                        f[k] += nee[k] + glints[local * m_exits + k] +
                                (delta.empty() ? 0.0 : delta[local * m_exits + k]);
                        if (!sums.cones.empty()) {
                            // The adaptive model's moments at rate x (adapt): E[Y] = E[X] and
                            // E[x Y^2] = E[X^2] at x <= 1 (Y = X / x on a share x of the paths);
                            // beyond, the thinning's variance falls as 1 / x while a collision's
                            // chance stays below 1, and x Y^2 keeps the model's B / x.
                            const double rate = m_nee_fraction[k];
                            sums.cones[k].nee_rate += rate;
                            sums.cones[k].nee_s1 += nee[k];
                            sums.cones[k].nee_s2 += rate * nee[k] * nee[k];
                        }
                    }
                }
            }
            if (p == first_path) shift = sample;
            for (std::size_t k = 0; k < sample.size(); ++k) {
                const double d = sample[k] - shift[k];
                s1[k] += d;
                s2[k] += d * d;
            }
        }
        sums.paths = paths;
        if (paths <= 0) return sums;
        const auto n = static_cast<double>(paths);
        for (std::size_t k = 0; k < sample.size(); ++k) {
            sums.mean[k] = shift[k] + s1[k] / n;
            sums.m2[k] = std::max(0.0, s2[k] - s1[k] * s1[k] / n);
        }
        return sums;
    }

    // Adaptive fractions (McSettings::adaptive_fractions), from every path so
    // far (`total`: the batches' sums merged in order, so deterministic). Per
    // exit cone k the variance of f per path is modelled as
    //   V_k(q, g, r) = A + B / q + C / g + D / r,   A = Var(histogram part) - E[X]^2,
    // B = E[X^2] (X the raw next-event score of a path that runs it, q the share
    // of paths that do), C = Var(raw glint sample) (g samples per path; the
    // stratification only lowers it), D = Var(raw reverse-walk sample) (r walks
    // per path), and the cost per path (microseconds on the reference machine,
    // from counted work: free paths, tile intersections, connections;
    // docs/PERFORMANCE.md) as c_walk + sum_k (q_k c_nee + g_k c_glint,k + r_k c_rev,k).
    // The stop rule waits for the worst cone, so the fractions minimise
    // max_k V_k / f_k^2 x cost: for a common level rho of V_k / f_k^2 each cone
    // takes the cheapest (q, g, r) that reaches it (cheapestRates), and rho is
    // scanned over a geometric grid. Only the next paths' fractions change, so
    // each path's estimate stays unbiased.
    // Returns whether it set the rates.
    bool adapt(const Sums& total) {
        if (!m_adaptive || total.paths < 1024 || total.cones.size() != m_exits) return false;
        const auto n = static_cast<double>(total.paths);
        const double c_walk = kCostPerPath + kCostPerWalkStep * total.walk_cost / n;
        double nee_rate = 0.0;
        for (const auto& c : total.cones) nee_rate += c.nee_rate;
        const double c_nee = nee_rate > 0.0 ? std::max(0.01, total.nee_cost / nee_rate) : 0.5;
        // Per cone: the three rates' variance coefficients, costs and bounds (next-event, glint, reverse).
        std::vector<std::array<RateTerm, 3>> terms(m_exits);
        std::vector<double> a(m_exits), f2(m_exits);
        for (std::size_t k = 0; k < m_exits; ++k) {
            const ConeStats& cs = total.cones[k];
            const std::size_t h = estimateEntries() + k;
            const double v_hist = total.paths > 1 ? total.m2[h] / (n - 1.0) : 0.0;
            const double mean_x = cs.nee_s1 / n;
            RateTerm nee{cs.nee_s2 / n, c_nee, kMinFraction, kMaxNeeRate};
            RateTerm glint{0.0, kCostPerGlint, kMinGlintRate, kMaxGlintRate};
            if (cs.glint_samples > 1.0) {
                const double mean_g = cs.glint_s1 / cs.glint_samples;
                glint.variance = std::max(0.0, cs.glint_s2 / cs.glint_samples - mean_g * mean_g);
                glint.cost = kCostPerGlint + kCostPerGlintRay * cs.glint_rays / cs.glint_samples;
            }
            RateTerm reverse{0.0, 1.0, kMinReverseRate, kMaxReverseRate};
            if (m_reverse && cs.reverse_samples > 1.0) {
                const double mean_r = cs.reverse_s1 / cs.reverse_samples;
                reverse.variance = std::max(0.0, cs.reverse_s2 / cs.reverse_samples - mean_r * mean_r);
                reverse.cost = std::max(0.05, cs.reverse_cost / cs.reverse_samples);
            }
            terms[k] = {nee, glint, reverse};
            a[k] = std::max(0.0, v_hist - mean_x * mean_x);
            const double f = total.mean[kFirstExit + k];
            f2[k] = f * f;
        }
        // The delta-chain walks serve every cone at once: one common rate d, scanned
        // over powers of two, its variance D_k / d joining A.
        std::vector<double> delta_variance(m_exits, 0.0);
        double delta_cost = 0.0;
        std::vector<double> delta_rates{m_delta_rate};
        if (m_delta && total.cones[0].delta_samples > 1.0) {
            delta_rates.clear();
            for (double d = kMinDeltaRate; d <= kMaxDeltaRate * 1.0001; d *= 2.0) delta_rates.push_back(d);
            for (std::size_t k = 0; k < m_exits; ++k) {
                const ConeStats& cs = total.cones[k];
                const double mean_d = cs.delta_s1 / cs.delta_samples;
                delta_variance[k] = std::max(0.0, cs.delta_s2 / cs.delta_samples - mean_d * mean_d);
            }
            delta_cost = total.cones[0].delta_cost / total.cones[0].delta_samples;
        }
        double best = std::numeric_limits<double>::infinity();
        std::vector<std::array<double, 3>> x(m_exits);
        for (const double d : delta_rates) {
            std::vector<double> a_d(m_exits);
            for (std::size_t k = 0; k < m_exits; ++k) a_d[k] = a[k] + delta_variance[k] / d;
            const auto variance = [&](std::size_t k, const std::array<double, 3>& rates) {
                double v = a_d[k];
                for (std::size_t t = 0; t < 3; ++t) v += terms[k][t].variance / rates[t];
                return v;
            };
            double rho_min = 0.0;  // the worst cone's relative variance at the largest rates
            for (std::size_t k = 0; k < m_exits; ++k)
                if (f2[k] > 0.0)
                    rho_min =
                        std::max(rho_min, variance(k, {kMaxNeeRate, kMaxGlintRate, kMaxReverseRate}) / f2[k]);
            if (!(rho_min > 0.0)) continue;
            for (int step = 0; step < 200; ++step) {
                const double rho = rho_min * std::pow(1.06, step);
                double cost = c_walk + d * delta_cost;
                double worst = 0.0;
                for (std::size_t k = 0; k < m_exits; ++k) {
                    if (f2[k] > 0.0) {
                        x[k] = cheapestRates(terms[k], rho * f2[k] - a_d[k]);
                        worst = std::max(worst, variance(k, x[k]) / f2[k]);
                    } else {
                        for (std::size_t t = 0; t < 3; ++t) x[k][t] = terms[k][t].lo;
                    }
                    for (std::size_t t = 0; t < 3; ++t)
                        if (t == 0 || terms[k][t].variance > 0.0) cost += x[k][t] * terms[k][t].cost;
                }
                if (worst * cost < best) {
                    best = worst * cost;
                    m_delta_rate = d;
                    for (std::size_t k = 0; k < m_exits; ++k) {
                        m_nee_fraction[k] = x[k][0];
                        m_glint_rate[k] = x[k][1];
                        m_reverse_rate[k] = x[k][2];
                    }
                }
            }
        }
        if (m_first_flake) learnFirstFlakeProposal(total, f2);
        weighPromiseCones(total, delta_variance, f2);
        return true;
    }

private:
    // The promise's cone weights (chain_promise.h): a chain into cone k is
    // worth its share of f_k (the stop rule's measure) times the cone's need
    // of the delta walks, the relative variance they leave in it over the
    // largest such: c_k = (f_min / f_k) (v_k / v_max), v_k = Var_delta,k / f_k^2.
    // (With f_min / f_k alone the demo's near-specular cones, whose delta part
    // is ~1e-3 of their variance, kept most branches: 20 % less cost per
    // walk at 437 nm instead of 35 %, and no shorter stop.)
    void weighPromiseCones(const Sums& total, const std::vector<double>& delta_variance,
                           const std::vector<double>& f2) {
        if (m_promise.empty()) return;
        double f_min = std::numeric_limits<double>::infinity();
        double v_max = 0.0;
        for (std::size_t k = 0; k < m_exits; ++k) {
            const double f = total.mean[kFirstExit + k];
            if (f > 0.0) f_min = std::min(f_min, f);
            if (f2[k] > 0.0) v_max = std::max(v_max, delta_variance[k] / f2[k]);
        }
        if (!std::isfinite(f_min) || !(v_max > 0.0)) return;
        std::vector<double> weights(m_exits, 0.0);
        for (std::size_t k = 0; k < m_exits; ++k) {
            const double f = total.mean[kFirstExit + k];
            if (f > 0.0) weights[k] = f_min / f * (delta_variance[k] / f2[k]) / v_max;
        }
        m_promise.setConeWeights(weights);
    }

    // The first-flake walks' group weights from every walk so far (first_flake.h):
    // P_G proportional to A_G rho_key is variance-optimal for the sum of the
    // cones' relative variances (the flop cones, whose delta part is largest,
    // weigh most) at rho_key^2 = E[sum_k (f_k P_G / A_G)^2 / f_k^2 | key]. A
    // key holds few hits (a few hundred over hundreds of keys at the demo's
    // flop), so its mean square is shrunk towards that of all keys with the
    // weight of kFirstFlakePrior draws: unmeasured keys stay area-proportional.
    // (Without the shrinkage the learned weights followed single hits, and
    // the delta walks' variance at 780 nm rose 1.4x above the area-proportional draw.)
    void learnFirstFlakeProposal(const Sums& total, const std::vector<double>& f2) {
        const std::size_t keys = total.first_count.size();
        std::vector<double> s(keys, 0.0);
        double s_all = 0.0;
        double n_all = 0.0;
        for (std::size_t key = 0; key < keys; ++key) {
            for (std::size_t k = 0; k < m_exits; ++k)
                if (f2[k] > 0.0 && (key + 1) * m_exits <= total.first_s2.size())
                    s[key] += total.first_s2[key * m_exits + k] / f2[k];
            s_all += s[key];
            n_all += total.first_count[key];
        }
        if (!(s_all > 0.0) || !(n_all > 0.0)) return;
        const double mean_all = s_all / n_all;
        m_first_proposal.h.assign(keys, 0.0);
        for (std::size_t key = 0; key < keys; ++key)
            m_first_proposal.h[key] = std::sqrt((s[key] + kFirstFlakePrior * mean_all) /
                                                (total.first_count[key] + kFirstFlakePrior));
        m_first_proposal.rho_default = std::sqrt(mean_all);
    }

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
    WalkSettings m_walk;
    struct View {
        Vec3 v_in;
        std::vector<HistogramBin> bins;
        FourierCells cells;
        std::vector<GlintSet> glints;  // per bin (connections)
    };
    std::vector<std::vector<View>> m_views;  // [batch][view]
    std::size_t m_view_count = 1;
    double m_connection_fraction = 1.0;
    bool m_azimuths = false;  // glint_azimuths
    bool m_adaptive = false;  // adaptive_fractions
    bool m_reverse = false;   // reverse_walks
    bool m_nee_on = true;     // connection_parts
    bool m_glints_on = true;
    bool m_delta = false;  // delta_walks
    double m_delta_rate = 0.25;
    bool m_first_flake = false;    // first_flake_walks: the delta chains that begin at a flake
    bool m_uniform_delta = false;  // the uniform delta-chain walks (for the other chains)
    FirstFlakeProposal m_first_proposal;
    ChainPromise m_promise;              // the delta walks' roulette by promise (empty: off)
    std::vector<double> m_reverse_rate;  // per exit: reverse walks per path
    std::size_t m_diagnostics = 0;
    std::vector<double> m_nee_fraction;  // per exit: share of paths that run its next-event connections
    std::vector<double> m_glint_rate;    // per exit: glint samples per path
    std::vector<std::vector<AzimuthGlintSet>> m_azimuth_glints;  // [batch][exit]
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
    for (std::size_t k = kFirstExit + runner.exitCount(); k < runner.estimateEntries(); ++k)
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
            layers.push_back({m_tiles[b][l].get(), kinds[l], tilts.order.empty() ? nullptr : &tilts,
                              groups.flakes.empty() ? nullptr : &groups});
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
    // Small runs: chunks small enough that every batch gets paths.
    const std::int64_t chunk = std::max<std::int64_t>(
        1, std::min<std::int64_t>(m_settings.chunk_paths, (max_paths + m_batches - 1) / m_batches));
    std::vector<Sums> batches(static_cast<std::size_t>(m_batches),
                              Sums(runner.entries(), runner.coneStats()));
    const bool over_batches = m_settings.explicit_flakes && m_batches > 1;
    std::int64_t next_chunk = 0;  // chunks started: chunk k goes to batch k % batches
    std::int64_t started = 0;     // paths started: the next chunk's first path index
    JobResult current;
    Sums seen(runner.entries(), runner.coneStats());  // every path so far, for the adaptive rates
    bool pilot_dropped = false;
    while (started < max_paths) {
        // One round of chunks in parallel; summed in chunk order (deterministic).
        const std::int64_t remaining = max_paths - started;
        std::int64_t round_chunk = chunk;
        std::int64_t round_chunks =
            std::min<std::int64_t>(std::max(1, m_settings.chunks_per_round), (remaining + chunk - 1) / chunk);
        if (budget_seconds > 0.0) {
            // A time budget: the stop is checked between rounds only, and one
            // round of a slow paint (long walks in a scattering ground coat)
            // can outlast a job's share many times over (measured: 370 s for
            // a 20 s compare of the three-layer demo). So a short pilot round
            // first, then rounds sized to the time left at the pace measured;
            // runs with a path count alone keep their fixed chunks.
            const double elapsed = std::chrono::duration<double>(Clock::now() - job_start).count();
            if (started == 0) {
                round_chunk = std::min<std::int64_t>(chunk, kPilotChunkPaths);
            } else {
                const double seconds_per_path = elapsed / static_cast<double>(started);
                const double affordable = std::max(0.0, budget_seconds - elapsed) / seconds_per_path;
                const auto paths =
                    static_cast<std::int64_t>(std::min(affordable, static_cast<double>(remaining)));
                round_chunk = std::clamp<std::int64_t>((paths + round_chunks - 1) / round_chunks, 1, chunk);
            }
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
            // unboosted chance, then boosted up to 64 times); they only set the
            // rates and are dropped while they are a small part of the job
            // (unbiased: the rates are fixed before the kept paths run).
            // Measured on the demo at 380 nm: 328k paths to 1 % instead of 574k.
            if (runner.adapt(seen) && !pilot_dropped) {
                pilot_dropped = true;
                if (started * 8 <= max_paths && (budget_seconds <= 0.0 || elapsed * 8.0 <= budget_seconds)) {
                    for (auto& b : batches) b = Sums(runner.entries(), runner.coneStats());
                    dropped_now = true;
                }
            }
        }
        current = finish(runner, batches, over_batches, elapsed);
        const bool out_of_time = budget_seconds > 0.0 && elapsed >= budget_seconds;
        if (progress) {
            double fraction = std::min(1.0, static_cast<double>(started) / static_cast<double>(max_paths));
            if (budget_seconds > 0.0) fraction = std::max(fraction, std::min(1.0, elapsed / budget_seconds));
            if (!progress(fraction)) throw Error("Monte Carlo: cancelled");
        }
        // The stop rule reads the spread of the batches: only once every batch has paths
        // (a spread over a few batches of one chunk each is itself too uncertain to stop on).
        const bool every_batch = !over_batches || std::all_of(batches.begin(), batches.end(),
                                                              [](const Sums& b) { return b.paths > 0; });
        if (out_of_time ||
            (!dropped_now && every_batch && converged(current, m_settings.target_rel_error, job.orders)))
            break;
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
    std::function<bool()> keep_going;
    if (progress) keep_going = [&progress] { return progress(0.0); };
    const McEngine engine(recipe, settings, keep_going);
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
