#pragma once
// Connections for the explicit-flake histogram estimator (mc_walk.h): the
// path classes whose last direction change is not a delta are scored by
// deterministic connections to the exit cones instead of waiting for the
// path to land in one (docs/PERFORMANCE.md, "Full model", has the error
// budget that motivated them).
//
// A path's class is what happened after its last direction change
// (PathClass); "straight" events do not change it: refraction at a smooth
// interface and the straight-on transmission through an interference flake.
//  - Smooth: the last change was a pigment scattering or the Lambertian
//    substrate. Scored at every such vertex by next-event estimation to a
//    direction drawn uniformly in each cone, along the straight path to the
//    ambient traced through the real flake tiles (a mirror flake stops it,
//    an interference flake passes its T(|u.n|)), the pigments (e^-sigma_t s)
//    and the interfaces (1 - Fresnel each, no internal reflection: those
//    paths are class Other). Weighted by cos w Omega_cone / Omega_proj, its
//    mean is the cone average of f cos over that of cos: the histogram's own
//    definition, not the point value at wo.
//  - BeamFlake: the unscattered beam's first reflection, off a flake of the
//    tile, then straight out. For each cone the flakes whose mirror
//    direction of the beam refracts into the cone are listed per tile
//    (mc_glints.h, GlintSet); each path picks one in proportion to the area of the beam
//    it intercepts (A |v.n| / |v_z| / L^2: the probability that a uniformly
//    placed entry point's beam meets it), a point uniform on its polygon,
//    and scores the straight transmittance of the beam down to that point
//    (entry Fresnel, pigments, the flakes above) times R(|v.n|) times the
//    straight transmittance up and out. Real positions, normals and sizes:
//    every shadowing between flakes is the tile's own. By default the same
//    term is estimated over every azimuth of the tile at once, with
//    importance sampling, independently of the paths (mc_glints.h,
//    AzimuthGlintSet; mc_job_chunks.cpp draws its samples per chunk).
//  - Other (multiple flake reflections, internal Fresnel reflections, metal
//    mirrors) and Beam (a beam never leaves unscattered except by a mirror):
//    the histogram, except three parts of Other that have their own walks
//    (mc_walk.h, default on): the chains without a smooth vertex (delta-chain
//    walks), the paths whose first change was smooth (reverse walks, by
//    reciprocity), and those whose first change was the beam's reflection off
//    a flake followed by a pigment vertex in its layer (reverse walks
//    connecting to the beam's mirror images, mc_reflected_beams.h).
// The histogram then scores Beam and Other escapes only, so every path class
// is counted exactly once. The connections may run on a random share of the
// paths only, their scores divided by it (McSettings::connection_fraction).
//
// Known limit: the glint weight 1 / L^2 assumes the entry points are uniform
// over the flake layer's own tile; with tiles of different sides in several
// layers they are uniform over the largest (mc_engine.cpp), exact when the
// sides are commensurate and for one flaked layer (the demos).

#include "flake_tile.h"
#include "mc_random.h"
#include "mc_stack.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace paintlab::mc {

inline constexpr int kMaxCrossings = 100000;  // safety cap on flakes / wraps along one straight path

// Histogram estimator of f around an exit direction: escaping weight inside
// the cone of half-angle alpha, divided by the cone's projected solid angle
// pi sin^2(alpha) cos(theta_o) (exact for a cone above the horizon),
// estimates the cone average of f cos / the cone average of cos.
struct HistogramBin {
    Vec3 wo;
    double cos_cone = 1.0;
    double projected_solid_angle = 0.0;
    double solid_angle = 0.0;  // 2 pi (1 - cos alpha)
};

