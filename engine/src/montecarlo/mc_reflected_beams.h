#pragma once
// The beam's mirror images off the explicit flakes of a layer, seen from a
// point in it (reverse walks and forward flake images, mc_walk.h): a spatial
// search of the tile's flakes whose reflected column holds the point.

#include "mc_connection.h"
#include "mc_glints.h"
#include "mc_stack.h"

#include <cstddef>
#include <cstdint>
#include <span>

namespace paintlab::mc {

// Reverse walks (mc_walk.h, traceReversePath): the beam reflected once by an
// explicit flake is again a collimated beam (a flat mirror keeps its
// perpendicular flux density, times R), so a pigment vertex in a flake layer is
// lit by the beam directly and by every flake below (or above) whose reflected
// column holds it; a column reflected upwards also comes back down from the
// paint's top (its internal reflection, also flat: times F), and lights the
// vertex from there. For the vertex at (x, y, depth) in slice j, with the
// walk's propagation direction v and the beam's direction beam_top (downward,
// in the top slice), the sum over the flakes of its layer's tile (periodic
// images included) whose column holds the point of:
//  - off_flakes: kernel(v, -r) (r the reflected direction) times the
//    transmittance from the point to the flake (pigments, the flakes crossed)
//    times R(|beam.n|) times the beam's straight transmittance from the
//    ambient down to the flake;
//  - off_flake_then_top: kernel(v, u) (u = r mirrored at the top, reversed)
//    times the transmittance from the point up to the top, F of the top, the
//    transmittance from the top down to the flake, R and the beam's as above.
// The caller's factor for f is that of the direct beam (weight / (sigma q
// |beam_z|) and (n_0 / n)^2). Exhaustive over the tile's flakes (a cheap plane
// test each; the walks reach it rarely, see traceReversePath). Never throws.
struct BeamImages {
    bool off_flakes = true;
    bool off_flake_then_top = true;
};
double reflectedBeams(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                      double depth, double x, double y, const Vec3& v, const Vec3& beam_top,
                      BeamImages images, std::int64_t* rays = nullptr);

}  // namespace paintlab::mc
