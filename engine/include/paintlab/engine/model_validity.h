#pragma once
// Where the fast model's continuum of flakes stops standing for real flat
// flakes: the boundary measured by the fast-vs-full comparison report
// (docs/VALIDATION.md, "Fast vs full model: comparison report";
// docs/fast_vs_full.csv), as a number the effect planner can use
// (shared/ARCHITECTURE.md, "Effect planner": the full model only outside the
// fast model's validity).
//
// What breaks: the fast model treats flakes as independent infinitesimal
// reflectors spread evenly through the film's depth. Real flakes are large,
// and two things follow (model_validity.cpp derives both):
// - Hiding: the light a flake reflects leaves along a way close to the way
//   in, which was just found free of flakes: light escapes more easily (the
//   hiding or opposition effect of dense media of large scatterers), and the
//   full model is brighter, by up to a factor of two in single scattering.
// - Surface depletion: a tilted flake cannot poke out of its film, so its
//   centre keeps r sin(tilt) from each face and the film's top holds fewer
//   tilted flakes than the continuum's even spread. Where the film absorbs
//   (carbon black under a pearl), the top is what the viewer sees, and the
//   full model is the darker at the geometries that need tilted flakes (the
//   demo pearlescent: -11 % near the specular to -35 % at 45as75).
// The rule is the two mechanisms, the hiding with three constants fitted to
// the report's points geometry by geometry, the depletion in closed form.

#include "paintlab/engine/recipe.h"

#include <string>

namespace paintlab {

// The seed paper's (Voloboy, Ershov, Pozdnyakov) bar for dielectric
// particles: under 10 % difference between the two models.
inline constexpr double kDefaultFastModelTolerance = 0.10;

struct FastModelValidity {
    // Expected relative difference (full - fast) / fast of the BRDF, summed
    // over the six multi-angle geometries (45° incidence, weighted by the
    // flakes' signal there); positive where the full model is the brighter.
    // 0 when the paint has no flakes: then both models solve the same
    // radiative-transfer equation.
    double expected_rel_difference = 0.0;
    // The largest |difference| expected at one of the six geometries where
    // the flakes send at least 3 % of their brightest signal (signed), and
    // that geometry's aspecular angle: what the worst pixels of an image see.
    double largest_rel_difference = 0.0;
    double largest_at_aspecular_deg = 0.0;
    double tolerance = kDefaultFastModelTolerance;
    bool within = true;  // |expected_rel_difference| <= tolerance
    // Names the layer and flake component that set the difference, with its
    // coverage and diameter over free path (or why the paint is exact).
    std::string reason;
};

// The surface-depletion factor (model_validity.cpp): the flake signal of
// tilted flakes whose centres keep `half_height_um` (r sin(tilt)) from each
// face of a film of `film_um`, over the continuum's evenly spread one, when a
// reflection at depth z counts exp(-kappa_per_um z). In (0, 1] for a film that
// attenuates (kappa > 0), exactly 1 for kappa = 0 or half_height 0.
double tiltedFlakeSurfaceDepletion(double kappa_per_um, double film_um, double half_height_um);

// Throws InputError if the recipe is not valid (validateRecipe) or tolerance
// is not in (0, 1].
FastModelValidity fastModelValidity(const Recipe& recipe, double tolerance = kDefaultFastModelTolerance);

}  // namespace paintlab
