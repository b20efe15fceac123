// The fast model's azimuthal Fourier sum (fast_model/fourier_series.h).
#include "paintlab/engine/fast_model/fourier_series.h"

#include <gtest/gtest.h>

#include <vector>

namespace paintlab {
namespace {

// sum_m terms[m] coefficients[m * stride], scaled after the sum.
TEST(FourierSeries, SumsStridedCoefficientsThenScales) {
    const std::vector<double> terms{1.0, 0.5, -0.25};
    // Two bands interleaved: band 0 is (2, 4, 8), band 1 is (1, 1, 1).
    const std::vector<double> coefficients{2.0, 1.0, 4.0, 1.0, 8.0, 1.0};
    EXPECT_EQ(clippedFourierSum(terms, coefficients, 2, 3.0), 3.0 * (2.0 + 2.0 - 2.0));
    EXPECT_EQ(clippedFourierSum(terms, std::span<const double>(coefficients).subspan(1), 2, 1.0), 1.25);
}

// A series that rings below zero is clipped to zero, whatever the scale.
TEST(FourierSeries, ClipsBelowZero) {
    const std::vector<double> terms{1.0, -1.0};
    const std::vector<double> coefficients{0.1, 0.3};
    EXPECT_EQ(clippedFourierSum(terms, coefficients, 1, 2.0), 0.0);
    EXPECT_EQ(clippedFourierSum({}, coefficients, 1, 2.0), 0.0);
}

}  // namespace
}  // namespace paintlab