// Explicit flakes of one layer: its tile and the optics of its kinds at this
// wavelength, in the tile's kind order.
struct TiltIndex;
struct FlakeGroups;
struct LastFlakeLaw;
struct LayerFlakes {
    const FlakeTile* tile = nullptr;
    std::vector<FlakeKind> kinds;
    const TiltIndex* tilts = nullptr;          // the tile's flakes by tilt (azimuthGlintSets; null: none)
    const FlakeGroups* groups = nullptr;       // by tilt, azimuth and depth (first_flake.h; null: none)
    const LastFlakeLaw* last_flake = nullptr;  // the tiles' law (last_flake.h; null: no chain connections)
    // Which chain connections run in this layer (McSettings; only with a law).
    bool last_flake_connections = false;
    bool cavity_connections = false;
    bool drawn_cavity_chains = false;  // ... and the drawn ones (McSettings::cavity_forms)
    // Whether the layer's kind draws the rarer cavity chains by the settings
    // (McSettings::cavity_forms, connections on or not): where it does, one
    // round trip is among them (cavityEveryFlightTrips), so the walks' and
    // the connections' forms split alike whatever runs.
    bool draws_cavity_chains = false;
};

// A path's class by its last direction change (the histogram's classes, McSettings::histogram_classes).
enum class PathClass {
    Beam,       // no direction change yet
    BeamFlake,  // the beam's first reflection off an explicit flake
    Smooth,     // a pigment scattering or the Lambertian substrate
    Other,      // anything else (several flakes, internal reflections, mirrors)
};

// Snell at a planar interface: tangential components scale by n_from / n_to;
// false under total internal reflection.
bool refractPlanar(const Vec3& v, double n_from, double n_to, Vec3& out);

// A flake that a straight trace passes through as if it were not in its
// tile (azimuthGlintSample's flake, moved elsewhere in the tile); none by default.
struct AbsentFlake {
    int layer = -1;
    std::int64_t flake = -1;
    // The flake absent from layer l's tile (-1: none).
    std::int64_t in(std::size_t l) const {
        return layer >= 0 && static_cast<std::size_t>(layer) == l ? flake : -1;
    }
};

// Transmittance of the straight path from (x, y, depth) in slice j along the
// upward direction u (in slice j) into the ambient: pigment extinction of
// every slice, the flake tiles of their layers (T of each interference flake
// crossed, 0 at a mirror flake), 1 - Fresnel at every index step and at the
// top (0 under total internal reflection). Slices of layers with tiles must
// carry no continuum flakes (McEngine::band clears them). Never throws.
// `rays`, if given, is incremented by the tile intersections traced (the cost model of the
// adaptive connection fractions, mc_rates.h). `roulette`, if given, draws the
// Russian roulette below kConnectionRouletteT (unbiased: E[T] unchanged).
double straightToAmbient(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u, std::int64_t* rays = nullptr,
                         PathRng* roulette = nullptr, const AbsentFlake& absent = {});

// Russian roulette of a connection (issue 30): before the first flake tile it
// would trace, a connection whose transmittance so far (the pigments' and
// binders' extinction of the slices below, exact and cheap) is T < this goes
// on with probability T / kConnectionRouletteT, then carries
// kConnectionRouletteT. A white ground coat (optical depth ~600) puts most
// of a walk's collisions where T ~ e^-50, and without the roulette each of
// their connections traced the flake layer above into every cone: the
// three-layer demo's connections were most of its time. The variance added
// is at most kConnectionRouletteT times the mean of the connections cut.
inline constexpr double kConnectionRouletteT = 1e-3;

// The same path up to just below the paint's top, without the top interface:
// T (0 if blocked or totally reflected at an index step on the way), the
// lateral position reached (wrapped into the tile where a tiled layer was
// crossed last) and the direction in the top slice.
struct TopArrival {
    double T = 0.0;
    double x = 0.0;
    double y = 0.0;
    Vec3 u{0.0, 0.0, 1.0};
};
TopArrival straightToTop(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u, std::int64_t* rays = nullptr,
                         PathRng* roulette = nullptr, const AbsentFlake& absent = {});

