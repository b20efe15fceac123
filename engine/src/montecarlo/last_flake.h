#pragma once
// Last-flake connections (McSettings::mirror_chain_connections and
// last_flake_connections, issue 30): the delta-chain walks' (and, for what
// its histogram scores, the forward walk's) escapes whose last direction change is a mirror
// reflection off an explicit flake that the path meets for the first time,
// after at least one earlier change (flake -> the top's internal reflection
// -> flake -> cone, flake -> flake -> cone), scored by next-event estimation
// through a flake drawn on the chain's straight flights instead of waiting
// for a real flake to mirror a flight into a 5 degree cone (silver
// metallic's flop: docs/PERFORMANCE.md, "Full model on every demo paint
// (issue 30)"). The walk still scores the escapes after a flake it met
// before (flake -> flake -> the same flake -> cone, the wedges of
// intersecting flakes; flake -> top -> the same flake -> cone: a third of the
// part at the back-scatter exit of flakes right under the top) and after
// other changes, but for the cavity chains (x c x ..., cavity_chain.h),
// which the cavity connections take with the same law; the first-flake
// walks keep all of theirs. Each flight connects to one cone, on the
// delta walks drawn by its kernel and the cone's need
// (Walker::kernelConeProbabilities), elsewhere uniformly. On by default for layers of mirror flakes (on
// silver metallic the two halved the time to 1 %; alone, before the cavity connections and with all six cones
// per flight, they had made it longer: docs/PERFORMANCE.md has the figures).
//
// What is estimated. The tiles are realisations of a random arrangement of
// flakes (flake_tile.h), and the estimate is over them (the batches' errors
// include their spread). For flakes placed independently with the tile's
// law, Mecke's formula turns the sum over the flakes c of a tile of g(c, tile)
// (the escapes whose last reflection is c) into the integral over a flake c
// drawn from that law, added to an independent tile, of g(c, tile + c). On a
// flight of the walk (no real flake in the way) the flakes a ray meets at
// distance t with normal h per sr have the rate A |v.h| D(h) rho(depth, h)
// (A the layer's mean area density, rho the density of the flakes' surface at
// that depth relative to the mean: 1 inside the layer, lower where a tilted
// flake cannot reach because it is kept inside the film, the depth profile's
// shape elsewhere); mirrored through h, the cone's direction u costs
// dOmega_u = 4 |v.h| dOmega_h, so the connection's kernel is the continuum's,
// A R(|v.h|) D(h) rho / 4 per sr and µm (Slice::kernel), times the straight
// transmittance from the flake to the ambient through the real tiles
// (straightToAmbient). Where one of the path's previous legs crosses c's
// polygon, the path with c in the tile is the branch that passed c there:
// the score carries c's T at each such crossing (0 for a mirror flake:
// Walker::legsTransmittance). A path that reflected off a flake before and
// does again is the walk's part, not this one's (Walker::meetFlake records
// reflections only, and sorts the walk's escapes). Mecke's formula holds for
// each of the two parts alone.
//
// Where the tiles differ from independent flakes, so does this estimate:
// a tile has exactly N flakes (one more than the Palm law's N - 1: a relative
// 1 / N = 5e-5 at 20,000 flakes), Halton-stratified normals (each flake's
// normal still has the law D), the polygon's offsets drawn as the disk's of
// its area, periodic copies of the virtual flake not tested against the legs,
// and with reject_overlaps a hard-core arrangement (the connections are then
// off). A path that meets more than Walker::kLegVertices flakes forgets the
// first ones (weights below R^32). The tests hold it against the walks it
// replaces and the histogram (test_mc_connections.cpp), the fast model in
// the continuum limit (test_explicit_flakes.cpp) and the law against a tile
// (test_last_flake.cpp).

#include "flake_tile.h"
#include "mc_random.h"
#include "mc_stack.h"

#include <vector>

namespace paintlab::mc {

// One layer's flake law as its tiles draw it (FlakeTile's constructor).
struct LastFlakeLaw {
    struct Kind {
        FlakeGeometry geometry;
        double mean_area_um2 = 0.0;  // E[A] of the diameter law
        double profile_mean = 1.0;   // integral of the depth profile's weight over [0, 1]
    };
    std::vector<Kind> kinds;  // in the tile's kind order (LayerFlakes::kinds)
    double top_um = 0.0;
    double bottom_um = 0.0;
    double circumradius_factor = 1.0;  // flakeCircumradiusFactor of the tile's polygons
};
LastFlakeLaw lastFlakeLaw(const std::vector<FlakeGeometry>& kinds, double top_um, double bottom_um,
                          int polygon_sides);

// A flake of kind k drawn to pass through the point at `depth` (µm) with unit
// normal h (either sign): its diameter from the law (weighted by its area
// over the mean's), the point uniform on it (as the disk of its area), so
// its centre is the point minus that offset; `rho` is an unbiased estimate
// of the relative surface density at that depth and normal (0 where no
// centre can lie: the tile keeps a flake of circumradius r and tilt theta
// r sin(theta) inside the layer when the layer is thicker than twice that).
struct VirtualFlake {
    double rho = 0.0;
    Vec3 centre_offset;  // centre minus the point (µm; z up)
    double radius_um = 0.0;
};
VirtualFlake drawVirtualFlake(const LastFlakeLaw& law, std::size_t kind, const Vec3& h, double depth,
                              PathRng& rng);

}  // namespace paintlab::mc
