#pragma once
// Cavity connections (McSettings::cavity_connections, issue 30): the
// delta-chain walks' escapes in which light caught between two flakes
// leaves the way it came. With c the last flake the chain met for the first
// time and x_1, x_2, ... the flake reflections just before it (x_1 the
// latest), the chain ends
//   x_m ... x_2 x_1 c (x_1 c)^j x_1 x_2 ... x_m -> cone,   j >= 0, m >= 1:
// j round trips between c and x_1, then back over x_2 ... x_m (m = 1, j = 0
// is x c x: back to the flake it came from), or, m = 0, j >= 1, at c itself:
//   x_1 c (x_1 c)^j -> cone.
// On silver metallic these were most of the flop's error once the
// last-flake connections took the chains whose last flake is met once
// (docs/PERFORMANCE.md).
//
// Planar mirrors make the exit direction a function of the normals alone:
// u = Q (M_1 M_h)^(j+1) d, with d the flight's direction towards c, M_v the
// mirror through the plane normal to v, M_1 = M_{n(x_1)}, h c's normal and
// Q = M_m ... M_2 fixed by the path so far (Q = M_1 when the chain ends at
// c, m = 0: M_1 u = (M_1 M_h)^(j+1) d). M_1 M_h turns about the axis
// e = n_1 x h / |n_1 x h| by twice the angle between n_1 and h, so its power
// k = j + 1 takes d to Q^T u only about the e normal to both n_1 and
// Q^T u - d, and h = n_1 turned about that e by (phi + 2 pi i) / (2k) for
// the angle phi from d to Q^T u: k normals at most (cavityNormals). The
// connection draws c on the flight with the tiles' law (last_flake.h:
// Mecke's formula, its kernel A |d.h| D(h) rho per µm and sr of h), so per
// sr of u the kernel is A |d.h| D(h) rho / J, J = dOmega_u / dOmega_h
// (4 |d.h| at k = 1, where it is the last-flake connection's; in closed
// form at every k: cavityJacobian), times the reflectances and extinction
// along the chain, whose legs are traced through the real tile and the
// drawn c (Walker::cavityConnections).

#include "mc_stack.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

// The round trips (j) and the flakes gone back over (m) that the connections
// take; the walk keeps longer chains. Every flight runs the chains with
// j <= cavityEveryFlightTrips and 1 <= m <= kCavityEveryFlightRetrace (the
// commonest: x c x, x' x c x x'); the others (round trips, more flakes, or
// ending at c) are rarer and each costs up to j + 1 normals, so a flight
// runs one of them, drawn uniformly and weighted by their count (the delta
// walks: by learned weights, below), where the layer runs the drawn chains
// (McSettings::cavity_forms: by default in mirror-flake layers).
inline constexpr int kMaxCavityRoundTrips = 3;
inline constexpr int kMaxCavityRetrace = 4;
inline constexpr int kCavityEveryFlightRetrace = 2;
// One round trip is drawn with the others where the layer draws chains
// (silver metallic ~10 % faster to 1 % than with it on every flight) and
// runs on every flight elsewhere (interference flakes, where without it
// the walks score it: the pearlescent ~15 % slower; docs/PERFORMANCE.md).
inline constexpr int cavityEveryFlightTrips(bool draws_in_layer) { return draws_in_layer ? 0 : 1; }
// The delta walks draw their drawn chain in proportion to learned weights
// (JobRunner::learnCavityFormWeights) mixed with this share of the uniform
// draw, so that every form keeps a chance and the estimate stays unbiased.
inline constexpr double kUniformFormShare = 0.25;
// A form's slot in the learned weights (CavityFormWeights): m (kMaxCavityRoundTrips + 1) + j.
inline constexpr std::size_t kCavityFormSlots =
    static_cast<std::size_t>(kMaxCavityRetrace + 1) * (kMaxCavityRoundTrips + 1);
inline constexpr std::size_t cavityFormSlot(int trips, int retrace) {
    return static_cast<std::size_t>(retrace) * (kMaxCavityRoundTrips + 1) + static_cast<std::size_t>(trips);
}
// The drawn chains' draw: per slot a weight (each flight draws among the
// forms it can run, in proportion, mixed with the uniform draw); and what
// the walks learn for it: per slot and cone k the sum of X^2 / p over the
// draws (X a drawn chain's score before the draw's weight 1 / p and the
// chain share's, [slot * cones + k], sized by the first draw), and per
// slot the flights that could draw it. For the rate q of the flights that
// run the drawn chain (ConeRates::drawn_chain_rate), per cone k over the
// flights that ran one, Y = X / p the flight's drawn score before the
// weights 1 / q and the chain share's: the sums of Y^2 / q (so their mean
// per walk is E[sum over its flights of Y^2] at q = 1), of Y^2 (1 - q) / q^2
// (what the rate added to the walks' C^2), the largest Y^2; and the
// drawn chains' work in walk steps (two per normal tried, as the other
// connections'), as run and divided by q (the work at q = 1).
using CavityFormWeights = std::array<double, kCavityFormSlots>;
struct CavityFormLearning {
    std::vector<double> m2_over_p;
    CavityFormWeights available{};
    std::vector<double> drawn_s1;  // the sum of Y / q (per walk: its drawn part)
    std::vector<double> drawn_s2;
    std::vector<double> drawn_excess;
    std::vector<double> drawn_max2;
    double drawn_steps = 0.0;
    double drawn_steps_at_one = 0.0;
    void add(const CavityFormLearning& other);
};