// The straight segment from (x, y, depth) along u of `length` µm through one
// layer's periodic tile (wrapping at its sides): on_hit(hit, travelled) for
// each flake it meets, in order (hit.t from the current point, x, y, depth;
// travelled before it), returns whether the segment goes on past it. Returns
// false when on_hit stopped it, else true with x, y advanced to the end
// (depth is not). The one march of the connections' shadow rays.
template <class OnHit> bool marchTile(const FlakeTile& tile, double& x, double& y, double& depth,
                                      const Vec3& u, double length, std::int64_t* rays, const OnHit& on_hit) {
    const double L = tile.sideUm();
    const double inf = std::numeric_limits<double>::infinity();
    double t_near = kTileEpsilonUm;
    double travelled = 0.0;
    for (int step = 0; step < kMaxCrossings; ++step) {
        const double left = length - travelled;
        if (!(left > 0.0)) return true;
        if (x < 0.0 || x > L) x -= L * std::floor(x / L);
        if (y < 0.0 || y > L) y -= L * std::floor(y / L);
        const double tx = u.x > 0.0 ? (L - x) / u.x : (u.x < 0.0 ? -x / u.x : inf);
        const double ty = u.y > 0.0 ? (L - y) / u.y : (u.y < 0.0 ? -y / u.y : inf);
        const double t_side = std::min(tx, ty);
        const FlakeHit hit = tile.intersect({x, y, -depth}, u, t_near, std::min(left, t_side));
        if (rays != nullptr) ++*rays;
        if (hit.kind >= 0) {
            if (!on_hit(hit, travelled)) return false;
            x += u.x * hit.t;
            y += u.y * hit.t;
            depth -= u.z * hit.t;
            travelled += hit.t;
            t_near = kTileEpsilonUm;
            continue;
        }
        if (t_side >= left) {
            x += u.x * left;
            y += u.y * left;
            return true;
        }
        x += u.x * t_side;
        y += u.y * t_side;
        depth -= u.z * t_side;
        travelled += t_side;
        if (tx <= ty)
            x = u.x > 0.0 ? 0.0 : L;
        else
            y = u.y > 0.0 ? 0.0 : L;
        t_near = 0.0;
    }
    return true;
}

// The first flake of one layer's tile along the segment from (x, y, depth) of
// `length` µm in direction u (wrapping at the tile's sides): the hit (kind -1:
// none; t from the start) and the lateral position reached (at the hit, or
// at the segment's end), wrapped into the tile.
struct TileHit {
    FlakeHit hit;
    double x = 0.0;
    double y = 0.0;
};
TileHit firstFlakeAlong(const LayerFlakes& lf, double x, double y, double depth, const Vec3& u, double length,
                        std::int64_t* rays = nullptr);
// The same for flake `target` (its index in the tile): the light passes the
// other flakes before it, each multiplying `T` by its transmittance (a mirror
// flake's 0 ends the march: kind -1, T 0).
TileHit targetFlakeAlong(const LayerFlakes& lf, double x, double y, double depth, const Vec3& u,
                         double length, std::int64_t target, double& T, std::int64_t* rays = nullptr);

// Transmittance along the segment from (x, y, depth) of `length` µm in
// direction u through one layer's tile (wrapping at its sides): the product
// of T(|u.n|) over the flakes crossed but `absent_flake` (-1: none). x, y
// are advanced to the segment's end.
double tileTransmittance(const LayerFlakes& lf, double& x, double& y, double depth, const Vec3& u,
                         double length, std::int64_t* rays = nullptr, std::int64_t absent_flake = -1);

// Pigment optical depth of the straight segment between two depths of one
// layer along a direction of cosine |mu| (the slices of a depth profile each
// at their own extinction; tiled layers carry no continuum flakes).
double layerOpticalDepth(const PaintStack& stack, int layer, double depth_a, double depth_b, double abs_mu);

// The slice of `layer` that holds `depth`; stack.slices.size() if none (a point
// of a flake tilted in a film thinner than it pokes out of the layer, which the
// walk cannot hit there either: it traces a tile inside its layer only).
std::size_t sliceAt(const PaintStack& stack, int layer, double depth);

// A direction uniform in the bin's cone (solid angle).
Vec3 sampleInCone(const HistogramBin& bin, double u1, double u2);

}  // namespace paintlab::mc
