#pragma once
// Where the fast model's continuum of flakes stops standing for real flat
// flakes, as a number the effect planner can use: the boundary measured by
// the fast-vs-full comparison report (docs/VALIDATION.md). Large flakes
// differ from the continuum in two ways (model_validity.cpp derives both):
// - hiding: light leaves along a way close to the way in, just found free
//   of flakes, so the full model is brighter (up to 2x in single scattering);
// - surface depletion: a tilted flake cannot poke out of its film, so the
//   top of an absorbing film holds fewer tilted flakes and the full model is
//   darker where they are needed.
// Hiding has three constants fitted to the report; depletion is closed form.

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
