#include "mc_walk.h"

#include "first_flake.h"

#include "paintlab/engine/fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kPi = std::numbers::pi;

// Orthonormal basis around a unit vector (Duff et al., JCGT 2017).
void basis(const Vec3& n, Vec3& b1, Vec3& b2) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    b1 = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    b2 = {b, sign + n.y * n.y * a, -n.y};
}

Vec3 around(const Vec3& axis, double cos_theta, double phi) {
    Vec3 b1;
    Vec3 b2;
    basis(axis, b1, b2);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double cx = sin_theta * std::cos(phi);
    const double cy = sin_theta * std::sin(phi);
    return {cx * b1.x + cy * b2.x + cos_theta * axis.x, cx * b1.y + cy * b2.y + cos_theta * axis.y,
            cx * b1.z + cy * b2.z + cos_theta * axis.z};
}

// Inverse-CDF sample of the Henyey-Greenstein cosine (e.g. pbrt-v4, SampleHenyeyGreenstein).
double sampleHgCos(double g, double u) {
    if (std::abs(g) < 1e-3) return 1.0 - 2.0 * u;
    const double q = (1.0 - g * g) / (1.0 + g - 2.0 * g * u);
    return std::clamp((1.0 + g * g - q * q) / (2.0 * g), -1.0, 1.0);
}

// Snell at a planar interface (called when Fresnel let the ray through, so never beyond the critical angle).
Vec3 refract(const Vec3& v, double n_from, double n_to) {
    Vec3 out;
    if (!refractPlanar(v, n_from, n_to, out)) out = {v.x * n_from / n_to, v.y * n_from / n_to, 0.0};
    return out;
}

struct Walker {
    const PaintStack& stack;
    std::span<const ExitChain> chains;
    std::span<const HistogramBin> bins;
    std::span<const LayerFlakes> explicit_flakes;
    const FourierCells* fourier;
    PathRng& rng;
    PathRng* connection_rng;  // non-null: connections on
    const WalkSettings& settings;
    std::span<double> brdf_out;
    Vec3 v;
    double weight;
    double x = 0.0;  // lateral position (µm), only used with explicit flakes
    double y = 0.0;
    std::size_t j = 0;   // slice
    double depth = 0.0;  // µm below the top of the paint
    double transmitted = 0.0;
    unsigned path_class = kClassBeam;     // what the last direction change was (mc_connection.h)
    std::span<const double> nee_weights;  // per bin (empty: settings.connection_weight)
    std::span<double> nee_out;            // per bin (empty: brdf_out)
    // Per bin, the factor (>= 1) on a pigment collision's chance to run the
    // connections into it (PathContext::nee_boost); empty: 1.
    std::span<const double> nee_boost = {};
    std::int64_t events = 0;
    std::int64_t rays = 0;
    std::int64_t nee_rays = 0;
    std::int64_t nee_attempts = 0;
    std::int64_t image_calls = 0;   // flake-image connections (reflectedBeams) traced
    std::int64_t image_rays = 0;    // their tile intersections and candidate tests
    bool delta_chain = true;        // no smooth vertex yet (WalkSettings::histogram_other)
    bool first_smooth = false;      // the first direction change was a smooth vertex
    int beam_flake_layer = -1;      // layer of the beam's first reflection (class BeamFlake)
    bool prefix_flake = false;      // a pigment vertex right after that reflection, in its layer
    bool flake_then_top = false;    // the last changes: that reflection, then the top's internal one
    bool prefix_flake_top = false;  // a pigment vertex right after both, in the flake's layer
    // How the path ends (histogram_other 32, 64; the forward flake images):
    // 1 the last change was a pigment vertex in the tiled layer end_layer, on a
    // path of part 2 (classTwoPrefixAt); 2 then the internal reflection at the
    // paint's top; 3 after 1, and 4 after 2, a reflection off a flake of
    // end_layer; 0 anything else.
    int end_state = 0;
    int end_layer = -1;
    // Reverse walk (traceReversePath): it enters from the exit cone, and scores
    // next-event estimates towards reverse_target (upward in the top slice, the
    // beam reversed) from its smooth vertices once its first direction change
    // was a delta; a first change at a smooth vertex ends it.
    bool reverse = false;
    Vec3 reverse_target{0.0, 0.0, 1.0};
    double reverse_score = 0.0;
    // Delta-chain walk (traceDeltaChains): no collisions; the extinction of the
    // slices is applied as the weight e^(-sigma t) of the straight flight instead,
    // and a smooth vertex (the Lambertian substrate) ends it.
    bool delta_only = false;
    double promise_weight = 0.0;  // promise_threshold times the start weight
    double beam_x = 1.0;          // the beam's lateral travel direction (the promise's frame)
    double beam_y = 0.0;
    int splits = 0;              // splits above this branch
    double escaped_extra = 0.0;  // what split-off branches carried out through the top

