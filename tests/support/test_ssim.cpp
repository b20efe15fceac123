// The screenshot comparison's SSIM (ssim.h) against closed forms.

#include "ssim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>

namespace paintlab::test {
namespace {

GreyImage constant(int w, int h, double v) {
    return {w, h, std::vector<double>(static_cast<std::size_t>(w * h), v)};
}

// Identical images: every window's two factors are 1, exactly.
TEST(Ssim, IdenticalImagesGiveOne) {
    GreyImage a = constant(40, 24, 0.0);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 255.0);
    for (double& v : a.value) v = u(rng);
    EXPECT_NEAR(meanSsim(a, a), 1.0, 1e-12);  // round-off of the window sums
}

// Two flat images of levels p and q: no variance, so SSIM is the luminance
// term alone, (2pq + C1) / (p^2 + q^2 + C1), C1 = (0.01 * 255)^2.
TEST(Ssim, FlatImagesGiveTheLuminanceTerm) {
    const double c1 = 6.5025;
    for (const auto& [p, q] : {std::pair{200.0, 100.0}, std::pair{10.0, 0.0}, std::pair{128.0, 127.0}}) {
        const double expected = (2.0 * p * q + c1) / (p * p + q * q + c1);
        EXPECT_NEAR(meanSsim(constant(16, 16, p), constant(16, 16, q)), expected, 1e-12) << p << " " << q;
    }
}

// An image against its negative about the mean: the structure term is
// (C2 - 2 var) / (2 var + C2) for equal means, close to -1 for strong contrast.
TEST(Ssim, NegativeImageIsAnticorrelated) {
    GreyImage a = constant(16, 16, 0.0);
    GreyImage b = a;
    for (int i = 0; i < 16 * 16; ++i) {
        const double s = ((i % 16 + i / 16) % 2 == 0) ? 100.0 : -100.0;  // checkerboard about 128
        a.value[static_cast<std::size_t>(i)] = 128.0 + s;
        b.value[static_cast<std::size_t>(i)] = 128.0 - s;
    }
    // Each 8 x 8 window: mean 128 in both, var = 100^2 * 64 / 63, cov = -var.
    const double var = 1e4 * 64.0 / 63.0;
    const double c2 = 58.5225;
    const double expected = (-2.0 * var + c2) / (2.0 * var + c2);
    EXPECT_NEAR(meanSsim(a, b), expected, 1e-12);
}

TEST(Ssim, DifferentSizesAreRefused) {
    EXPECT_THROW((void)meanSsim(constant(16, 16, 1.0), constant(16, 17, 1.0)), std::invalid_argument);
    EXPECT_THROW((void)meanSsim(constant(4, 4, 1.0), constant(4, 4, 1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace paintlab::test
