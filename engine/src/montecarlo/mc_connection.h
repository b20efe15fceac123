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
//    (GlintSet); each path picks one in proportion to the area of the beam
//    it intercepts (A |v.n| / |v_z| / L^2: the probability that a uniformly
//    placed entry point's beam meets it), a point uniform on its polygon,
//    and scores the straight transmittance of the beam down to that point
//    (entry Fresnel, pigments, the flakes above) times R(|v.n|) times the
//    straight transmittance up and out. Real positions, normals and sizes:
//    every shadowing between flakes is the tile's own. That is the estimator
//    of 2026-12-01 (per view of the tile); by default the same term is
//    estimated over every azimuth of the tile at once, with importance
//    sampling, independently of the paths (AzimuthGlintSet below;
//    monte_carlo.cpp draws its samples per chunk).
//  - Other (multiple flake reflections, internal Fresnel reflections, metal
//    mirrors) and Beam (a beam never leaves unscattered except by a mirror):
//    the histogram, except three parts of Other that have their own walks
//    (mc_walk.h, default on): the chains without a smooth vertex (delta-chain
//    walks), the paths whose first change was smooth (reverse walks, by
//    reciprocity), and those whose first change was the beam's reflection off
//    a flake followed by a pigment vertex in its layer (reverse walks
//    connecting to the beam's mirror images, reflectedBeams below).
// The histogram then scores Beam and Other escapes only, so every path class
// is counted exactly once. The connections may run on a random share of the
// paths only, their scores divided by it (McSettings::connection_fraction).
//
// Known limit: the glint weight 1 / L^2 assumes the entry points are uniform
// over the flake layer's own tile; with tiles of different sides in several
// layers they are uniform over the largest (monte_carlo.cpp), exact when the
// sides are commensurate and for one flaked layer (the demos).

#include "flake_tile.h"
#include "mc_random.h"
#include "mc_stack.h"

#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

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
struct LayerFlakes {
    const FlakeTile* tile = nullptr;
    std::vector<FlakeKind> kinds;
    const TiltIndex* tilts = nullptr;     // the tile's flakes by tilt (azimuthGlintSets; null: none)
    const FlakeGroups* groups = nullptr;  // by tilt, azimuth and depth (first_flake.h; null: none)
};

enum PathClass : unsigned {
    kClassBeam = 1U,       // no direction change yet
    kClassBeamFlake = 2U,  // the beam's first reflection off an explicit flake
    kClassSmooth = 4U,     // a pigment scattering or the Lambertian substrate
    kClassOther = 8U,      // anything else (several flakes, internal reflections, mirrors)
    kAllClasses = 15U,
};

// Snell at a planar interface: tangential components scale by n_from / n_to;
// false under total internal reflection.
bool refractPlanar(const Vec3& v, double n_from, double n_to, Vec3& out);

// Transmittance of the straight path from (x, y, depth) in slice j along the
// upward direction u (in slice j) into the ambient: pigment extinction of
// every slice, the flake tiles of their layers (T of each interference flake
// crossed, 0 at a mirror flake), 1 - Fresnel at every index step and at the
// top (0 under total internal reflection). Slices of layers with tiles must
// carry no continuum flakes (McEngine::band clears them). Never throws.
// `rays`, if given, is incremented by the tile intersections traced (the cost model of the
// adaptive connection fractions, monte_carlo.cpp).
double straightToAmbient(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u, std::int64_t* rays = nullptr);

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
                         double depth, double x, double y, Vec3 u, std::int64_t* rays = nullptr);

// The slice of `layer` that holds `depth`; stack.slices.size() if none (a point
// of a flake tilted in a film thinner than it pokes out of the layer, which the
// walk cannot hit there either: it traces a tile inside its layer only).
std::size_t sliceAt(const PaintStack& stack, int layer, double depth);

// A direction uniform in the bin's cone (solid angle).
Vec3 sampleInCone(const HistogramBin& bin, double u1, double u2);

// Per tile realisation and cone: the flakes whose reflection of the beam
// leaves into the cone, with the cumulative weights A |v.n| / (|v_z| L^2).
struct GlintFlake {
    int layer = 0;
    std::size_t flake = 0;
    Vec3 v;  // the beam's direction in the layer (downward)
    Vec3 r;  // its mirror direction off the flake (upward)
    double cos_local = 0.0;
};

struct GlintSet {
    std::vector<GlintFlake> flakes;
    std::vector<double> cumulative;  // ascending; the last is the total weight
    double total() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
};

// The glint sets of one tile realisation for the beam v_in (refracted into
// the top slice) and every bin.
std::vector<GlintSet> glintSets(const PaintStack& stack, std::span<const LayerFlakes> tiles, const Vec3& v_in,
                                std::span<const HistogramBin> bins);

