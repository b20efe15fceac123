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
//    every shadowing between flakes is the tile's own.
//  - Other (multiple flake reflections, internal Fresnel reflections, metal
//    mirrors) and Beam (a beam never leaves unscattered except by a mirror):
//    left to the histogram.
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
struct LayerFlakes {
    const FlakeTile* tile = nullptr;
    std::vector<FlakeKind> kinds;
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
double straightToAmbient(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u);

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

}  // namespace paintlab::mc