// v mirrored through the plane with unit normal n.
inline Vec3 mirrored(const Vec3& v, const Vec3& n) {
    const double vn = dot(v, n);
    return {v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
}

// (M_n M_h)^k d: k round trips of d between the flakes of normals h and n, h first.
Vec3 cavityExit(const Vec3& d, const Vec3& n, const Vec3& h, int k);

// J = dOmega_u / dOmega_h at the normal h = n turned about the unit e
// (normal to n) by theta (its cosine and sine given), for u =
// cavityExit(d, n, h, k): k round trips turn d about e by -2 k theta
// (4 |d.h| at k = 1).
double cavityJacobian(const Vec3& n, const Vec3& e, double theta, double cos_theta, double sin_theta, int k,
                      const Vec3& u);

// The normals h (upper hemisphere) with cavityExit(d, n, h, k) = target, each
// with J = dOmega_exit / dOmega_h; returns how many (at most k, k <= kMaxCavityRoundTrips + 1).
struct CavityNormal {
    Vec3 h;
    double jacobian = 0.0;
};
using CavityNormals = std::array<CavityNormal, kMaxCavityRoundTrips + 1>;
int cavityNormals(const Vec3& d, const Vec3& n, const Vec3& target, int k, CavityNormals& out);

// What every k shares for one flight d, flake x_1 of normal n and target:
// the turn's axis e, e x n, and the cosine and sine of the angle phi from d
// to the target about e (phi itself, an atan2, only where k > 1 needs it).
// cavityTurn: false where no axis exists (then there are no normals).
struct CavityTurn {
    Vec3 e;
    Vec3 en;
    double cos_phi = 1.0;
    double sin_phi = 0.0;
    double phi() const { return std::atan2(sin_phi, cos_phi); }
};
bool cavityTurn(const Vec3& d, const Vec3& n, const Vec3& target, CavityTurn& out);
// k = 1 without the turn: M_h d = M_n target, so h is the half vector of d
// and M_n target, J = 4 |d.h| (cavityNormals' one normal, up to rounding);
// false where d = M_n target (no reflection turns d into itself).
bool oneTripNormal(const Vec3& d, const Vec3& n, const Vec3& target, CavityNormal& out);
int cavityNormals(const CavityTurn& turn, const Vec3& d, const Vec3& n, const Vec3& target, int k,
                  CavityNormals& out);

// The walk's side: a direction change of the path (latest first in the
// spans below): the flake reflected (flake * 64 + layer; -1 another change)
// and whether it was the first meeting of a flake whose law has a density.
struct ChainChange {
    std::int64_t flake_id = -1;
    bool first_meeting = false;
};
// Whether the changes so far (latest first; every change the ring still
// holds) end in a cavity chain with j <= kMaxCavityRoundTrips and
// m <= kMaxCavityRetrace (m = 0: at c, j >= 1), all of its flakes in one
// layer: that chain (layer -1: none).
struct CavityForm {
    int layer = -1;   // -1: no cavity chain
    int trips = 0;    // j
    int retrace = 0;  // m (0: ending at c)
    // Whether a flight runs this chain only when it is drawn (the limits above;
    // draws_in_layer: LayerFlakes::draws_cavity_chains of its layer).
    bool drawn(bool draws_in_layer) const {
        return retrace == 0 || trips > cavityEveryFlightTrips(draws_in_layer) ||
               retrace > kCavityEveryFlightRetrace;
    }
};
CavityForm cavityChainForm(std::span<const ChainChange> latest_first);

// Whether the connections take a matched chain (McSettings::cavity_forms):
// a drawn one (drawn by its layer's kind, LayerFlakes::draws_cavity_chains)
// only where its layer runs the drawn chains (drawn_run).
inline bool cavityFormTaken(const CavityForms& forms, const CavityForm& form, bool draws_in_layer,
                            bool drawn_run) {
    return form.layer >= 0 && (form.drawn(draws_in_layer) ? drawn_run : forms.every_flight);
}

}  // namespace paintlab::mc