    // Splitting (WalkSettings::split_branches): the same expectation as choosing a
    // branch with its probability, without that choice's noise; it matters for
    // the chains of several delta reflections (class Other), which the choice
    // thins by the product of the flakes' R and the top's F (docs/PERFORMANCE.md).
    bool splitting() const { return settings.split_branches && splits < settings.max_splits; }

    // Follows a copy of this path, its weight times `factor`, to its end, and keeps what it carried.
    void runBranch(double factor) {
        Walker branch = *this;
        branch.weight *= factor;
        branch.transmitted = 0.0;
        branch.escaped_extra = 0.0;
        branch.events = 0;
        branch.rays = 0;
        branch.nee_rays = 0;
        branch.nee_attempts = 0;
        branch.image_calls = 0;
        branch.image_rays = 0;
        branch.reverse_score = 0.0;
        const double escaped = branch.roulette() && branch.promiseRoulette() ? branch.run() : 0.0;
        escaped_extra += escaped + branch.escaped_extra;
        transmitted += branch.transmitted;
        events += branch.events;
        rays += branch.rays;
        nee_rays += branch.nee_rays;
        nee_attempts += branch.nee_attempts;
        image_calls += branch.image_calls;
        image_rays += branch.image_rays;
        reverse_score += branch.reverse_score;
    }

    // A smooth direction change (pigment, Lambertian substrate, continuum flake).
    void smoothChange() {
        if (path_class == kClassBeam) first_smooth = true;
        path_class = kClassSmooth;
        delta_chain = false;
        flake_then_top = false;
        end_state = 0;
    }

    bool tiled(int layer) const {
        return static_cast<std::size_t>(layer) < explicit_flakes.size() &&
               explicit_flakes[static_cast<std::size_t>(layer)].tile != nullptr;
    }

    // Whether a pigment vertex in `layer` now leaves the path in part 2 of
    // class Other's histogram (WalkSettings::histogram_other): its prefix is
    // none of parts 1, 4, 8 and 16, which are fixed at the first smooth vertex.
    bool classTwoPrefixAt(int layer) const {
        if (first_smooth || prefix_flake || prefix_flake_top || path_class == kClassBeam) return false;
        if (!delta_chain) return true;  // an earlier smooth vertex fixed the prefix
        // This vertex would be the first smooth one.
        return !((path_class == kClassBeamFlake || flake_then_top) && layer == beam_flake_layer);
    }

    // A delta direction change other than the beam's first flake reflection;
    // `at_top`: the internal reflection at the paint's top.
    void deltaChange(bool at_top) {
        flake_then_top = at_top && path_class == kClassBeamFlake;
        path_class = kClassOther;
        end_state = at_top && end_state == 1 ? 2 : 0;
    }

    // A mirror reflection off an explicit flake of `layer`: the class after it.
    void flakeReflection(int layer) {
        if (path_class == kClassBeam) {
            path_class = kClassBeamFlake;
            return;
        }
        const int next = layer == end_layer && (end_state == 1 || end_state == 2) ? end_state + 2 : 0;
        deltaChange(false);
        end_state = next;
    }

    void move(double t) {
        x += v.x * t;
        y += v.y * t;
    }

    // Left through the top (v already refracted into the ambient): the
    // histogram bins that contain the exit direction.
    void escape() {
        if ((settings.histogram_classes & path_class) != 0U &&
            (path_class != kClassOther || (settings.histogram_other & (delta_chain        ? 1U
                                                                       : first_smooth     ? 4U
                                                                       : prefix_flake     ? 8U
                                                                       : prefix_flake_top ? 16U
                                                                       : end_state == 3   ? 32U
                                                                       : end_state == 4   ? 64U
                                                                                          : 2U)) != 0U))
            for (std::size_t k = 0; k < bins.size(); ++k)
                if (dot(v, bins[k].wo) >= bins[k].cos_cone)
                    brdf_out[k] += weight / bins[k].projected_solid_angle;
        if (fourier != nullptr) project(*fourier);
    }

