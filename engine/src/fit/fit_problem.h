#pragma once
// A fit problem checked and put in the optimiser's terms: each free
// parameter mapped to u in [0, 1] (linear, or logarithmic for a positive
// range spanning more than a decade), the observations prepared. Private.

#include "residual_model.h"

#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/parameter_paths.h"

#include <span>
#include <vector>

namespace paintlab::fit {

struct FreeDimension {
    ParameterPath info;
    double lower = 0.0;
    double upper = 1.0;
    bool log = false;

    double toValue(double u) const;
    double toUnit(double value) const;
    double valuePerUnit(double u) const;  // d value / d u
};

struct PreparedProblem {
    std::vector<FreeDimension> dims;
    PreparedObservations observations;
};

// Throws InputError naming the field (validateFitProblem's contract).
PreparedProblem prepareProblem(const FitProblem& problem);

// The template with the free parameters at u.
Recipe recipeAt(const Recipe& recipe, const std::vector<FreeDimension>& dims, std::span<const double> u);

// Halton points in [0, 1)^dims (bases the first primes), shifted modulo 1 by a
// seeded random vector (Cranley-Patterson rotation) so that seeds differ:
// a low-discrepancy scatter of multi-start points.
std::vector<std::vector<double>> haltonStarts(std::size_t count, std::size_t dims, std::uint64_t seed);

}  // namespace paintlab::fit
