#pragma once
// Measurements and fits of the database in the fitter's terms (engine
// fit/observations.h, fit/fit.h): what `paintlab-cli fit` and the Match dock
// hand the fitter, and the `fit` table row they store afterwards. Plain
// data conversions: the database does not run fits.

#include "paintlab/database/measurements.h"
#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/observations.h"

#include <string>
#include <vector>

namespace paintlab::db {

// Adds the measurement to the observations as seen from `side`: multi-angle
// readings with their spectra (when the measurement has them) and CIELAB;
// BRDF samples as linear sRGB (channels R, G, B in any order) or per
// wavelength. Noise fields stay 0 (the fitter's documented defaults).
// Throws InputError naming the measurement and field for channels other than
// R, G and B.
void addFitObservation(fit::Observations& observations, const Measurement& measurement, fit::Side side);

// The `fit` table's rows for a fit stored against a recipe version, one per
// measurement of the problem (in its order: multi-angle, then BRDF): method,
// whitened residual RMS over all measurements, that measurement's residuals
// (ΔE00 per multi-angle geometry, the log error per BRDF sample), the fitted
// values by path and their sigmas by "path.sigma" (infinite sigmas left out).
std::vector<Fit> fitRecords(const fit::FitResult& result, const fit::FitProblem& problem,
                            const std::string& recipe_name, int recipe_version, const std::string& note);

}  // namespace paintlab::db
