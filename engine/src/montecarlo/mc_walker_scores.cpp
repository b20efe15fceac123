#include "mc_walker.h"

#include "last_flake.h"
#include "mc_bottom.h"
#include "mc_reflected_beams.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

// Connections into the cones: for each cone this path connects to, a
// direction w uniform in it (u: refracted into slice s) and score(w, u),
// the vertex's estimate towards w before the connection weight, the
// radiance law (n_0 / n)^2 and the cone's factor w_z Omega / Omega_proj.
// `cone_weight(k)`: this vertex's own factor on cone k's connection (0: none).
template <class Score, class ConeWeight>
void Walker::eachCone(const Slice& s, const Score& score, const ConeWeight& cone_weight) {
    const double scale = (stack.ambient_n / s.n) * (stack.ambient_n / s.n);
    for (std::size_t k = 0; k < bins.size(); ++k) {
        const double connection_weight =
            (nee_weights.empty() ? settings.connection_weight : nee_weights[k]) * cone_weight(k);
        if (!(connection_weight > 0.0)) continue;
        const HistogramBin& bin = bins[k];
        const double u1 = connection_rng->uniform();
        const Vec3 w = sampleInCone(bin, u1, connection_rng->uniform());
        Vec3 u;
        if (!(w.z > 0.0) || !refractPlanar(w, stack.ambient_n, s.n, u)) continue;
        const double value = score(w, u);
        if (!(value > 0.0)) continue;
        (nee_out.empty() ? brdf_out : nee_out)[k] +=
            connection_weight * value * scale * w.z * bin.solid_angle / bin.projected_solid_angle;
    }
}

// Connections: next-event estimation from a smooth vertex in slice j into
// a direction uniform in each cone, through the tiles (mc_connection.h);
// `emitted(u)` is the vertex's scattered weight per sr towards u (in the
// slice) over the cosine's projection factor.
template <class Emitted, class ConeWeight>
void Walker::coneNextEvent(const Slice& s, const Emitted& emitted, const ConeWeight& cone_weight) {
    eachCone(
        s,
        [&](const Vec3& /*w*/, const Vec3& u) {
            const double value = emitted(u);
            if (!(value > 0.0)) return 0.0;
            ++tally.nee_attempts;
            return value * straightToAmbient(stack, explicit_flakes, j, depth, x, y, u, &tally.nee_rays,
                                             settings.connection_roulette ? connection_rng : nullptr);
        },
        cone_weight);
}

// Connections through one flake (WalkSettings::flake_images): from a pigment
// vertex in slice j (a tiled layer), for a direction w uniform in each cone
// (u_top in the top slice), the light that reaches w after one mirror
// reflection off a flake of this layer, straight or by way of the top's
// internal reflection: by reciprocity the beam -u_top's images off those
// flakes seen from the vertex (mc_connection.h, reflectedBeams), which a
// planar flake makes exact. `factor` is the vertex's weight / (sigma q);
// its scattered weight per sr towards the flake is factor times the kernel
// (reflectedBeams includes it), and the 1 / u_z of a direct connection is
// that of the last leg (mirroring keeps the volume element), as for the
// reverse walks' images.
template <class ConeWeight>
void Walker::coneFlakeImages(const Slice& s, double factor, const ConeWeight& cone_weight) {
    const double n_top = stack.slices.front().n;
    eachCone(
        s,
        [&](const Vec3& w, const Vec3& u) {
            Vec3 u_top;
            if (!(u.z > 0.0) || !refractPlanar(w, stack.ambient_n, n_top, u_top)) return 0.0;
            ++tally.image_calls;
            return factor / u.z *
                   reflectedBeams(stack, explicit_flakes, j, depth, x, y, v, {-u_top.x, -u_top.y, -u_top.z},
                                  {true, true}, &tally.image_rays);
        },
        cone_weight);
}

// Reverse walk: the next-event estimate towards reverse_target (f at that
// one direction, as the point estimator: no cone), `emitted(u)` as in coneNextEvent.
template <class Emitted> void Walker::reverseNextEvent(const Slice& s, const Emitted& emitted) {
    Vec3 u;
    if (!refractPlanar(reverse_target, stack.slices.front().n, s.n, u) || !(u.z > 0.0)) return;
    const double value = emitted(u);
    if (!(value > 0.0)) return;
    ++tally.nee_attempts;
    const double scale = (stack.ambient_n / s.n) * (stack.ambient_n / s.n);
    tally.reverse_score += value *
                           straightToAmbient(stack, explicit_flakes, j, depth, x, y, u, &tally.nee_rays,
                                             settings.connection_roulette ? connection_rng : nullptr) *
                           scale;
}