    void project(const FourierCells& cells) {
        const double mu = std::clamp(v.z, 0.0, 1.0);
        const double t_out = 1.0 - fresnelDielectric(mu, cells.top_eta);
        if (!(t_out > 0.0)) return;
        const auto it = std::lower_bound(cells.upper_mu.begin(), cells.upper_mu.end(), mu);
        const auto cell =
            std::min(static_cast<std::size_t>(it - cells.upper_mu.begin()), cells.scale.size() - 1);
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

    // An explicit flake hit with unit normal n: reflect, pass or absorb.
    bool explicitFlakeEvent(const FlakeKind& f, const Vec3& n, int layer) {
        if (path_class == kClassBeam) beam_flake_layer = layer;
        const double vn = dot(v, n);
        const double c = std::abs(vn);
        const double R = f.R(c);
        if (delta_only && settings.skip_beam_flake_reflections && path_class == kClassBeam) {
            // The first-flake walks take the reflected branch; only the passed one goes on.
            const double T = f.T(c);
            if (splitting()) {
                ++splits;
                weight *= T;
                return T > 0.0 && roulette();
            }
            return rng.uniform() < T;
        }
        if (splitting()) {
            ++splits;
            const double T = f.T(c);
            if (T > 0.0) runBranch(T);  // passed straight on
            if (!(R > 0.0)) return false;
            weight *= R;
            v = {v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
            flakeReflection(layer);
            return roulette() && promiseRoulette();
        }
        const double u = rng.uniform();
        if (u < R) {
            v = {v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
            flakeReflection(layer);
            return roulette() && promiseRoulette();
        }
        return u < R + f.T(c);
    }

    // Connections into the cones: for each cone this path connects to, a
    // direction w uniform in it (u: refracted into slice s) and score(w, u),
    // the vertex's estimate towards w before the connection weight, the
    // radiance law (n_0 / n)^2 and the cone's factor w_z Omega / Omega_proj.
    // `cone_weight(k)`: this vertex's own factor on cone k's connection (0: none).
    template <class Score, class ConeWeight>
    void eachCone(const Slice& s, const Score& score, const ConeWeight& cone_weight) {
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
    void coneNextEvent(const Slice& s, const Emitted& emitted, const ConeWeight& cone_weight) {
        eachCone(
            s,
            [&](const Vec3& /*w*/, const Vec3& u) {
                const double value = emitted(u);
                if (!(value > 0.0)) return 0.0;
                ++nee_attempts;
                return value * straightToAmbient(stack, explicit_flakes, j, depth, x, y, u, &nee_rays);
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
    void coneFlakeImages(const Slice& s, double factor, const ConeWeight& cone_weight) {
        const double n_top = stack.slices.front().n;
        eachCone(
            s,
            [&](const Vec3& w, const Vec3& u) {
                Vec3 u_top;
                if (!(u.z > 0.0) || !refractPlanar(w, stack.ambient_n, n_top, u_top)) return 0.0;
                ++image_calls;
                return factor / u.z *
                       reflectedBeams(stack, explicit_flakes, j, depth, x, y, v,
                                      {-u_top.x, -u_top.y, -u_top.z}, {true, true}, &image_rays);
            },
            cone_weight);
    }

    // A pigment collision's chance to run cone k's connections: the share
    // q = sigma_s / sigma of the collisions that scatter, times the cone's boost.
    double coneCollisionRate(double q, std::size_t k) const {
        return nee_boost.empty() ? q : std::min(1.0, q * nee_boost[k]);
    }

    // Explicit flakes of the current layer along the free path t (medium) and
    // to_boundary (slice): 1 = a flake was hit and handled, 2 = the ray
    // wrapped at the tile's side, 0 = nothing in the way, -1 = the path ended.
    int traceTile(const Slice& s, double sigma, double t, double to_boundary) {
        if (explicit_flakes.empty()) return 0;
        const LayerFlakes& lf = explicit_flakes[static_cast<std::size_t>(s.layer)];
        if (lf.tile == nullptr) return 0;
        const double L = lf.tile->sideUm();
        // Into [0, L] (a new layer's tile may be smaller); the sides themselves stay,
        // so a ray just wrapped to x = L moving towards -x is not wrapped back.
        if (x < 0.0 || x > L) x -= L * std::floor(x / L);
        if (y < 0.0 || y > L) y -= L * std::floor(y / L);
        const double inf = std::numeric_limits<double>::infinity();
        const double tx = v.x > 0.0 ? (L - x) / v.x : (v.x < 0.0 ? -x / v.x : inf);
        const double ty = v.y > 0.0 ? (L - y) / v.y : (v.y < 0.0 ? -y / v.y : inf);
        const double t_side = std::min(tx, ty);
        const double t_far = std::min({t, to_boundary, t_side});
        const FlakeHit hit = lf.tile->intersect({x, y, -depth}, v, kTileEpsilonUm, t_far);
        ++rays;
        if (hit.kind >= 0) {
            move(hit.t);
            depth = std::clamp(depth - v.z * hit.t, s.top_um, s.bottom_um);
            if (delta_only) weight *= std::exp(-sigma * hit.t);
            return explicitFlakeEvent(lf.kinds[static_cast<std::size_t>(hit.kind)], hit.normal, s.layer) ? 1
                                                                                                         : -1;
        }
        if (t_side < t && t_side < to_boundary) {
            move(t_side);
            depth = std::clamp(depth - v.z * t_side, s.top_um, s.bottom_um);
            if (delta_only) weight *= std::exp(-sigma * t_side);
            if (tx <= ty)
                x = v.x > 0.0 ? 0.0 : L;
            else
                y = v.y > 0.0 ? 0.0 : L;
            return 2;
        }
        return 0;
    }

    // Next-event estimate from a collision in slice j with sampling rate sigma.
    void scoreCollision(const Slice& s, double sigma) {
        for (std::size_t k = 0; k < chains.size(); ++k) {
            const ExitChain& c = chains[k];
            const double mu = c.mu[j];
            if (mu <= 0.0) continue;
            const double e = c.extinction[j];
            double value = 0.0;
            if (c.up[j] > 0.0)
                value += s.kernel(v, c.direction(stack, j, true)) * std::exp(-e * (depth - s.top_um) / mu) *
                         c.up[j];
            if (c.down[j] > 0.0)
                value += s.kernel(v, c.direction(stack, j, false)) *
                         std::exp(-e * (s.bottom_um - depth) / mu) * c.down[j];
            brdf_out[k] += weight * value / (sigma * mu);
        }
    }

    // Whether the exit direction of upward v (in slice j) lies in a cone: n sin(theta) is kept up to the
    // ambient.
    bool headsIntoCone() const {
        const double ratio = stack.slices[j].n / stack.ambient_n;
        const double wx = v.x * ratio;
        const double wy = v.y * ratio;
        const double lateral = wx * wx + wy * wy;
        if (!(lateral < 1.0)) return false;
        const Vec3 w{wx, wy, std::sqrt(1.0 - lateral)};
        return std::any_of(bins.begin(), bins.end(),
                           [&w](const HistogramBin& bin) { return dot(w, bin.wo) >= bin.cos_cone; });
    }

    // Delta-chain walks: the roulette of a new branch by its promise
    // (WalkSettings::chain_promise); the beam's own branches and those that
    // head into a cone always go on. Returns false when the branch ends.
    bool promiseRoulette() {
        const ChainPromise* promise = settings.chain_promise;
        if (promise == nullptr || !delta_only || path_class == kClassBeam || !(promise_weight > 0.0))
            return true;
        const double q =
            std::clamp(weight * promise->at(v, beam_x, beam_y) / promise_weight, settings.promise_floor, 1.0);
        if (q >= 1.0 || (v.z > 0.0 && headsIntoCone())) return true;
        if (rng.uniform() >= q) return false;
        weight /= q;
        return true;
    }

    // Returns false when the path ends.
    bool roulette() {
        if (weight >= settings.roulette_weight) return true;
        if (weight <= 0.0 || rng.uniform() >= weight / settings.roulette_weight) return false;
        weight = settings.roulette_weight;
        return true;
    }

    // A flake collision: sample a normal from D weighted by |v.n| (the flakes a
    // ray meets), then reflect, pass (interference flakes) or absorb.
    bool flakeEvent(const FlakeKind& f) {
        FlakeNormal n = f.orientation.sample(rng.uniform(), rng.uniform());
        if (!f.orientation.isDelta()) {
            for (int tries = 0; tries < 100000; ++tries) {
                if (rng.uniform() < std::abs(v.x * n.x + v.y * n.y + v.z * n.z)) break;
                n = f.orientation.sample(rng.uniform(), rng.uniform());
            }
        }
        const double vn = v.x * n.x + v.y * n.y + v.z * n.z;
        const double c = std::abs(vn);
        const double R = f.R(c);
        const double T = f.T(c);
        const double u = rng.uniform();
        if (u < R) {
            v = {v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
            // A continuum flake's normal is drawn from a density (a smooth vertex), unless D is the delta.
            if (f.orientation.isDelta())
                deltaChange(false);  // not a tile's flake: never a flake image's end
            else
                smoothChange();
            return true;
        }
        return u < R + T;  // transmitted light goes straight on
    }

    // Reverse walk: the next-event estimate towards reverse_target (f at that
    // one direction, as the point estimator: no cone), `emitted(u)` as in coneNextEvent.
    template <class Emitted> void reverseNextEvent(const Slice& s, const Emitted& emitted) {
        Vec3 u;
        if (!refractPlanar(reverse_target, stack.slices.front().n, s.n, u) || !(u.z > 0.0)) return;
        const double value = emitted(u);
        if (!(value > 0.0)) return;
        ++nee_attempts;
        const double scale = (stack.ambient_n / s.n) * (stack.ambient_n / s.n);
        reverse_score +=
            value * straightToAmbient(stack, explicit_flakes, j, depth, x, y, u, &nee_rays) * scale;
    }

    // Reverse walk: the next-event estimates towards the beam's single mirror
    // images off the flakes of this layer, and those off a flake and then the
    // paint's top (mc_connection.h, reflectedBeams), with
    // the direct beam's factors (`factor` = weight / (sigma q), over |beam_z|).
    void reverseReflectedBeams(const Slice& s, double factor) {
        Vec3 beam;
        if (!refractPlanar(reverse_target, stack.slices.front().n, s.n, beam) || !(beam.z > 0.0)) return;
        ++image_calls;
        const double scale = (stack.ambient_n / s.n) * (stack.ambient_n / s.n);
        reverse_score += factor / beam.z * scale *
                         reflectedBeams(stack, explicit_flakes, j, depth, x, y, v,
                                        {-reverse_target.x, -reverse_target.y, -reverse_target.z},
                                        {settings.reflected_beams, settings.top_images}, &image_rays);
    }

    bool collide(const Slice& s, double sigma, double flake_rate) {
        // Reverse walk: a smooth first change belongs to the forward connections (the
        // path reversed ends at a smooth vertex); tiled layers have no continuum flakes,
        // so every collision here scatters off a pigment.
        if (reverse) {
            if (path_class == kClassBeam) return false;
            if (s.sigma_s_per_um > 0.0) {
                const double q = std::min(1.0, s.sigma_s_per_um / sigma);
                if (connection_rng->uniform() < q) {
                    reverseNextEvent(
                        s, [&](const Vec3& u) { return weight * s.kernel(v, u) / (sigma * q * u.z); });
                    if (settings.reflected_beams || settings.top_images)
                        reverseReflectedBeams(s, weight / (sigma * q));
                }
            }
        }
        scoreCollision(s, sigma);
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
            for (std::size_t k = 0; k < nee_boost.size(); ++k)
                q_max = std::max(q_max, coneCollisionRate(q, k));
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
                if (settings.flake_images && u_connect < q && tiled(s.layer) && classTwoPrefixAt(s.layer))
                    coneFlakeImages(s, weight / (sigma * q), [](std::size_t /*k*/) { return 1.0; });
            }
        }
        const double scatter = s.sigma_s_per_um + flake_rate;
        if (!(scatter > 0.0)) return false;  // a pure absorber
        weight *= scatter / sigma;           // absorption by weighting
        double u = rng.uniform() * scatter;
        if (u < s.sigma_s_per_um) {
            double pick = rng.uniform();
            double g = 0.0;
            for (const auto& lobe : s.lobes) {
                g = lobe.g;
                if ((pick -= lobe.weight) < 0.0) break;
            }
            v = around(v, sampleHgCos(g, rng.uniform()), 2.0 * kPi * rng.uniform());
            if (path_class == kClassBeamFlake && s.layer == beam_flake_layer) prefix_flake = true;
            if (flake_then_top && s.layer == beam_flake_layer) prefix_flake_top = true;
            const bool ends = tiled(s.layer) && classTwoPrefixAt(s.layer);
            smoothChange();
            if (ends) {
                end_state = 1;
                end_layer = s.layer;
            }
        } else {
            u -= s.sigma_s_per_um;
            std::size_t k = 0;
            for (; k + 1 < s.flakes.size(); ++k) {
                const double rate = s.flakeRate(k, std::abs(v.z));
                if (u < rate) break;
                u -= rate;
            }
            if (!flakeEvent(s.flakes[k])) return false;
        }
        return roulette();
    }

    // `top`: the paint's top (the ambient beyond).
    bool crossInterface(double n_from, double n_to, bool top) {
        if (std::abs(n_from - n_to) < 1e-12) return true;
        if (rng.uniform() < fresnelDielectric(std::abs(v.z), n_to / n_from)) {
            v.z = -v.z;
            deltaChange(top);
            return false;
        }
        v = refract(v, n_from, n_to);
        return true;
    }

    bool substrate(const Slice& s) {
        switch (stack.substrate) {
        case SubstrateKind::Black:
            return false;
        case SubstrateKind::Lambertian: {
            if (delta_only) return false;
            if (reverse) {
                if (path_class == kClassBeam) return false;
                const double emitted = weight * stack.lambert_albedo / kPi;
                reverseNextEvent(s, [emitted](const Vec3& /*u*/) { return emitted; });
            }
            for (std::size_t k = 0; k < chains.size(); ++k)
                brdf_out[k] += weight * stack.lambert_albedo / kPi * chains[k].lambert;
            if (connection_rng != nullptr && settings.cone_direct) {
                const double emitted = weight * stack.lambert_albedo / kPi;
                coneNextEvent(
                    s, [emitted](const Vec3& /*u*/) { return emitted; },
                    [](std::size_t /*k*/) { return 1.0; });
            }
            weight *= stack.lambert_albedo;
            smoothChange();
            const double u1 = rng.uniform();
            const double phi = 2.0 * kPi * rng.uniform();
            const double r = std::sqrt(u1);
            v = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
            return roulette();
        }
        case SubstrateKind::Metal:
            weight *= stack.substrateMirrorReflectance(std::abs(v.z));
            v.z = -v.z;
            deltaChange(false);
            return roulette();
        case SubstrateKind::Transparent:
            if (rng.uniform() < fresnelDielectric(std::abs(v.z), stack.below_n / s.n)) {
                v.z = -v.z;
                deltaChange(false);
                return true;
            }
            // += : split branches of this path may already have transmitted (runBranch).
            transmitted += weight;
            return false;
        }
        return false;
    }

    // The weight that leaves through the top; 0 when the path is absorbed or lost.
    double run() {
        const std::size_t count = stack.slices.size();
        for (int event = 0; event < settings.max_events; ++event) {
            ++events;
            const Slice& s = stack.slices[j];
            const double abs_cos = std::abs(v.z);
            if (abs_cos < 1e-12) return 0.0;  // exactly grazing: never reaches a boundary
            double flake_rate = 0.0;
            for (std::size_t k = 0; k < s.flakes.size(); ++k) flake_rate += s.flakeRate(k, abs_cos);
            const double sigma = s.sigma_a_per_um + s.sigma_s_per_um + flake_rate;
            const double to_boundary = (v.z < 0.0 ? s.bottom_um - depth : depth - s.top_um) / abs_cos;
            const double t = sigma > 0.0 && !delta_only ? -std::log1p(-rng.uniform()) / sigma
                                                        : std::numeric_limits<double>::infinity();
            // Free paths are memoryless: after a flake or a wrap, a new one is drawn.
            const int tile = traceTile(s, sigma, t, to_boundary);
            if (tile < 0) return 0.0;
            if (tile > 0) continue;
            if (delta_only) {
                weight *= std::exp(-sigma * to_boundary);
                if (!roulette()) return 0.0;
            }
            if (t < to_boundary) {
                move(t);
                depth = std::clamp(depth - v.z * t, s.top_um, s.bottom_um);
                if (!collide(s, sigma, flake_rate)) return 0.0;
                continue;
            }
            move(to_boundary);
            if (v.z < 0.0) {
                depth = s.bottom_um;
                if (j + 1 < count) {
                    if (crossInterface(s.n, stack.slices[j + 1].n, false)) ++j;
                } else if (!substrate(s)) {
                    return 0.0;
                }
            } else {
                depth = s.top_um;
                if (j == 0 && splitting() && std::abs(s.n - stack.ambient_n) >= 1e-12) {
                    // Both branches of the top interface: out with weight 1 - F, back with weight F.
                    ++splits;
                    const double F = fresnelDielectric(std::abs(v.z), stack.ambient_n / s.n);
                    if (F < 1.0) {
                        const Vec3 inside = v;
                        const double w = weight;
                        v = refract(v, s.n, stack.ambient_n);
                        weight = w * (1.0 - F);
                        escape();
                        escaped_extra += weight;
                        v = inside;
                        weight = w;
                    }
                    if (!(F > 0.0)) return 0.0;
                    weight *= F;
                    v.z = -v.z;
                    deltaChange(true);
                    if (!roulette() || !promiseRoulette()) return 0.0;
                    continue;
                }
                if (j == 0) {
                    if (crossInterface(s.n, stack.ambient_n, true)) {
                        escape();
                        return weight;
                    }
                    if (!promiseRoulette()) return 0.0;  // reflected back down
                } else if (crossInterface(s.n, stack.slices[j - 1].n, false)) {
                    --j;
                }
            }
        }
        return 0.0;
    }
};

}  // namespace

PathOutcome tracePath(const PathContext& context, Vec3 v, double weight, double x, double y, PathRng& rng,
                      std::span<double> f_out, PathRng* connection_rng) {
    const bool connect = context.settings.connections && connection_rng != nullptr &&
                         !context.explicit_flakes.empty() && !context.bins.empty();
    Walker walker{context.stack,
                  context.chains,
                  context.bins,
                  context.explicit_flakes,
                  context.fourier,
                  rng,
                  connect ? connection_rng : nullptr,
                  context.settings,
                  f_out,
                  v,
                  weight,
                  x,
                  y,
                  0,
                  0.0,
                  0.0,
                  kClassBeam,
                  context.nee_weights,
                  context.nee_out,
                  context.nee_boost};
    const double escaped = walker.run() + walker.escaped_extra;
    if (connect && !context.glints.empty())
        scoreGlints(context.stack, context.explicit_flakes, context.glints, context.bins,
                    context.settings.connection_weight, *connection_rng, f_out);
    return {escaped,         walker.transmitted,  walker.events,      walker.rays,
            walker.nee_rays, walker.nee_attempts, walker.image_calls, walker.image_rays};
}

namespace {

// What the delta-chain walks score: class Other's chains without a smooth vertex (histogram_other 1).
WalkSettings deltaChainSettings(const WalkSettings& settings) {
    WalkSettings delta = settings;
    delta.histogram_classes = kClassOther;
    delta.histogram_other = 1U;
    return delta;
}

// A walk without collisions (Walker::delta_only) from (x, y, depth) in slice j.
Walker deltaWalker(const PathContext& context, const WalkSettings& settings, PathRng& rng,
                   std::span<double> f_out, const Vec3& v, double weight, double x, double y, std::size_t j,
                   double depth, unsigned path_class) {
    Walker walker{context.stack,
                  {},
                  context.bins,
                  context.explicit_flakes,
                  nullptr,
                  rng,
                  nullptr,
                  settings,
                  f_out,
                  v,
                  weight,
                  x,
                  y,
                  j,
                  depth,
                  0.0,
                  path_class,
                  {},
                  {}};
    walker.delta_only = true;
    return walker;
}

}  // namespace

PathOutcome traceDeltaChains(const PathContext& context, Vec3 v, double weight, double x, double y,
                             PathRng& rng, std::span<double> f_out) {
    const WalkSettings settings = deltaChainSettings(context.settings);
    Walker walker = deltaWalker(context, settings, rng, f_out, v, weight, x, y, 0, 0.0, kClassBeam);
    const double lateral = std::hypot(v.x, v.y);
    if (lateral > 0.0) {
        walker.beam_x = v.x / lateral;
        walker.beam_y = v.y / lateral;
    }
    walker.promise_weight = settings.promise_threshold * weight;
    const double escaped = walker.run() + walker.escaped_extra;
    return {escaped, walker.transmitted, walker.events, walker.rays, 0, 0};
}

PathOutcome traceFromFirstFlake(const PathContext& context, const Vec3& v_top, double weight,
                                const FirstFlakeDraw& draw, PathRng& rng, std::span<double> f_out) {
    if (draw.layer < 0 || static_cast<std::size_t>(draw.layer) >= context.explicit_flakes.size()) return {};
    const PaintStack& stack = context.stack;
    const LayerFlakes& lf = context.explicit_flakes[static_cast<std::size_t>(draw.layer)];
    const PlacedFlake& flake = lf.tile->flakes()[draw.flake];
    const double depth = -draw.point.z;
    const std::size_t j = sliceAt(stack, draw.layer, depth);
    if (j == stack.slices.size()) return {};
    // The beam in slice j: refracted at every index step above it.
    Vec3 v = v_top;
    for (std::size_t i = 0; i < j; ++i) {
        const double n_from = stack.slices[i].n;
        const double n_to = stack.slices[i + 1].n;
        Vec3 below;
        if (std::abs(n_from - n_to) < 1e-12) continue;
        if (!refractPlanar(v, n_from, n_to, below)) return {};
        v = below;
    }
    const double vn = dot(v, flake.normal);
    const double R = lf.kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(vn));
    if (!(R > 0.0) || !(std::abs(v.z) > 1e-12)) return {};
    PathOutcome outcome;
    const double t_in = straightToTop(stack, context.explicit_flakes, j, depth, draw.point.x, draw.point.y,
                                      {-v.x, -v.y, -v.z}, &outcome.rays)
                            .T;
    if (!(t_in > 0.0)) return outcome;
    const double L = lf.tile->sideUm();
    const double start =
        weight * t_in * R * draw.area_over_probability * std::abs(vn) / (L * L * std::abs(v.z));
    WalkSettings settings = deltaChainSettings(context.settings);
    settings.roulette_weight *= draw.natural_over_probability;
    const Vec3 r{v.x - 2.0 * vn * flake.normal.x, v.y - 2.0 * vn * flake.normal.y,
                 v.z - 2.0 * vn * flake.normal.z};
    Walker walker = deltaWalker(context, settings, rng, f_out, r, start, draw.point.x, draw.point.y, j, depth,
                                kClassBeamFlake);
    walker.beam_flake_layer = draw.layer;
    walker.splits = 1;  // as after the uniform walk's split at this flake
    if (!walker.roulette()) return outcome;
    outcome.escaped = walker.run() + walker.escaped_extra;
    outcome.transmitted = walker.transmitted;
    outcome.events = walker.events;
    outcome.rays += walker.rays;
    return outcome;
}

ReverseOutcome traceReversePath(const PathContext& context, Vec3 v, double weight, double x, double y,
                                const Vec3& target, PathRng& rng, PathRng& connection_rng) {
    WalkSettings settings = context.settings;
    settings.histogram_classes = 0;
    Walker walker{context.stack,
                  {},
                  {},
                  context.explicit_flakes,
                  nullptr,
                  rng,
                  &connection_rng,
                  settings,
                  {},
                  v,
                  weight,
                  x,
                  y,
                  0,
                  0.0,
                  0.0,
                  kClassBeam,
                  {},
                  {}};
    walker.reverse = true;
    walker.reverse_target = target;
    walker.run();
    return {walker.reverse_score, walker.events + walker.rays, walker.nee_rays + walker.nee_attempts,
            walker.image_calls, walker.image_rays};
}

}  // namespace paintlab::mc
