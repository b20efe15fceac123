#include "mc_job_runner.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace paintlab::mc {

namespace {

// Seeds of the random streams besides the walks' own.
constexpr std::uint64_t kConnectionStream = 0x636f6e6e656374ULL;  // "connect"
constexpr std::uint64_t kGlintStream = 0x676c696e74ULL;           // "glint"
constexpr std::uint64_t kReverseStream = 0x72657665727365ULL;     // "reverse"
constexpr std::uint64_t kDeltaStream = 0x64656c7461ULL;           // "delta"
constexpr std::uint64_t kShareStream = 0x7368617265ULL;           // "share"

}  // namespace

// The glint samples of one chunk (glint_azimuths): per exit k,
// S_k = floor(rate_k paths + xi) samples (E[S_k] = rate_k paths), the flake
// pick stratified over them (sample j in stratum j of the cumulative
// weight) and the polygon's fan triangle by a random permutation of the
// strata (Latin hypercube); sample j is added to path j paths / S_k with
// weight 1 / rate_k, so the chunk's mean is sum_j value_j / (rate_k paths),
// unbiased (E[sum_j value_j | S_k] = S_k G). Returns the per-path additions
// [local path][exit] and fills the cone statistics.
std::vector<double> JobRunner::chunkGlints(std::size_t batch, std::int64_t first_path, std::int64_t paths,
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
        const double rate = m_rates.glint_rate[k];
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
            u.u1 = (static_cast<double>(permutation[static_cast<std::size_t>(j)]) + rng.uniform()) / strata;
            u.u2 = rng.uniform();
            u.u3 = rng.uniform();
            if (m_move_glint_flakes) {
                u.moved = true;
                u.move_x = rng.uniform();
                u.move_y = rng.uniform();
            }
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
void JobRunner::chunkReverse(std::size_t batch, std::int64_t first_path, std::int64_t paths,
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
        const double rate = m_rates.reverse_rate[k];
        const auto count =
            static_cast<std::int64_t>(std::floor(rate * static_cast<double>(paths) + count_rng.uniform()));
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
                        traceReversePath(context, v, entry, x, y, {-view.v_in.x, -view.v_in.y, -view.v_in.z},
                                         rng, connection_rng);
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
double JobRunner::firstFlakeWalk(const PathContext& context, const FirstFlakeTable& table, const Vec3& v_in,
                                 PathRng& rng, std::vector<double>& f_out, Sums& sums) const {
    const double u_group = rng.uniform();
    const double u_flake = rng.uniform();
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    const double u3 = rng.uniform();
    const FirstFlakeDraw draw = drawFirstFlake(context.explicit_flakes, table, u_group, u_flake, u1, u2, u3);
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
// with weight 1 / rate. Without first-flake walks, a walk runs the chain
// connections with probability delta_chain_share (its own stream's draw, made
// only below 1), their scores weighted by its inverse; the split of its
// score between escapes and connections goes into the cone statistics.
void JobRunner::chunkDelta(std::size_t batch, std::int64_t first_path, std::int64_t paths,
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
        std::floor(m_rates.delta_rate * static_cast<double>(paths) + count_rng.uniform()));
    walk.skip_beam_flake_reflections = m_first_flake;
    // The chain connections' share (the first-flake walks keep them on every walk).
    const double share = m_first_flake ? 1.0 : m_rates.delta_chain_share;
    const bool split = !m_first_flake && walk.delta_chain_connections;
    WalkSettings walk_bare = walk;
    walk_bare.delta_chain_connections = false;
    walk.chain_connection_weight = 1.0 / share;
    walk.drawn_chain_rate = m_first_flake ? 1.0 : m_rates.drawn_chain_rate;
    walk.chain_length_um = m_first_flake ? 0.0 : m_rates.chain_length_um;
    walk.kernel_chain_cones = m_settings.kernel_chain_cones;
    walk.chain_cone_scale = m_chain_cone_scale;
    if (m_form_weights_learned) walk.cavity_form_weights = &m_form_weights;
    std::vector<double> f(m_exits);
    std::vector<double> f_chain(m_exits);
    std::vector<double> f_first(m_exits);
    std::vector<double> drawn_before;  // the learning's drawn_s1 before the walk
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
        bool chained = true;
        if (share < 1.0) {
            PathRng coin(m_settings.seed ^ kDeltaStream ^ kShareStream, m_band_key, m_incidence_key,
                         static_cast<std::uint64_t>(4 * first_path + j));
            chained = coin.uniform() < share;
        }
        std::fill(f.begin(), f.end(), 0.0);
        std::fill(f_chain.begin(), f_chain.end(), 0.0);
        const PathContext context{m_band.stack,
                                  {},
                                  view.bins,
                                  tiles,
                                  chained ? walk : walk_bare,
                                  nullptr,
                                  {},
                                  {},
                                  {},
                                  {},
                                  split ? std::span<double>(f_chain) : std::span<double>(),
                                  &sums.form_learning,
                                  m_first_flake ? nullptr : &sums.length_learning};
        double cost = 0.0;
        double chain_cost = 0.0;
        if (m_uniform_delta) {
            const double drawn_steps = sums.form_learning.drawn_steps;
            drawn_before = sums.form_learning.drawn_s1;
            const PathOutcome out = traceDeltaChains(context, view.v_in, m_entry_weight, x, y, rng, f);
            // A last-flake connection (a cone's draw, kernel and roulette) costs about two walk steps,
            // the drawn cavity chains their counted steps.
            chain_cost = kCostPerWalkStep * (static_cast<double>(2 * out.nee_attempts) +
                                             sums.form_learning.drawn_steps - drawn_steps);
            cost += kCostPerPath + kCostPerWalkStep * static_cast<double>(out.events + out.rays) + chain_cost;
        }
        if (m_first_flake) {
            FirstFlakeTable& table = tables[view_index];
            if (table.cumulative.empty()) table = firstFlakeTable(tiles, view.v_in, m_first_proposal);
            cost += firstFlakeWalk(context, table, view.v_in, rng, f_first, sums);
            for (std::size_t k = 0; k < m_exits; ++k) f[k] += f_first[k];
        }
        const auto path =
            static_cast<std::size_t>(std::min<std::int64_t>(paths - 1, (2 * j + 1) * paths / (2 * count)));
        for (std::size_t k = 0; k < m_exits; ++k) {
            const double escapes = f[k];
            const double total = escapes + f_chain[k];
            added[path * m_exits + k] += total / m_rates.delta_rate;
            if (cones.empty()) continue;
            cones[k].delta_samples += 1.0;
            cones[k].delta_s1 += total;
            cones[k].delta_s2 += total * total;
            cones[k].delta_cost += cost;
            if (!split) continue;
            cones[k].escape_s2 += escapes * escapes;
            if (!chained) continue;
            const double chain = f_chain[k] * share;  // unweighted by the share
            cones[k].chain_samples += 1.0;
            cones[k].chain_s2 += chain * chain;
            cones[k].chain_cross += escapes * chain;
            cones[k].chain_cost += chain_cost;
            // The guard's largest C^2 without the drawn chains' part (they have their own: DeltaWalkModel).
            const std::vector<double>& drawn_after = sums.form_learning.drawn_s1;
            const double drawn = k < drawn_after.size()
                                     ? drawn_after[k] - (k < drawn_before.size() ? drawn_before[k] : 0.0)
                                     : 0.0;
            const double rest = chain - drawn;
            cones[k].chain_max2 = std::max(cones[k].chain_max2, rest * rest);
        }
    }
}

Sums JobRunner::runChunk(std::size_t batch, std::int64_t first_path, std::int64_t paths) const {
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
                    const double share = std::min(1.0, m_rates.nee_fraction[k]);
                    nee_weights[k] = (m_nee_on || m_walk.flake_images) && u < share ? 1.0 / share : 0.0;
                    nee_boost[k] = std::max(1.0, m_rates.nee_fraction[k]);
                    connect = connect || nee_weights[k] > 0.0;
                }
                std::fill(nee.begin(), nee.end(), 0.0);
            } else {
                connect = m_connections &&
                          (m_connection_fraction >= 1.0 || connection_rng.uniform() < m_connection_fraction);
            }
            const PathContext context{m_band.stack,    m_chains,    view.bins,
                                      explicit_flakes, m_walk,      m_projected > 0 ? &view.cells : nullptr,
                                      view.glints,     nee_weights, nee,
                                      nee_boost};
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
                        const double rate = m_rates.nee_fraction[k];
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

}  // namespace paintlab::mc
