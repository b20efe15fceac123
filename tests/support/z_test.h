#pragma once
// The statistical comparison of the Monte Carlo tests: an estimate x with
// standard error se against a reference y with its own uncertainty se_y
// (another estimate's standard error, or a computed deterministic allowance),
// passing when |x - y| <= z sqrt(se^2 + se_y^2). The default z = 4 has
// two-sided significance ~6e-5 per comparison under a normal error (~1e-3
// under Student t with 15 degrees of freedom: errors over 16 batches); each
// test file states what its comparisons add up to. PAINTLAB_MC_VERBOSE=1
// prints every comparison with its z-score (the numbers in docs/VALIDATION.md).

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace paintlab::test {

inline constexpr double kZ = 4.0;

inline void expectClose(double x, double se, double y, double se_y, const std::string& what, double z = kZ) {
    const double sigma = std::sqrt(se * se + se_y * se_y);
    const double score = sigma > 0.0 ? (x - y) / sigma : 0.0;
    if (std::getenv("PAINTLAB_MC_VERBOSE") != nullptr)  // NOLINT(concurrency-mt-unsafe)
        std::printf("  %-44s MC %.6g +- %.2g  ref %.6g (+- %.2g)  z = %+.2f\n", what.c_str(), x, se, y, se_y,
                    score);
    EXPECT_NEAR(x, y, z * sigma) << what << ": MC " << x << " +- " << se << ", reference " << y << " (+- "
                                 << se_y << "), z = " << score;
}

// Two Monte Carlo results of one incidence (mc::IncidenceResult): the albedo
// and f at every exit, each by expectClose; `what` prefixes the labels.
template <class Incidence>
void expectSameIncidence(const Incidence& a, const Incidence& b, const std::string& what, double z = kZ) {
    expectClose(a.albedo.mean, a.albedo.std_error, b.albedo.mean, b.albedo.std_error, what + "albedo", z);
    for (std::size_t k = 0; k < a.brdf_per_sr.size() && k < b.brdf_per_sr.size(); ++k)
        expectClose(a.brdf_per_sr[k].mean, a.brdf_per_sr[k].std_error, b.brdf_per_sr[k].mean,
                    b.brdf_per_sr[k].std_error, what + "f exit " + std::to_string(k), z);
}

// As expectClose, for a reference that a known systematic effect moves by an
// amount between `low` and `high` (deterministic bounds, not errors): passes
// when y + low - z sigma <= x <= y + high + z sigma, sigma = sqrt(se^2 + se_y^2).
// The bounds widen the interval once; put into sigma as an allowance they
// would be multiplied by z, letting ~4 times the effect through.
inline void expectWithin(double x, double se, double y, double se_y, double low, double high,
                         const std::string& what, double z = kZ) {
    const double sigma = std::sqrt(se * se + se_y * se_y);
    const double lo = y + low;
    const double hi = y + high;
    const double outside = x < lo ? x - lo : x > hi ? x - hi : 0.0;
    const double score = sigma > 0.0 ? outside / sigma : 0.0;
    if (std::getenv("PAINTLAB_MC_VERBOSE") != nullptr)  // NOLINT(concurrency-mt-unsafe)
        std::printf("  %-44s MC %.6g +- %.2g  ref %.6g in [%+.2g, %+.2g]  z beyond = %+.2f\n", what.c_str(),
                    x, se, y, low, high, score);
    EXPECT_GE(x, lo - z * sigma) << what << ": MC " << x << " +- " << se << ", reference " << y << " + ["
                                 << low << ", " << high << "], z beyond = " << score;
    EXPECT_LE(x, hi + z * sigma) << what << ": MC " << x << " +- " << se << ", reference " << y << " + ["
                                 << low << ", " << high << "], z beyond = " << score;
}

}  // namespace paintlab::test
