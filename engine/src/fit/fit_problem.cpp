#include "fit_problem.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/recipe_paths.h"
#include "paintlab/engine/recipe_validation.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace paintlab::fit {

namespace {

using io::formatNumber;

// A positive range wider than this ratio is searched on a log scale.
constexpr double kLogRangeRatio = 10.0;

void checkSettings(const FitSettings& s) {
    const auto fail = [](const std::string& key, const std::string& message) {
        throw InputError("<settings>", fieldPath("settings", key), message);
    };
    if (s.starts < 1 || s.starts > 10000) fail("starts", std::to_string(s.starts) + " is outside 1 to 10000");
    if (s.polish_count < 1) fail("polish_count", "must be at least 1");
    if (s.searches < 1) fail("searches", "must be at least 1");
    if (s.search_iterations < 1) fail("search_iterations", "must be at least 1");
    if (s.polish_iterations < 1) fail("polish_iterations", "must be at least 1");
    if (!(s.alternative_cost_abs >= 0.0) || !std::isfinite(s.alternative_cost_abs))
        fail("alternative_cost_abs", "must be a finite number >= 0");
    if (!(s.alternative_cost_rel >= 0.0) || !std::isfinite(s.alternative_cost_rel))
        fail("alternative_cost_rel", "must be a finite number >= 0");
    if (!(s.correlation_threshold > 0.0 && s.correlation_threshold <= 1.0))
        fail("correlation_threshold", "must be in (0, 1]");
}

}  // namespace

FitBounds defaultFitBounds(const ParameterPath& parameter, const FitSettings& settings) {
    FitBounds out{parameter.min, parameter.max};
    // A spread the fit's grids cannot resolve would only fit noise.
    if (parameter.decl == &params::kOrientationSpread) {
        const double resolved =
            std::max(narrowestResolvedFlakeSpreadDeg(fitSettings(settings.search_preset)),
                     narrowestResolvedFlakeSpreadDeg(fitSettings(settings.polish_preset)));
        out.lower = std::clamp(std::ceil(resolved * 10.0) / 10.0, parameter.min, parameter.max);
    }
    return out;
}

double FreeDimension::toValue(double u) const {
    return log ? lower * std::pow(upper / lower, u) : lower + u * (upper - lower);
}

double FreeDimension::toUnit(double value) const {
    const double u =
        log ? std::log(value / lower) / std::log(upper / lower) : (value - lower) / (upper - lower);
    return std::clamp(u, 0.0, 1.0);
}

double FreeDimension::valuePerUnit(double u) const {
    return log ? toValue(u) * std::log(upper / lower) : upper - lower;
}

PreparedProblem prepareProblem(const FitProblem& problem) {
    validateRecipe(problem.recipe, "<template>");
    checkSettings(problem.settings);
    if (problem.free.empty()) throw InputError("<argument>", "free", "no free parameter: nothing to fit");
    PreparedProblem out;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < problem.free.size(); ++i) {
        const FreeParameter& f = problem.free[i];
        FreeDimension d;
        d.info = describeParameter(problem.recipe, f.path);  // InputError naming the path
        if (!seen.insert(f.path).second) throw InputError("<argument>", f.path, "freed twice");
        const FitBounds defaults = defaultFitBounds(d.info, problem.settings);
        d.lower = f.lower.value_or(defaults.lower);
        d.upper = f.upper.value_or(defaults.upper);
        const ParameterDecl& decl = *d.info.decl;
        const std::string allowed = "allowed " + formatNumber(decl.min) + " to " + formatNumber(decl.max);
        for (const double bound : {d.lower, d.upper})
            if (!decl.allows(bound))
                throw InputError("<argument>", f.path,
                                 "bound " + formatNumber(bound) + " is outside the allowed range (" +
                                     allowed + ")");
        if (!(d.lower < d.upper))
            throw InputError("<argument>", f.path,
                             "lower bound " + formatNumber(d.lower) + " is not below upper bound " +
                                 formatNumber(d.upper));
        d.log = problem.settings.log_scale && d.info.log_scale_suited && d.lower > 0.0 &&
                d.upper / d.lower > kLogRangeRatio;
        out.dims.push_back(std::move(d));
    }
    out.observations = prepareObservations(problem.observations, problem.recipe);
    return out;
}

Recipe recipeAt(const Recipe& recipe, const std::vector<FreeDimension>& dims, std::span<const double> u) {
    Recipe out = recipe;
    for (std::size_t j = 0; j < dims.size(); ++j)
        setParameterValue(out, dims[j].info.path, dims[j].toValue(u[j]));
    return out;
}

std::vector<std::vector<double>> haltonStarts(std::size_t count, std::size_t dims, std::uint64_t seed) {
    static constexpr int kPrimes[] = {2,  3,  5,  7,  11, 13, 17, 19, 23, 29, 31, 37, 41,
                                      43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97};
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<double> shift(dims);
    for (double& s : shift) s = uniform(rng);
    std::vector<std::vector<double>> points(count, std::vector<double>(dims));
    for (std::size_t i = 0; i < count; ++i)
        for (std::size_t j = 0; j < dims; ++j) {
            // Radical inverse of i + 1 in base p (dimensions beyond the table
            // reuse its primes with another shift: still well spread).
            const int p = kPrimes[j % std::size(kPrimes)];
            double f = 1.0;
            double r = 0.0;
            for (std::size_t n = i + 1; n > 0; n /= static_cast<std::size_t>(p)) {
                f /= p;
                r += f * static_cast<double>(n % static_cast<std::size_t>(p));
            }
            points[i][j] = std::fmod(r + shift[j], 1.0);
        }
    return points;
}

}  // namespace paintlab::fit
