#pragma once
// Synthetic measurements from a recipe: the model's values at the
// geometries of given observations, and noise drawn from their stated
// sigmas. What the round-trip tests and benchmarks fit, and what the Match
// dock overlays as "fitted" at the measured geometries.

#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/observations.h"
#include "paintlab/engine/recipe.h"

#include <cstdint>
#include <vector>

namespace paintlab::fit {

// Readings at the six standard geometries of multiangle.h (45° illumination,
// aspecular -15 ... 110°), spectra at wavelengths_nm (empty: 400-700 nm in
// 10 nm steps, what instruments export), values 0 until simulated.
MultiAngleMeasurement standardMultiAngleMeasurement(Side side = Side::Top,
                                                    std::vector<double> wavelengths_nm = {});

// The observations with every value replaced by the recipe's model value
// (fast model at fitSettings(preset), fit.h): reflectance factors and Lab for multi-angle
// readings (Lab only where the reading had Lab or no spectrum), BRDF values
// as linear sRGB or per wavelength. Bottom-side observations see
// recipeSeenFromBelow(recipe). Noise fields are kept. Throws as
// validateFitProblem for bad observations or recipes.
Observations simulateObservations(const Recipe& recipe, const Observations& at, Preset preset);

// Adds independent Gaussian noise with each value's sigma (the defaults of
// observations.h where a noise field is 0): reflectance factors and Lab
// additively, BRDF values on ln(1 + f cos θi) (then back to f, >= 0).
// The same seed gives the same noise.
void addMeasurementNoise(Observations& observations, std::uint64_t seed);

}  // namespace paintlab::fit
