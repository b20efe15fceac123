#pragma once
// Shared by the fitter's tests: demo recipes and synthetic problems.

#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/parameter_paths.h"
#include "paintlab/engine/fit/simulate.h"
#include "paintlab/engine/recipe_json.h"
#include "test_recipes.h"

#include <string>
#include <vector>

namespace paintlab::test {

// A fit problem on synthetic measurements of `truth` (noisy with `seed`),
// starting from `start`, freeing `paths` with the default bounds.
inline fit::FitProblem syntheticProblem(const Recipe& truth, const Recipe& start,
                                        const std::vector<std::string>& paths,
                                        const fit::Observations& geometry, Preset preset,
                                        std::uint64_t seed) {
    fit::FitProblem p;
    p.recipe = start;
    for (const auto& path : paths) p.free.push_back({path, std::nullopt, std::nullopt});
    p.observations = fit::simulateObservations(truth, geometry, preset);
    fit::addMeasurementNoise(p.observations, seed);
    return p;
}

}  // namespace paintlab::test