// Reverse walk: the next-event estimates towards the beam's single mirror
// images off the flakes of this layer, and those off a flake and then the
// paint's top (mc_connection.h, reflectedBeams), with
// the direct beam's factors (`factor` = weight / (sigma q), over |beam_z|).
void Walker::reverseReflectedBeams(const Slice& s, double factor) {
    Vec3 beam;
    if (!refractPlanar(reverse_target, stack.slices.front().n, s.n, beam) || !(beam.z > 0.0)) return;
    ++tally.image_calls;
    const double scale = (stack.ambient_n / s.n) * (stack.ambient_n / s.n);
    tally.reverse_score += factor / beam.z * scale *
                           reflectedBeams(stack, explicit_flakes, j, depth, x, y, v,
                                          {-reverse_target.x, -reverse_target.y, -reverse_target.z},
                                          {settings.reflected_beams, settings.top_images}, &tally.image_rays);
}

void Walker::escape() {
    // An escape right after a reflection off a flake met for the first time,
    // of a layer with a law (and an earlier change: class Other), is the
    // last-flake connections' (lastFlakeConnections); one that ends a cavity
    // chain the cavity connections' (cavityConnections). They run on the
    // delta-chain walks and, for what its histogram scores, the forward walk.
    bool taken = false;
    using WalkScores = CavityForms::WalkScores;
    const WalkScores walk_scores = settings.cavity_forms.walk_scores;
    bool drawn_form = false;  // the escape ends a drawn cavity chain (WalkScores::DrawnOnly)
    if (chainRecording() && (chain_connections || walk_scores == WalkScores::DrawnOnly)) {
        if (chain_connections && last_flake_layer >= 0 && history.path_class == PathClass::Other &&
            explicit_flakes[static_cast<std::size_t>(last_flake_layer)].last_flake_connections)
            taken = true;
        // (A cavity chain ends at a flake of its layer: the ring is searched only then.)
        const std::int64_t latest = change_count > 0 ? changeBack(0).chain.flake_id : -1;
        if (!taken && latest >= 0 &&
            (walk_scores == WalkScores::DrawnOnly ||
             explicit_flakes[static_cast<std::size_t>(latest % 64)].cavity_connections)) {
            const CavityForm form = cavityFormNow();
            if (form.layer >= 0) {
                const LayerFlakes& in = explicit_flakes[static_cast<std::size_t>(form.layer)];
                drawn_form = form.drawn(in.draws_cavity_chains);
                taken = chain_connections &&
                        explicit_flakes[static_cast<std::size_t>(latest % 64)].cavity_connections &&
                        in.cavity_connections &&
                        cavityFormTaken(settings.cavity_forms, form, in.draws_cavity_chains,
                                        in.drawn_cavity_chains);
            }
        }
    }
    const bool scored =
        walk_scores == WalkScores::All || (walk_scores == WalkScores::DrawnOnly && drawn_form);
    if (!taken && scored && history.histogramScores(settings.histogram_classes, settings.histogram_other))
        for (std::size_t k = 0; k < bins.size(); ++k)
            if (dot(v, bins[k].wo) >= bins[k].cos_cone) brdf_out[k] += weight / bins[k].projected_solid_angle;
    if (fourier != nullptr) project(*fourier);
}

void Walker::project(const FourierCells& cells) {
    const double mu = std::clamp(v.z, 0.0, 1.0);
    const double t_out = 1.0 - fresnelDielectric(mu, cells.top_eta);
    if (!(t_out > 0.0)) return;
    const auto it = std::lower_bound(cells.upper_mu.begin(), cells.upper_mu.end(), mu);
    const auto cell = std::min(static_cast<std::size_t>(it - cells.upper_mu.begin()), cells.scale.size() - 1);
    // cos(m delta) by the Chebyshev recurrence from cos(delta).
    const double sin_o = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const double c =
        sin_o > 1e-12 ? std::clamp((v.x * cells.cos_in + v.y * cells.sin_in) / sin_o, -1.0, 1.0) : 1.0;
    const double value = weight / t_out * cells.scale[cell];
    double* out = brdf_out.data() + cells.offset + cell * static_cast<std::size_t>(cells.orders);
    double previous = 1.0;
    double current = c;
    out[0] += value;
    for (int m = 1; m < cells.orders; ++m) {
        out[m] += value * current;
        const double next = 2.0 * c * current - previous;
        previous = current;
        current = next;
    }
}

