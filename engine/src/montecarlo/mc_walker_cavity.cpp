// The delta-chain walks' cavity connections (cavity_chain.h): the draw of a
// flake c on a flight, its normals for each cone, and the chain's legs
// traced through the real tile and c.

#include "last_flake.h"
#include "mc_walker.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

namespace paintlab::mc {

namespace {

// The first t in (kTileEpsilonUm, length] where the ray from o along the unit
// d meets the disk (centre, unit normal n, radius) or one of its eight
// periodic copies at the tile's side L; infinity if none.
double diskHit(const Vec3& o, const Vec3& d, double length, const Vec3& centre, const Vec3& n,
               double radius_um, double L) {
    double best = std::numeric_limits<double>::infinity();
    const double dn = dot(d, n);
    if (std::abs(dn) < 1e-12) return best;
    for (int i = -1; i <= 1; ++i)
        for (int k = -1; k <= 1; ++k) {
            const Vec3 c{centre.x + i * L, centre.y + k * L, centre.z};
            const double t = dot({c.x - o.x, c.y - o.y, c.z - o.z}, n) / dn;
            if (!(t > kTileEpsilonUm) || t > length || t >= best) continue;
            const Vec3 p{o.x + d.x * t - c.x, o.y + d.y * t - c.y, o.z + d.z * t - c.z};
            if (dot(p, p) < radius_um * radius_um) best = t;
        }
    return best;
}

}  // namespace

CavityForm Walker::cavityFormNow() const {
    std::array<ChainChange, kChangeRing> latest_first{};
    const int stored = std::min(change_count, kChangeRing);
    for (int i = 0; i < stored; ++i) latest_first[static_cast<std::size_t>(i)] = changeBack(i).chain;
    return cavityChainForm(
        std::span<const ChainChange>(latest_first.data(), static_cast<std::size_t>(stored)));
}

// One chain to trace: c drawn through the flight's point, the round trips
// and the flakes gone back over (x_1 .. x_m: changeBack(0 .. m - 1)).
struct Walker::CavityLeg {
    Vec3 start;      // c's point on the flight (unwrapped, z = -depth)
    double x = 0.0;  // ... wrapped into the tile
    double y = 0.0;
    Vec3 direction;  // leaving c (M_h v)
    Vec3 h;          // c's normal
    Vec3 centre;     // c's centre (unwrapped)
    double radius_um = 0.0;
    const FlakeKind* kind_c = nullptr;
    int round_trips = 0;  // j
    int retrace = 1;      // m
    double top_um = 0.0;  // the layer's depths
    double bottom_um = 0.0;
};

double Walker::traceCavityChain(const Slice& s, const LayerFlakes& lf, const CavityLeg& leg) const {
    const double L = lf.tile->sideUm();
    Vec3 at = leg.start;
    double wx = leg.x;
    double wy = leg.y;
    Vec3 dir = leg.direction;
    double value = 1.0;
    double tau = 0.0;
    // The flakes met in order: x_1 and c alternately (2j + 1 of them, 2j when
    // the chain ends at c, m = 0), then x_2 .. x_m.
    const int legs = 2 * leg.round_trips + leg.retrace;
    for (int i = 0; i < legs; ++i) {
        const double at_depth = -at.z;
        if (std::abs(dir.z) < 1e-12) return 0.0;
        const double to_side =
            dir.z > 0.0 ? (at_depth - leg.top_um) / dir.z : (leg.bottom_um - at_depth) / -dir.z;
        const double t_c = diskHit(at, dir, to_side, leg.centre, leg.h, leg.radius_um, L);
        const bool to_c = i < 2 * leg.round_trips && i % 2 == 1;
        double t = 0.0;
        Vec3 n;
        double R = 0.0;
        // The real flakes in the way pass the light on with their T (a mirror's 0 ends the chain).
        double T = 1.0;
        if (to_c) {
            if (!std::isfinite(t_c)) return 0.0;  // the light passes c: another chain
            T = tileTransmittance(lf, wx, wy, at_depth, dir, t_c);
            t = t_c;
            n = leg.h;
            R = leg.kind_c->R(std::abs(dot(dir, n)));
        } else {
            const Change& target = changeBack(i < 2 * leg.round_trips + 1 ? 0 : i - 2 * leg.round_trips);
            const TileHit hit =
                targetFlakeAlong(lf, wx, wy, at_depth, dir, to_side, target.chain.flake_id / 64, T);
            if (hit.hit.kind < 0) return 0.0;
            t = hit.hit.t;
            if (t_c < t) T *= leg.kind_c->T(std::abs(dot(dir, leg.h)));  // c in the way
            wx = hit.x;
            wy = hit.y;
            n = target.normal;
            R = lf.kinds[static_cast<std::size_t>(hit.hit.kind)].R(std::abs(dot(dir, n)));
        }
        const double new_depth = std::clamp(at_depth - dir.z * t, leg.top_um, leg.bottom_um);
        tau += layerOpticalDepth(stack, s.layer, at_depth, new_depth, std::abs(dir.z));
        value *= T * R;
        if (!(value > 0.0)) return 0.0;
        at = {at.x + dir.x * t, at.y + dir.y * t, -new_depth};
        dir = mirrored(dir, n);
    }
    // Out: c in the way up to the layer's top passes the light on with its T (the real flakes are
    // straightToAmbient's).
    const double out_depth = -at.z;
    if (!(dir.z > 0.0)) return 0.0;
    if (std::isfinite(
            diskHit(at, dir, (out_depth - leg.top_um) / dir.z, leg.centre, leg.h, leg.radius_um, L)))
        value *= leg.kind_c->T(std::abs(dot(dir, leg.h)));
    if (!(value > 0.0)) return 0.0;
    const std::size_t j_out = sliceAt(stack, s.layer, out_depth);
    if (j_out >= stack.slices.size()) return 0.0;
    return value * std::exp(-tau) * straightToAmbient(stack, explicit_flakes, j_out, out_depth, wx, wy, dir);
}

// For a direction w uniform in the cone (u in the slice), each chain (j, m)
// and each normal h that sends the flight's v to u through it
// (cavityNormals, after undoing the mirrors of x_2 .. x_m, or of x_1 for a
// chain that ends at c), a flake c drawn through a point uniform on the
// flight (last_flake.h's law): per sr of u the kernel A |v.h| D(h) rho R_c / J,
// the flight's factors as the last-flake connections', times the traced
// chain. The chains with j <= cavityEveryFlightTrips and 1 <= m <=
// kCavityEveryFlightRetrace run on every flight; of the others one, drawn
// with probability p by the job's learned weights (CavityFormWeights; the
// forward walks: uniformly) and weighted by 1 / p.
void Walker::cavityConnections(const Slice& s, const LayerFlakes& lf, double length, double sigma) {
    if (!(length > 0.0) || bins.empty()) return;
    // x_1, x_2, ...: the latest changes, reflections off flakes of this layer.
    int available = 0;
    const int stored = std::min(change_count, kChangeRing);
    while (available < kMaxCavityRetrace && available < stored) {
        const Change& before = changeBack(available);
        if (before.chain.flake_id < 0 || before.chain.flake_id % 64 != s.layer || before.kind < 0) break;
        ++available;
    }
    if (available == 0) return;
    PathRng& chain_rng = chainRng();
    const ChainDraw draw = drawChainCone(s, length, sigma, chain_rng);
    if (!draw.ok) return;
    // Every round-trip count run towards one target shares its turn (cavityTurn).
    const Vec3 n_1 = changeBack(0).normal;
    CavityTurn turn;
    if (settings.cavity_forms.every_flight)
        for (int m = 1; m <= std::min(available, kCavityEveryFlightRetrace); ++m) {
            const Vec3 target = cavityTarget(draw.u, m);
            cavityFormConnection(s, lf, draw, {target, {}}, 0, m, 1.0, chain_rng);
            const int trips_max = cavityEveryFlightTrips(lf.draws_cavity_chains);
            if (trips_max > 0 && cavityTurn(v, n_1, target, turn))
                for (int trips = 1; trips <= trips_max; ++trips)
                    cavityFormConnection(s, lf, draw, {target, turn}, trips, m, 1.0, chain_rng);
        }
    if (!lf.drawn_cavity_chains) return;
    // Only a share q of the flights run it, weighted 1 / q (the forms stay
    // taken: the walks never score their escapes).
    const double q = settings.drawn_chain_rate;
    if (q < 1.0 && chain_rng.uniform() >= q) return;
    // The drawn chain, one of the others: ending at c (m = 0, j >= 1),
    // more round trips, or more flakes gone back over.
    std::array<CavityForm, kCavityFormSlots> drawn{};
    int forms = 0;
    for (int m = 0; m <= available; ++m)
        for (int trips = m == 0 ? 1 : 0; trips <= kMaxCavityRoundTrips; ++trips)
            if (const CavityForm form{s.layer, trips, m}; form.drawn(lf.draws_cavity_chains))
                drawn[static_cast<std::size_t>(forms++)] = form;
    if (forms == 0) return;
    // In proportion to the learned weights, mixed with the uniform draw
    // (kUniformFormShare): every form keeps a chance, so the estimate stays
    // unbiased whatever was learned; uniform before any learning and on the
    // forward walks, which learn nothing.
    const CavityFormWeights* weights = settings.cavity_form_weights;
    std::array<double, drawn.size()> p{};
    double total = 0.0;
    const auto weight_of = [weights](const CavityForm& form) {
        return weights != nullptr ? (*weights)[cavityFormSlot(form.trips, form.retrace)] : 0.0;
    };
    for (int i = 0; i < forms; ++i) total += weight_of(drawn[static_cast<std::size_t>(i)]);
    for (int i = 0; i < forms; ++i) {
        const CavityForm& form = drawn[static_cast<std::size_t>(i)];
        const double learned = total > 0.0 ? weight_of(form) / total : 0.0;
        const double uniform = 1.0 / forms;
        p[static_cast<std::size_t>(i)] =
            total > 0.0 ? kUniformFormShare * uniform + (1.0 - kUniformFormShare) * learned : uniform;
    }
    const double u = chain_rng.uniform();
    int chosen = forms - 1;
    double below = 0.0;
    for (int i = 0; i < forms - 1; ++i) {
        below += p[static_cast<std::size_t>(i)];
        if (u < below) {
            chosen = i;
            break;
        }
    }
    const CavityForm& pick = drawn[static_cast<std::size_t>(chosen)];
    const double p_pick = p[static_cast<std::size_t>(chosen)];
    const std::int64_t attempts_before = tally.nee_attempts;
    const Vec3 target = cavityTarget(draw.u, pick.retrace);
    const double score = pick.trips == 0 || cavityTurn(v, n_1, target, turn)
                             ? cavityFormConnection(s, lf, draw, {target, turn}, pick.trips, pick.retrace,
                                                    1.0 / (p_pick * q), chain_rng)
                             : 0.0;
    if (form_learning != nullptr) {
        // Its work is counted here, not among the other connections' attempts
        // (as theirs, two walk steps per normal tried; counting the legs it
        // traces too made silver metallic slower: docs/PERFORMANCE.md).
        const double steps = 2.0 * static_cast<double>(tally.nee_attempts - attempts_before);
        tally.nee_attempts = attempts_before;
        // X = score p_pick q s: the chain's score before the draw's weight, the
        // rate's and the chain share's (which change between rounds); X^2 / p
        // has the mean E[X^2].
        const double unweighted = score * p_pick * q / settings.chain_connection_weight;
        const std::size_t cones = bins.size();
        if (form_learning->m2_over_p.size() < kCavityFormSlots * cones) {
            form_learning->m2_over_p.resize(kCavityFormSlots * cones, 0.0);
            form_learning->drawn_s1.resize(cones, 0.0);
            form_learning->drawn_s2.resize(cones, 0.0);
            form_learning->drawn_excess.resize(cones, 0.0);
            form_learning->drawn_max2.resize(cones, 0.0);
        }
        form_learning->m2_over_p[cavityFormSlot(pick.trips, pick.retrace) * cones + draw.k] +=
            unweighted * unweighted / p_pick;
        const double y2 = unweighted * unweighted / (p_pick * p_pick);
        form_learning->drawn_s1[draw.k] += unweighted / (p_pick * q);
        form_learning->drawn_s2[draw.k] += y2 / q;
        form_learning->drawn_excess[draw.k] += y2 * (1.0 - q) / (q * q);
        form_learning->drawn_max2[draw.k] = std::max(form_learning->drawn_max2[draw.k], y2);
        form_learning->drawn_steps += steps;
        form_learning->drawn_steps_at_one += steps / q;
        for (int i = 0; i < forms; ++i)
            form_learning->available[cavityFormSlot(drawn[static_cast<std::size_t>(i)].trips,
                                                    drawn[static_cast<std::size_t>(i)].retrace)] += 1.0;
    }
}

Vec3 Walker::cavityTarget(const Vec3& u, int m) const {
    // Before the way back over x_m .. x_2 (M_2 ... M_m u), or over x_1 for a chain ending at c (M_1 u).
    if (m == 0) return mirrored(u, changeBack(0).normal);
    Vec3 target = u;
    for (int i = m; i >= 2; --i) target = mirrored(target, changeBack(i - 1).normal);
    return target;
}

double Walker::cavityFormConnection(const Slice& s, const LayerFlakes& lf, const ChainDraw& draw,
                                    const CavityAim& aim, int trips, int m, double form_weight,
                                    PathRng& chain_rng) {
    // No round trip: the half vector (oneTripNormal), no turn needed (aim.turn is unused).
    CavityNormals normals;
    const int count = trips == 0
                          ? (oneTripNormal(v, changeBack(0).normal, aim.target, normals[0]) ? 1 : 0)
                          : cavityNormals(aim.turn, v, changeBack(0).normal, aim.target, trips + 1, normals);
    CavityLeg leg;
    leg.round_trips = trips;
    leg.retrace = m;
    double scored = 0.0;
    for (int c = 0; c < count; ++c)
        scored += cavityNormalScore(s, lf, draw, normals[static_cast<std::size_t>(c)], leg,
                                    draw.factor * form_weight, chain_rng);
    return scored;
}

double Walker::cavityNormalScore(const Slice& s, const LayerFlakes& lf, const ChainDraw& draw,
                                 const CavityNormal& normal, CavityLeg& leg, double factor,
                                 PathRng& chain_rng) {
    const LastFlakeLaw& law = *lf.last_flake;
    const std::size_t kinds = std::min(law.kinds.size(), lf.kinds.size());
    const Vec3& h = normal.h;
    const double cos_vh = std::abs(dot(v, h));
    // The kernel per kind before rho: A R D |v.h| / J.
    const ChainKernel kernels = chainKernel(lf, h, cos_vh, cos_vh / normal.jacobian, factor, chain_rng);
    if (!(kernels.q > 0.0)) return 0.0;
    const auto& per_kind = kernels.per_kind;
    leg.start = {ux + v.x * draw.t, uy + v.y * draw.t, -draw.point_depth};
    leg.x = x + v.x * draw.t;
    leg.y = y + v.y * draw.t;
    leg.direction = mirrored(v, h);
    leg.h = h;
    leg.top_um = law.top_um;
    leg.bottom_um = law.bottom_um;
    double sum = 0.0;
    for (std::size_t i = 0; i < kinds && i < per_kind.size(); ++i) {
        if (!(per_kind[i] > 0.0)) continue;
        const VirtualFlake flake = drawVirtualFlake(law, i, h, draw.point_depth, chain_rng);
        if (!(flake.rho > 0.0)) continue;
        leg.centre = {leg.start.x + flake.centre_offset.x, leg.start.y + flake.centre_offset.y,
                      leg.start.z + flake.centre_offset.z};
        const double T_legs = legsTransmittance(leg.centre, h, flake.radius_um, lf.kinds[i], law);
        if (!(T_legs > 0.0)) continue;
        leg.radius_um = flake.radius_um;
        leg.kind_c = &lf.kinds[i];
        sum += per_kind[i] * flake.rho * T_legs * traceCavityChain(s, lf, leg);
    }
    if (!(sum > 0.0)) return 0.0;
    const double scored = sum * factor / kernels.q;
    chainOut()[draw.k] += scored;
    return scored;
}

}  // namespace paintlab::mc
