#pragma once
// What the planner needs to know of a recipe's spectra and depth profiles
// (plan.cpp): how well a band count samples them, and how far a slice count
// is from the exact concentration profile.

#include "paintlab/engine/recipe.h"

namespace paintlab::plan_detail {

// Largest error of every spectrum of the recipe (binder index and
// absorption, pigment coefficients, flake reflectance or metal index,
// substrate) when sampled at `bands` evenly spaced wavelengths over
// 380-780 nm and interpolated linearly, relative to the spectrum's largest
// absolute value, checked every 2 nm. 0 when every spectrum is constant.
double spectralSamplingError(const Recipe& recipe, int bands);

// Whether any component of any layer has a depth profile.
bool hasDepthProfiles(const Recipe& recipe);

// Largest relative error of the concentration when each profiled layer is
// cut into `slices` equal slices of constant (mean) concentration: max over
// profiles of int |w - slice mean| dz / int w dz (0 without profiles).
double sliceConcentrationError(const Recipe& recipe, int slices);

}  // namespace paintlab::plan_detail