void Walker::scoreCollision(const Slice& s, double sigma) {
    for (std::size_t k = 0; k < chains.size(); ++k) {
        const ExitChain& c = chains[k];
        const double mu = c.mu[j];
        if (mu <= 0.0) continue;
        const double e = c.extinction[j];
        double value = 0.0;
        if (c.up[j] > 0.0)
            value +=
                s.kernel(v, c.direction(stack, j, true)) * std::exp(-e * (depth - s.top_um) / mu) * c.up[j];
        if (c.down[j] > 0.0)
            value += s.kernel(v, c.direction(stack, j, false)) * std::exp(-e * (s.bottom_um - depth) / mu) *
                     c.down[j];
        brdf_out[k] += weight * value / (sigma * mu);
    }
}

double Walker::substrateEmitted(const Vec3& u) const {
    // The Lambertian's product in its order before the operator (bit-identical results).
    return stack.substrate == SubstrateKind::Operator ? weight * stack.bottom->eval(v, u)
                                                      : weight * stack.lambert_albedo / kPi;
}

void Walker::scoreLambert(const Slice& s) {
    for (std::size_t k = 0; k < chains.size(); ++k)
        if (chains[k].lambert > 0.0)
            brdf_out[k] += substrateEmitted(chains[k].direction(stack, j, true)) * chains[k].lambert;
    if (connection_rng != nullptr && settings.cone_direct)
        coneNextEvent(
            s, [&](const Vec3& u) { return substrateEmitted(u); }, [](std::size_t /*k*/) { return 1.0; });
}

void Walker::connectFromPigment(const Slice& s, double sigma) {
    // Connections: the kernel of a tiled layer's slice is the pigments' alone
    // (sigma_s HG), so cone k's next event is drawn with probability
    // q_k = min(1, b_k sigma_s / sigma) and weighted by 1 / q_k (unbiased;
    // one uniform for every cone, so the cones' draws nest). With absorbing
    // pigments most collisions absorb by weighting: at b_k = 1 (the chance
    // that the collision scatters) a connection costs six shadow rays per
    // scattering, but the score is then zero on all but q of the
    // collisions (the demo's carbon black: q ~ 0.5-3 %), and at the flop,
    // where these connections are most of f, that thinning was most of
    // the variance. The boosts b_k (nee_boost) trade the two per cone.
    if (connection_rng != nullptr && s.sigma_s_per_um > 0.0) {
        const double q = std::min(1.0, s.sigma_s_per_um / sigma);
        double q_max = q;
        for (std::size_t k = 0; k < nee_boost.size(); ++k) q_max = std::max(q_max, coneCollisionRate(q, k));
        const double u_connect = connection_rng->uniform();
        if (u_connect < q_max) {
            const auto fired = [&](std::size_t k) {
                const double q_k = coneCollisionRate(q, k);
                return u_connect < q_k ? 1.0 / q_k : 0.0;
            };
            if (settings.cone_direct)
                coneNextEvent(
                    s, [&](const Vec3& u) { return weight * s.kernel(v, u) / (sigma * u.z); }, fired);
            // The flake images keep the unboosted chance q: they cost a search of
            // the tile's flakes each, and are a small part of f where boosts pay.
            if (settings.flake_images && u_connect < q && tiled(s.layer) &&
                history.deltaFirstPrefixAt(s.layer))
                coneFlakeImages(s, weight / (sigma * q), [](std::size_t /*k*/) { return 1.0; });
        }
    }
}

Walker::ChainKernel Walker::chainKernel(const LayerFlakes& lf, const Vec3& h, double cos_vh, double geometric,
                                        double factor, PathRng& chain_rng) {
    ChainKernel out;
    const std::size_t kinds = std::min(lf.last_flake->kinds.size(), lf.kinds.size());
    double bare = 0.0;
    for (std::size_t i = 0; i < kinds && i < out.per_kind.size(); ++i) {
        out.per_kind[i] = lf.last_flake->kinds[i].geometry.area_density_per_um *
                          lf.kinds[i].orientation.pdf(h.z) * geometric;
        bare += out.per_kind[i];
    }
    ++tally.nee_attempts;
    if (!(bare * factor > 0.0)) return out;
    const double q = std::min(1.0, bare * factor / settings.roulette_weight);
    if (q < 1.0 && chain_rng.uniform() >= q) return out;
    for (std::size_t i = 0; i < kinds && i < out.per_kind.size(); ++i)
        if (out.per_kind[i] > 0.0) out.per_kind[i] *= lf.kinds[i].R(cos_vh);
    out.q = q;
    return out;
}

