// Sparkle area, intensity, grade and graininess (sparkle_grades.h) on
// textures whose numbers follow from the definitions by hand.

#include "paintlab/engine/error.h"
#include "paintlab/engine/sparkle/sparkle_grades.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace paintlab {
namespace {

TEST(SparkleGrades, UniformTextureHasNoSparkleAndNoGrain) {
    const std::vector<double> v(64, 0.3);
    const SparkleGrades g = sparkleGrades(v, 8, 8);
    EXPECT_NEAR(g.mean, 0.3, 1e-15);
    EXPECT_EQ(g.sparkle_area_percent, 0.0);
    EXPECT_EQ(g.sparkle_intensity, 0.0);
    EXPECT_EQ(g.sparkle_grade, 0.0);
    EXPECT_NEAR(g.graininess, 0.0, 1e-12);
    EXPECT_NEAR(g.contrast_cv, 0.0, 1e-12);
}

TEST(SparkleGrades, OneGlintPerBlockByHand) {
    // 8 x 8 elements of 1 but one of 65: mean 2, threshold 4 -> 1 element above (1/64 = 1.5625 %),
    // contrast (65 - 2) / 2 = 31.5. Blocks: one of 16 has mean 17, the rest 1:
    // block mean 2, std sqrt((15^2 + 15 * 1^2) / 16) = sqrt(15), G = 100 sqrt(15) / 2.
    std::vector<double> v(64, 1.0);
    v[0] = 65.0;
    const SparkleGrades g = sparkleGrades(v, 8, 8);
    EXPECT_DOUBLE_EQ(g.mean, 2.0);
    EXPECT_DOUBLE_EQ(g.sparkle_area_percent, 100.0 / 64.0);
    EXPECT_DOUBLE_EQ(g.sparkle_intensity, 31.5);
    EXPECT_NEAR(g.sparkle_grade, std::sqrt(100.0 / 64.0 * 31.5), 1e-12);
    EXPECT_NEAR(g.graininess, 50.0 * std::sqrt(15.0), 1e-9);
}

TEST(SparkleGrades, BadInputIsRefused) {
    const std::vector<double> v(4, 1.0);
    EXPECT_THROW(sparkleGrades(v, 2, 3), InputError);
    EXPECT_THROW(sparkleGrades(v, 1, 4), InputError);
    EXPECT_THROW(sparkleGrades(v, 2, 2, 0.0), InputError);
    std::vector<double> bad(4, 1.0);
    bad[2] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(sparkleGrades(bad, 2, 2), InputError);
    bad[2] = -1.0;
    EXPECT_THROW(sparkleGrades(bad, 2, 2), InputError);
}

}  // namespace
}  // namespace paintlab