// One sample of the BeamFlake class's f (1/sr) for every bin, times `weight` (added to f_out[k]).
void scoreGlints(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                 std::span<const GlintSet> glints, std::span<const HistogramBin> bins, double weight,
                 PathRng& rng, std::span<double> f_out);

// BeamFlake over all azimuths of a tile (McSettings::glint_azimuths, the default).
//
// The flake statistics are isotropic, so the tile turned by any azimuth psi is
// as valid a realisation as the tile itself (the views of monte_carlo.cpp
// take 32 of them). The glint term of the tile averaged over every psi,
//   G = (1/2pi) int dpsi sum_i w_i(psi) <g_i(psi)> 1[flake i glints into the cone at psi],
// with w_i = A_i |v.n| / (|v_z| L^2) and <g_i> the mean over the flake's
// polygon of t_in R t_out (as scoreGlints), is estimated directly:
//  - per bin and layer, the normals whose mirror direction of the beam leaves
//    into the cone lie in a spherical cap around the half-vector of the
//    cone's axis (radius from 64 points of the cone's edge plus twice the
//    largest gap between their images: a superset); a flake of tilt tau meets
//    the cap, turned by psi, on one interval of psi (closed form), listed from
//    the flakes sorted by tilt (TiltIndex, built once per tile for every band);
//  - a sample picks a listed flake with probability proportional to
//    w_i R(|v.n|) exp(-optical depth of beam and exit to the flake's centre,
//    pigments and the layer's mean flake extinction) times the part of its
//    interval where it glints (16 points) (importance sampling: deep flakes
//    are dark under the demo's carbon black; it cut the per-sample relative
//    variance near the specular direction from ~2.4 to 0.1-0.4); then the
//    exact glint test at 16 azimuths of a randomly shifted grid over the
//    interval, one of the glinting ones drawn uniformly (score times the
//    glinting share: unbiased, and no sample is lost where the cap is wider
//    than the glint), a point uniform on the polygon, and the traces through
//    the real tile; divided by the probability density: unbiased for G
//    whatever the proposal, which only has to be positive where the
//    integrand is;
//  - the flakes are listed by depth, so that stratified picks (one per
//    stratum of the cumulative weight) spread over depths.
// No view enters: the tile-to-tile spread of G is that of the tile itself,
// not of 32 sampled azimuths (at 45as110 a view held ~1 glinting flake).
struct TiltIndex {
    std::vector<std::uint32_t> order;  // flake indices by ascending tilt
    std::vector<double> tilt;          // their tilts (radians), ascending
    // A lateral grid of the same flakes (reflectedBeams' candidates): cells x
    // cells squares of side cell_um over the tile, cell c = row * cells + column
    // holding cell_flakes[cell_start[c] .. cell_start[c + 1]) (by the centre's
    // position), each cell by ascending tilt (cell_tilts).
    int cells = 0;
    double cell_um = 0.0;
    double max_radius_um = 0.0;
    std::vector<std::uint32_t> cell_start;
    std::vector<std::uint32_t> cell_flakes;
    std::vector<double> cell_tilts;
};
TiltIndex tiltIndex(const FlakeTile& tile);

struct AzimuthGlint {
    int layer = 0;
    std::uint32_t flake = 0;
    double psi_lo = 0.0;     // the interval of view azimuths (radians) where it may glint
    double psi_width = 0.0;  // in (0, 2 pi]
    double depth = 0.0;      // of its centre (µm), the listing order
};

struct AzimuthGlintSet {
    std::vector<AzimuthGlint> flakes;  // by depth
    std::vector<double> cumulative;    // of the proposal weights; the last is the total
    std::vector<Vec3> v_layer;         // the unturned beam in each layer (downward; z = 0: none)
    std::vector<double> n_layer;       // each layer's binder index
    double total() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
};

// The sets of one tile realisation (layers without a tile or its TiltIndex are left out)
// for the unturned beam v_in (refracted into the top slice) and every bin (unturned).
std::vector<AzimuthGlintSet> azimuthGlintSets(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                                              const Vec3& v_in, std::span<const HistogramBin> bins);

// Uniforms of one sample: the pick (stratified by the caller), the azimuth
// within the interval and the point on the polygon (pointOnFlake's three).
struct GlintUniforms {
    double pick = 0.0, psi = 0.0, choose = 0.0, u1 = 0.0, u2 = 0.0, u3 = 0.0;
};

// One sample of bin k's BeamFlake f (1/sr) from its set (0 when the set is empty).
double azimuthGlintSample(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                          const AzimuthGlintSet& set, const HistogramBin& bin, const GlintUniforms& u,
                          std::int64_t* rays = nullptr);

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