bool Walker::kernelConeProbabilities(const Slice& s, const LayerFlakes& lf,
                                     std::array<double, kMaxKernelCones>& p) const {
    const std::size_t cones = bins.size();
    if (cones > p.size() || lf.last_flake == nullptr) return false;
    const std::size_t kinds = std::min(lf.last_flake->kinds.size(), lf.kinds.size());
    const RefractedConeAxes& axes = coneAxesIn(s.n);
    double total = 0.0;
    for (std::size_t k = 0; k < cones; ++k) {
        p[k] = 0.0;
        const Vec3& u = axes.u[k];
        if (!(u.z > 0.0)) continue;
        Vec3 h{u.x - v.x, u.y - v.y, u.z - v.z};
        const double len = std::sqrt(dot(h, h));
        if (len < 1e-12) continue;
        double density = 0.0;
        for (std::size_t i = 0; i < kinds; ++i)
            density +=
                lf.last_flake->kinds[i].geometry.area_density_per_um * lf.kinds[i].orientation.pdf(h.z / len);
        const double scale = k < settings.chain_cone_scale.size() ? settings.chain_cone_scale[k] : 1.0;
        p[k] = density * axes.factor[k] * scale;
        total += p[k];
    }
    if (!(total > 0.0) || !std::isfinite(total)) return false;
    for (std::size_t k = 0; k < cones; ++k)
        p[k] = kUniformConeShare / static_cast<double>(cones) + (1.0 - kUniformConeShare) * p[k] / total;
    return true;
}

const Walker::RefractedConeAxes& Walker::coneAxesIn(double n) const {
    if (cone_axes.n == n) return cone_axes;
    cone_axes.n = n;
    for (std::size_t k = 0; k < bins.size() && k < kMaxKernelCones; ++k) {
        const HistogramBin& bin = bins[k];
        Vec3 u;
        const bool ok = bin.wo.z > 0.0 && refractPlanar(bin.wo, stack.ambient_n, n, u) && u.z > 0.0;
        cone_axes.u[k] = ok ? u : Vec3{0.0, 0.0, 0.0};
        cone_axes.factor[k] = ok ? bin.wo.z / u.z * bin.solid_angle / bin.projected_solid_angle : 0.0;
    }
    return cone_axes;
}

Walker::ChainDraw Walker::drawChainCone(const Slice& s, double length, double sigma, PathRng& chain_rng,
                                        std::span<const double> cone_p) const {
    ChainDraw draw;
    const double pick = chain_rng.uniform();
    double cone_weight = static_cast<double>(bins.size());  // 1 / the drawn cone's probability
    if (cone_p.empty()) {
        draw.k = std::min(bins.size() - 1, static_cast<std::size_t>(pick * static_cast<double>(bins.size())));
    } else {
        double below = 0.0;
        draw.k = bins.size() - 1;
        for (std::size_t k = 0; k + 1 < bins.size(); ++k) {
            below += cone_p[k];
            if (pick < below) {
                draw.k = k;
                break;
            }
        }
        if (!(cone_p[draw.k] > 0.0)) return draw;
        cone_weight = 1.0 / cone_p[draw.k];
    }
    const HistogramBin& bin = bins[draw.k];
    draw.t = length * chain_rng.uniform();
    const double u1 = chain_rng.uniform();
    const Vec3 w = sampleInCone(bin, u1, chain_rng.uniform());
    if (!(w.z > 0.0) || !refractPlanar(w, stack.ambient_n, s.n, draw.u) || !(draw.u.z > 0.0)) return draw;
    draw.point_depth = std::clamp(depth - v.z * draw.t, s.top_um, s.bottom_um);
    const double scale = (stack.ambient_n / s.n) * (stack.ambient_n / s.n);
    draw.factor = length * weight * std::exp(-sigma * draw.t) / draw.u.z * scale * w.z * bin.solid_angle /
                  bin.projected_solid_angle * cone_weight * settings.chain_connection_weight;
    draw.ok = true;
    return draw;
}

