#include "paintlab/engine/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace paintlab {
namespace {

TEST(Spectrum, ConstantIsTheSameEverywhere) {
    const Spectrum s(0.25);
    EXPECT_TRUE(s.isConstant());
    EXPECT_EQ(s(200.0), 0.25);
    EXPECT_EQ(s(550.0), 0.25);
    EXPECT_EQ(s(2000.0), 0.25);
}

TEST(Spectrum, InterpolatesLinearlyAndHoldsEnds) {
    const Spectrum s({400.0, 500.0, 700.0}, {1.0, 3.0, 1.0});
    EXPECT_DOUBLE_EQ(s(450.0), 2.0);
    EXPECT_DOUBLE_EQ(s(600.0), 2.0);
    EXPECT_DOUBLE_EQ(s(500.0), 3.0);  // exactly at a sample
    EXPECT_DOUBLE_EQ(s(300.0), 1.0);  // held below the first sample
    EXPECT_DOUBLE_EQ(s(800.0), 1.0);  // held above the last
    EXPECT_DOUBLE_EQ(s.minValue(), 1.0);
    EXPECT_DOUBLE_EQ(s.maxValue(), 3.0);
}

TEST(Spectrum, ResamplingALinearFunctionIsExact) {
    // A linear function is reproduced exactly by linear interpolation, on any grid.
    const Spectrum s({380.0, 780.0}, {0.0, 4.0});
    const auto grid = visibleBands(41);
    const Spectrum r = s.resampled(grid);
    ASSERT_EQ(r.values().size(), 41u);
    for (std::size_t i = 0; i < grid.size(); ++i)
        EXPECT_NEAR(r.values()[i], (grid[i] - 380.0) / 100.0, 1e-12) << "at " << grid[i] << " nm";
}

TEST(Spectrum, GridsHaveTheExpectedSamples) {
    const auto grid = uniformWavelengthGrid(380.0, 780.0, 10.0);
    ASSERT_EQ(grid.size(), 41u);
    EXPECT_DOUBLE_EQ(grid.front(), 380.0);
    EXPECT_DOUBLE_EQ(grid.back(), 780.0);
    const auto bands = visibleBands(8);
    ASSERT_EQ(bands.size(), 8u);
    EXPECT_DOUBLE_EQ(bands.front(), kVisibleMinNm);
    EXPECT_DOUBLE_EQ(bands.back(), kVisibleMaxNm);
    EXPECT_THROW(visibleBands(1), std::invalid_argument);
    EXPECT_THROW(uniformWavelengthGrid(500.0, 400.0, 10.0), std::invalid_argument);
    EXPECT_THROW(uniformWavelengthGrid(400.0, 500.0, 0.0), std::invalid_argument);
}

TEST(Spectrum, RejectsMalformedTables) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(Spectrum({}, {}), std::invalid_argument);
    EXPECT_THROW(Spectrum({400.0, 500.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(Spectrum({500.0, 400.0}, {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(Spectrum({400.0, 400.0}, {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(Spectrum({400.0, 500.0}, {1.0, nan}), std::invalid_argument);
    EXPECT_THROW(Spectrum(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

}  // namespace
}  // namespace paintlab
