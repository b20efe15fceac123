#pragma once
// Where the fast model's continuum of flakes stops standing for real flat
// flakes: the boundary measured by the fast-vs-full comparison report
// (docs/VALIDATION.md, "Fast vs full model: comparison report";
// docs/fast_vs_full.csv), as a number the effect planner can use
// (shared/ARCHITECTURE.md, "Effect planner": the full model only outside the
// fast model's validity).
//
// What breaks: the fast model treats flakes as independent infinitesimal
// reflectors, so the light a flake reflects is attenuated on its way out as
// if the paint above were a fresh random medium. Real flakes are large, and
// the way out runs close to the way in, which was just found free of flakes:
// light escapes more easily (the hiding or opposition effect of dense media
// of large scatterers) and the full model is brighter, by up to a factor of
// two in single scattering. The rule is that mechanism with three
// constants fitted to the report's points (model_validity.cpp).

#include "paintlab/engine/recipe.h"

#include <string>

namespace paintlab {

// The seed paper's (Voloboy, Ershov, Pozdnyakov) bar for dielectric
// particles: under 10 % difference between the two models.
inline constexpr double kDefaultFastModelTolerance = 0.10;

struct FastModelValidity {
    // Expected relative difference (full - fast) / fast of the BRDF, summed
    // over the six multi-angle geometries (45° incidence, signal-weighted),
    // >= 0 (the full model is the brighter). 0 when the paint has no flakes:
    // then both models solve the same radiative-transfer equation.
    double expected_rel_difference = 0.0;
    double tolerance = kDefaultFastModelTolerance;
    bool within = true;  // expected_rel_difference <= tolerance
    // Names the layer and flake component that set the difference, with its
    // coverage and diameter over free path (or why the paint is exact).
    std::string reason;
};

// Throws InputError if the recipe is not valid (validateRecipe) or tolerance
// is not in (0, 1].
FastModelValidity fastModelValidity(const Recipe& recipe, double tolerance = kDefaultFastModelTolerance);

}  // namespace paintlab