// Next-event estimation through a flake on the flight ahead (last_flake.h):
// per cone, a point uniform on the flight (t in [0, length), weight length),
// a direction w uniform in the cone (u in the slice), the flake normal h that
// mirrors v into u, and per kind the kernel A R(|v.h|) D(h) rho / 4 (rho from
// a flake of the tile's law drawn through the point, 0 if one of the path's
// earlier legs crosses it), times the flight's transmittance e^(-sigma t) and
// the straight one from the point to the ambient, with eachCone's factors.
// Russian roulette below settings.roulette_weight (per sr) on the value at
// rho = 1, before the flake is drawn and traced (a layer's first 4 kinds).
// A flight runs it with probability p = min(1, length / settings.chain_length_um),
// weighted 1 / p (chain_length_rate.h).
void Walker::lastFlakeConnections(const Slice& s, const LayerFlakes& lf, double length, double sigma) {
    if (!(length > 0.0) || bins.empty()) return;
    PathRng& chain_rng = chainRng();
    const double p_length = chainLengthProbability(length, settings.chain_length_um);
    std::array<double, kChainLengths> p_candidates{};  // p_i of each candidate L_i
    if (length_learning != nullptr)
        for (std::size_t i = 0; i < kChainLengths; ++i) {
            p_candidates[i] = chainLengthProbability(length, kChainLengthsUm[i]);
            length_learning->connections[i] += p_candidates[i];
        }
    if (p_length < 1.0 && chain_rng.uniform() >= p_length) return;
    const std::int64_t rays_before = tally.rays;
    const std::int64_t attempts_before = tally.nee_attempts;
    const ConeScore score = lastFlakeConnection(s, lf, length, sigma, p_length, chain_rng);
    if (length_learning != nullptr) {
        length_learning->steps += 2.0 * static_cast<double>(tally.nee_attempts - attempts_before) +
                                  static_cast<double>(tally.rays - rays_before);
        length_learning->connected += 1.0;
        if (score.value > 0.0) learnChainLength(score, p_candidates, p_length);
    }
}

void Walker::learnChainLength(const ConeScore& score, const std::array<double, kChainLengths>& p_candidates,
                              double p_length) {
    // X (score_x): the score before 1 / p_length and the chain share's weight.
    const double score_x = score.value * p_length / settings.chain_connection_weight;
    const std::size_t cones = bins.size();
    ChainLengthLearning& learned = *length_learning;
    if (learned.m2.size() < kChainLengths * cones) {
        learned.m2.resize(kChainLengths * cones, 0.0);
        learned.max2.resize(kChainLengths * cones, 0.0);
        learned.excess.resize(cones, 0.0);
    }
    for (std::size_t i = 0; i < kChainLengths; ++i) {
        const double added = score_x * score_x * (1.0 / p_candidates[i] - 1.0);
        learned.m2[i * cones + score.k] += added / p_length;
        learned.max2[i * cones + score.k] = std::max(learned.max2[i * cones + score.k], added);
    }
    learned.excess[score.k] += score_x * score_x * (1.0 / p_length - 1.0) / p_length;
}

