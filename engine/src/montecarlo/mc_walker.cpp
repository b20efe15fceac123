#include "mc_walker.h"

#include "mc_bottom.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kPi = std::numbers::pi;

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

}  // namespace

void Walker::runBranch(double factor) {
    Walker branch = *this;
    branch.weight *= factor;
    branch.tally = {};
    const double escaped = branch.roulette() && branch.promiseRoulette() ? branch.run() : 0.0;
    tally.escaped_extra += escaped + branch.tally.escaped_extra;
    tally.transmitted += branch.tally.transmitted;
    tally.events += branch.tally.events;
    tally.rays += branch.tally.rays;
    tally.nee_rays += branch.tally.nee_rays;
    tally.nee_attempts += branch.tally.nee_attempts;
    tally.image_calls += branch.tally.image_calls;
    tally.image_rays += branch.tally.image_rays;
    tally.reverse_score += branch.tally.reverse_score;
}

double Walker::run() {
    const std::size_t count = stack.slices.size();
    for (int event = 0; event < settings.max_events; ++event) {
        ++tally.events;
        const Slice& s = stack.slices[j];
        const double abs_cos = std::abs(v.z);
        if (abs_cos < 1e-12) return 0.0;  // exactly grazing: never reaches a boundary
        double flake_rate = 0.0;
        for (std::size_t k = 0; k < s.flakes.size(); ++k) flake_rate += s.flakeRate(k, abs_cos);
        const double sigma = s.sigma_a_per_um + s.sigma_s_per_um + flake_rate;
        const double to_boundary = (v.z < 0.0 ? s.bottom_um - depth : depth - s.top_um) / abs_cos;
        const double t = sigma > 0.0 && mode != Mode::DeltaChain ? -std::log1p(-rng.uniform()) / sigma
                                                                 : std::numeric_limits<double>::infinity();
        // Free paths are memoryless: after a flake or a wrap, a new one is drawn.
        const int tile = traceTile(s, sigma, t, to_boundary);
        if (tile < 0) return 0.0;
        if (tile > 0) continue;
        if (mode == Mode::DeltaChain) {
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
                    tally.escaped_extra += weight;
                    v = inside;
                    weight = w;
                }
                if (!(F > 0.0)) return 0.0;
                weight *= F;
                v.z = -v.z;
                history.deltaChange(true);
                changedAtVertex();
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

bool Walker::roulette() {
    if (weight >= settings.roulette_weight) return true;
    if (weight <= 0.0 || rng.uniform() >= weight / settings.roulette_weight) return false;
    weight = settings.roulette_weight;
    return true;
}

bool Walker::promiseRoulette() {
    const ChainPromise* promise = settings.chain_promise;
    if (promise == nullptr || mode != Mode::DeltaChain || history.path_class == PathClass::Beam ||
        !(promise_weight > 0.0))
        return true;
    const double q =
        std::clamp(weight * promise->at(v, beam_x, beam_y) / promise_weight, settings.promise_floor, 1.0);
    if (q >= 1.0 || (v.z > 0.0 && headsIntoCone())) return true;
    if (rng.uniform() >= q) return false;
    weight /= q;
    return true;
}

int Walker::traceTile(const Slice& s, double sigma, double t, double to_boundary) {
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
    ++tally.rays;
    if (chainRecording() && chain_connections && lf.last_flake != nullptr &&
        (mode != Mode::DeltaChain || settings.delta_chain_connections)) {
        const double flight = hit.kind >= 0 ? hit.t : t_far;
        // The forward walk's flight ends at its sampled collision: the
        // connections on it need no e^(-sigma t) (a track-length estimate).
        const double sigma_flight = mode == Mode::DeltaChain ? sigma : 0.0;
        if (lf.last_flake_connections && history.path_class != PathClass::Beam &&
            (mode == Mode::DeltaChain || forwardScoresAfter(s.layer, 1)))
            lastFlakeConnections(s, lf, flight, sigma_flight);
        if (lf.cavity_connections && change_count > 0 && changeBack(0).chain.flake_id >= 0 &&
            changeBack(0).chain.flake_id % 64 == s.layer &&
            (mode == Mode::DeltaChain || forwardScoresAfter(s.layer, 2)))
            cavityConnections(s, lf, flight, sigma_flight);
    }
    if (hit.kind >= 0) {
        move(hit.t);
        depth = std::clamp(depth - v.z * hit.t, s.top_um, s.bottom_um);
        if (mode == Mode::DeltaChain) weight *= std::exp(-sigma * hit.t);
        return explicitFlakeEvent(lf.kinds[static_cast<std::size_t>(hit.kind)], hit.normal, s.layer,
                                  hit.flake, hit.kind)
                   ? 1
                   : -1;
    }
    if (t_side < t && t_side < to_boundary) {
        move(t_side);
        depth = std::clamp(depth - v.z * t_side, s.top_um, s.bottom_um);
        if (mode == Mode::DeltaChain) weight *= std::exp(-sigma * t_side);
        if (tx <= ty)
            x = v.x > 0.0 ? 0.0 : L;
        else
            y = v.y > 0.0 ? 0.0 : L;
        return 2;
    }
    return 0;
}

bool Walker::explicitFlakeEvent(const FlakeKind& f, const Vec3& n, int layer, std::int64_t flake, int kind) {
    if (history.path_class == PathClass::Beam) history.beam_flake_layer = layer;
    // The last-flake connections take the escapes after a reflection off a flake
    // reflected off for the first time whose orientation law has a density (not
    // the delta); the walk keeps the others (escape, last_flake.h). Passing a
    // flake is not meeting it: the connections weigh such a flake by its T.
    const auto reflected_layer = [&] {
        const bool met_before = chainRecording() && flake >= 0 && meetFlake(layer, flake);
        return f.orientation.isDelta() || met_before ? -1 : layer;
    };
    const std::int64_t flake_id = flake >= 0 ? flake * 64 + layer : -1;
    const double vn = dot(v, n);
    const double c = std::abs(vn);
    const double R = f.R(c);
    if (mode == Mode::DeltaChain && settings.skip_beam_flake_reflections &&
        history.path_class == PathClass::Beam) {
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
        history.flakeReflection(layer);
        changedAtVertex(reflected_layer(), flake_id, n, kind);
        return roulette() && promiseRoulette();
    }
    const double u = rng.uniform();
    if (u < R) {
        v = {v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
        history.flakeReflection(layer);
        changedAtVertex(reflected_layer(), flake_id, n, kind);
        return roulette() && promiseRoulette();
    }
    return u < R + f.T(c);
}

bool Walker::flakeEvent(const FlakeKind& f) {
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
            history.deltaChange(false);  // not a tile's flake: never a flake image's end
        else
            history.smoothChange();
        changedAtVertex();
        return true;
    }
    return u < R + T;  // transmitted light goes straight on
}

bool Walker::collide(const Slice& s, double sigma, double flake_rate) {
    // Reverse walk: a smooth first change belongs to the forward connections (the
    // path reversed ends at a smooth vertex); tiled layers have no continuum flakes,
    // so every collision here scatters off a pigment.
    if (mode == Mode::Reverse) {
        if (history.path_class == PathClass::Beam) return false;
        reverseFromPigment(s, sigma);
    }
    scoreCollision(s, sigma);
    connectFromPigment(s, sigma);
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
        v = directionAround(v, sampleHgCos(g, rng.uniform()), 2.0 * kPi * rng.uniform());
        history.pigmentScatter(s.layer, tiled(s.layer));
        changedAtVertex();
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

bool Walker::crossInterface(double n_from, double n_to, bool top) {
    if (std::abs(n_from - n_to) < 1e-12) return true;
    if (rng.uniform() < fresnelDielectric(std::abs(v.z), n_to / n_from)) {
        v.z = -v.z;
        history.deltaChange(top);
        changedAtVertex();
        return false;
    }
    v = refract(v, n_from, n_to);
    if (chainRecording()) markVertex();  // the leg bends; the class stays
    return true;
}

bool Walker::substrate(const Slice& s) {
    switch (stack.substrate) {
    case SubstrateKind::Black:
        return false;
    case SubstrateKind::Lambertian:
    case SubstrateKind::Operator: {
        // A smooth vertex: the Lambertian, or the flake-free bottom whose
        // direction is drawn from its operator with the weight f cos / pdf.
        if (mode == Mode::DeltaChain) return false;
        if (mode == Mode::Reverse) {
            if (history.path_class == PathClass::Beam) return false;
            reverseFromLambert(s);
        }
        scoreLambert(s);
        history.smoothChange();
        changedAtVertex();
        if (stack.substrate == SubstrateKind::Operator) {
            double factor = 0.0;
            v = stack.bottom->sample(v, rng, factor);
            weight *= factor;
            return roulette();
        }
        weight *= stack.lambert_albedo;
        const double u1 = rng.uniform();
        const double phi = 2.0 * kPi * rng.uniform();
        const double r = std::sqrt(u1);
        v = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
        return roulette();
    }
    case SubstrateKind::Metal:
        weight *= stack.substrateMirrorReflectance(std::abs(v.z));
        v.z = -v.z;
        history.deltaChange(false);
        changedAtVertex();
        return roulette();
    case SubstrateKind::Transparent:
        if (rng.uniform() < fresnelDielectric(std::abs(v.z), stack.below_n / s.n)) {
            v.z = -v.z;
            history.deltaChange(false);
            changedAtVertex();
            return true;
        }
        // += : split branches of this path may already have transmitted (runBranch).
        tally.transmitted += weight;
        return false;
    }
    return false;
}

}  // namespace paintlab::mc