Walker::ConeScore Walker::lastFlakeConnection(const Slice& s, const LayerFlakes& lf, double length,
                                              double sigma, double p_length, PathRng& chain_rng) {
    const LastFlakeLaw& law = *lf.last_flake;
    const std::size_t kinds = std::min(law.kinds.size(), lf.kinds.size());
    std::array<double, kMaxKernelCones> cone_p{};
    const bool weighted = settings.kernel_chain_cones && kernelConeProbabilities(s, lf, cone_p);
    const ChainDraw draw = drawChainCone(s, length, sigma, chain_rng,
                                         weighted ? std::span<const double>(cone_p.data(), bins.size())
                                                  : std::span<const double>{});
    if (!draw.ok) return {};
    const std::size_t k = draw.k;
    const double t = draw.t;
    const Vec3 u = draw.u;
    Vec3 h{u.x - v.x, u.y - v.y, u.z - v.z};
    const double len = std::sqrt(dot(h, h));
    if (len < 1e-12) return {};
    h = {h.x / len, h.y / len, h.z / len};
    const double cos_vh = std::abs(dot(v, h));
    const double point_depth = draw.point_depth;
    const Vec3 point{ux + v.x * t, uy + v.y * t, -point_depth};
    const double factor = draw.factor / p_length;
    // The kernel per kind before rho: A R D / 4.
    const ChainKernel kernels = chainKernel(lf, h, cos_vh, 0.25, factor, chain_rng);
    if (!(kernels.q > 0.0)) return {};
    const double q = kernels.q;
    const auto& per_kind = kernels.per_kind;
    double kernel = 0.0;
    for (std::size_t i = 0; i < kinds && i < per_kind.size(); ++i) {
        if (!(per_kind[i] > 0.0)) continue;
        const VirtualFlake flake = drawVirtualFlake(law, i, h, point_depth, chain_rng);
        if (!(flake.rho > 0.0)) continue;
        const Vec3 centre{point.x + flake.centre_offset.x, point.y + flake.centre_offset.y,
                          point.z + flake.centre_offset.z};
        const double T_legs = legsTransmittance(centre, h, flake.radius_um, lf.kinds[i], law);
        if (!(T_legs > 0.0)) continue;
        kernel += per_kind[i] * flake.rho * T_legs;
    }
    if (!(kernel > 0.0)) return {};
    const double value =
        kernel * factor / q *
        straightToAmbient(stack, explicit_flakes, j, point_depth, x + v.x * t, y + v.y * t, u, &tally.rays);
    chainOut()[k] += value;
    return {k, value};
}

double Walker::legsTransmittance(const Vec3& centre, const Vec3& n, double radius_um, const FlakeKind& kind,
                                 const LastFlakeLaw& law) const {
    double T = 1.0;
    const int stored = std::min(vertex_count, kLegVertices);
    const auto side = [&](const Vec3& p) { return dot(n, {p.x - centre.x, p.y - centre.y, p.z - centre.z}); };
    double sb =
        stored > 0 ? side(vertices[static_cast<std::size_t>((vertex_count - stored) % kLegVertices)]) : 0.0;
    for (int i = vertex_count - stored; i + 1 < vertex_count; ++i) {
        const Vec3& a = vertices[static_cast<std::size_t>(i % kLegVertices)];
        const Vec3& b = vertices[static_cast<std::size_t>((i + 1) % kLegVertices)];
        const double sa = sb;  // each vertex's side once, for the leg before it and the one after
        sb = side(b);
        if (!(sa * sb < 0.0)) continue;
        const double f = sa / (sa - sb);
        const Vec3 p{a.x + f * (b.x - a.x) - centre.x, a.y + f * (b.y - a.y) - centre.y,
                     a.z + f * (b.z - a.z) - centre.z};
        const double p_depth = -(centre.z + p.z);
        if (p_depth < law.top_um || p_depth > law.bottom_um) continue;
        if (!(dot(p, p) < radius_um * radius_um)) continue;
        const Vec3 leg{b.x - a.x, b.y - a.y, b.z - a.z};
        T *= kind.T(std::abs(sa - sb) / std::sqrt(dot(leg, leg)));  // |cos| of the leg on c
        if (!(T > 0.0)) return 0.0;
    }
    return T;
}

void Walker::reverseFromPigment(const Slice& s, double sigma) {
    if (s.sigma_s_per_um > 0.0) {
        const double q = std::min(1.0, s.sigma_s_per_um / sigma);
        if (connection_rng->uniform() < q) {
            reverseNextEvent(s, [&](const Vec3& u) { return weight * s.kernel(v, u) / (sigma * q * u.z); });
            if (settings.reflected_beams || settings.top_images)
                reverseReflectedBeams(s, weight / (sigma * q));
        }
    }
}

void Walker::reverseFromLambert(const Slice& s) {
    reverseNextEvent(s, [&](const Vec3& u) { return substrateEmitted(u); });
}

bool Walker::headsIntoCone() const {
    const double ratio = stack.slices[j].n / stack.ambient_n;
    const double wx = v.x * ratio;
    const double wy = v.y * ratio;
    const double lateral = wx * wx + wy * wy;
    if (!(lateral < 1.0)) return false;
    const Vec3 w{wx, wy, std::sqrt(1.0 - lateral)};
    return std::any_of(bins.begin(), bins.end(),
                       [&w](const HistogramBin& bin) { return dot(w, bin.wo) >= bin.cos_cone; });
}

}  // namespace paintlab::mc
