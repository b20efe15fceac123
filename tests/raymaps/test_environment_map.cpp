// HDR environments: lookup, importance sampling (unbiased, pdf integrates to
// one, matches where samples land), and bad pixels and files named.

#include "temp_dir.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/environment_map.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

namespace paintlab::raymaps {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<float> constantPixels(int w, int h, float value) {
    return std::vector<float>(static_cast<std::size_t>(w * h * 3), value);
}

// A dim map with one bright pixel (a "sun"), at row `row`, column `col`.
EnvironmentMap hotspotMap(int w, int h, int row, int col, double rotation_deg = 0.0) {
    std::vector<float> px = constantPixels(w, h, 0.1F);
    for (int c = 0; c < 3; ++c) px[static_cast<std::size_t>(3 * (row * w + col) + c)] = 5000.0F;
    return EnvironmentMap::fromPixels(w, h, std::move(px), "hotspot", rotation_deg);
}

Eigen::Vector3d uniformSphere(double u1, double u2) {
    const double z = 1.0 - 2.0 * u1;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(2.0 * kPi * u2), r * std::sin(2.0 * kPi * u2), z};
}

// The integral of f over the sphere by the midpoint rule in (theta, phi) on
// a grid 4x finer than a w x h map's pixels: every pixel gets 4 x 4 nodes
// whatever the map's rotation, so a pdf constant per pixel in
// (phi, theta) is integrated exactly up to round-off.
double integrateOverSphere(int w, int h, const std::function<double(const Eigen::Vector3d&)>& f) {
    const int sub = 4;
    double sum = 0.0;
    for (int i = 0; i < h * sub; ++i) {
        const double theta = kPi * (i + 0.5) / (h * sub);
        for (int j = 0; j < w * sub; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / (w * sub);
            const Eigen::Vector3d d(std::sin(theta) * std::sin(phi), std::cos(theta),
                                    -std::sin(theta) * std::cos(phi));
            sum += f(d) * std::sin(theta);
        }
    }
    return sum * (kPi / (h * sub)) * (2.0 * kPi / (w * sub));
}

TEST(EnvironmentMap, ConstantEnvironment) {
    const EnvironmentMap env = EnvironmentMap::fromPixels(64, 32, constantPixels(64, 32, 2.0F), "const");
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 100; ++i) EXPECT_NEAR(env.radiance(uniformSphere(u(rng), u(rng))).x(), 2.0, 1e-6);
    // The midpoint rule in theta underestimates the integral of sin by
    // (pi/H)^2 / 24 relative: 4e-4 at H = 32.
    EXPECT_NEAR(env.luminanceIntegral(), 4.0 * kPi * 2.0, 4.0 * kPi * 2.0 * 5e-4);
}

TEST(EnvironmentMap, PdfIntegratesToOne) {
    const int w = 64;
    const int h = 32;
    const EnvironmentMap env = hotspotMap(w, h, 10, 40);
    // Integrate pdf dOmega = pdf sin(theta) dtheta dphi with the midpoint rule
    // on a grid 4x finer than the pixels, aligned with them. pdf sin(theta) is
    // constant within a pixel by construction (samples are uniform in
    // (phi, theta) there), so the rule is exact up to round-off; an error in
    // the direction <-> pixel mapping, the sin(theta) factor or the
    // normalisation shows up at the percent level.
    EXPECT_NEAR(integrateOverSphere(w, h, [&](const Eigen::Vector3d& d) { return env.pdf(d); }), 1.0, 1e-9);
}

TEST(EnvironmentMap, SamplingIsUnbiasedAndConsistentWithPdf) {
    const EnvironmentMap env = hotspotMap(64, 32, 10, 40, 30.0);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 40000;
    double sum = 0.0;
    double sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const auto s = env.sample(u(rng), u(rng));
        ASSERT_NEAR(s.direction.norm(), 1.0, 1e-12);
        ASSERT_GT(s.pdf_sr, 0.0);
        ASSERT_NEAR(s.pdf_sr, env.pdf(s.direction), 1e-9 * s.pdf_sr);
        const double x = luminance(s.radiance) / s.pdf_sr;
        sum += x;
        sum2 += x * x;
    }
    // The importance-sampled estimate of the luminance integral agrees with
    // the pixel sum. Bilinear filtering makes radiance() differ from the
    // piecewise-constant pdf near the hotspot, which the estimator still
    // integrates exactly in expectation only up to the filtering's smear:
    // the pixel sum is the integral of the unfiltered map, equal for the
    // filtered one (filtering preserves the integral up to sin(theta) weights,
    // < 1 % at 32 rows). Test: |z| < 4 (false alarm 6e-5) plus 1 %.
    const double mean = sum / n;
    const double se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_LT(std::abs(mean - env.luminanceIntegral()), 4.0 * se + 0.01 * env.luminanceIntegral())
        << "mean " << mean << " se " << se << " integral " << env.luminanceIntegral();
}

// The six next-event distributions (sampleFacing): each pdf integrates to
// one (midpoint rule on a 4x finer grid, exact up to round-off as above),
// sampling returns the pdf pdfFacing gives, and a normal takes the
// distribution of its nearest axis, which puts a sample below that axis's
// horizon with the weight 0.1 of the luminance there (the map is a dim
// sphere and a hotspot above the horizon, 40 degrees up: +y's distribution
// puts ~0.1 x half the dim light's share below, well under 10 %).
TEST(EnvironmentMap, FacingDistributionsAreNormalisedAndKeepSamplesAboveTheSurface) {
    const int w = 64;
    const int h = 32;
    const EnvironmentMap env = hotspotMap(w, h, 8, 40, 30.0);
    for (const Eigen::Vector3d& normal : {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0),
                                          Eigen::Vector3d(0.3, 0.2, -0.93).normalized()}) {
        EXPECT_NEAR(
            integrateOverSphere(w, h, [&](const Eigen::Vector3d& d) { return env.pdfFacing(normal, d); }),
            1.0, 1e-9);
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        int below = 0;
        for (int i = 0; i < 2000; ++i) {
            const auto s = env.sampleFacing(normal, u(rng), u(rng));
            ASSERT_NEAR(s.pdf_sr, env.pdfFacing(normal, s.direction), 1e-9 * s.pdf_sr);
            below += s.direction.dot(normal) < 0.0 ? 1 : 0;
        }
        if (normal.y() > 0.9) {
            EXPECT_LT(below, 200);  // the plain distribution: ~half of the dim light's share
        }
    }
}

TEST(EnvironmentMap, SamplesLandOnTheHotspotAndRotationTurnsIt) {
    const int w = 64;
    const int h = 32;
    for (const double rotation : {0.0, 90.0}) {
        const EnvironmentMap env = hotspotMap(w, h, 8, 16, rotation);
        // Pixel (16, 8): phi = 2 pi 16.5 / 64 from -z towards +x, theta = pi 8.5 / 32.
        const double phi = 2.0 * kPi * 16.5 / w + rotation * kPi / 180.0;
        const double theta = kPi * 8.5 / h;
        const Eigen::Vector3d hot(std::sin(theta) * std::sin(phi), std::cos(theta),
                                  -std::sin(theta) * std::cos(phi));
        EXPECT_NEAR(env.radiance(hot).x(), 5000.0, 1e-3);
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        int near_hot = 0;
        for (int i = 0; i < 1000; ++i)
            near_hot += env.sample(u(rng), u(rng)).direction.dot(hot) > 0.99 ? 1 : 0;
        // The hotspot holds 5000 sin(theta) / (0.1 x sum of sin over all pixels) ~ 98 % of the weight.
        EXPECT_GT(near_hot, 950);
    }
}

TEST(EnvironmentMap, BuiltinSkyIsBrighterAboveTheHorizonThanTheGround) {
    const EnvironmentMap sky = EnvironmentMap::builtinSky();
    EXPECT_GT(luminance(sky.radiance({0.0, 1.0, 0.0})), luminance(sky.radiance({0.0, -1.0, 0.0})));
    EXPECT_GT(sky.radiance({0.0, 1.0, 0.0}).z(), sky.radiance({0.0, 1.0, 0.0}).x());  // blue zenith
    Environment spec;
    spec.intensity = 3.0;
    // Pixels are stored as float: scaling rounds each to ~6e-8 relative.
    EXPECT_NEAR(EnvironmentMap::load(spec).luminanceIntegral(), 3.0 * sky.luminanceIntegral(),
                1e-6 * sky.luminanceIntegral());
}

TEST(EnvironmentMap, BadPixelsAreNamed) {
    for (const float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), -1.0F}) {
        std::vector<float> px = constantPixels(8, 4, 1.0F);
        px[3 * (2 * 8 + 5) + 1] = bad;  // pixel (5, 2), green
        try {
            (void)EnvironmentMap::fromPixels(8, 4, std::move(px), "sky.exr");
            FAIL() << "accepted " << bad;
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("sky.exr"), std::string::npos) << what;
            EXPECT_NE(what.find("pixel (5, 2) channel 1"), std::string::npos) << what;
        }
    }
}

// Lossy EXR compression rings into small negatives (Blender's CC0 maps:
// -0.004 at a mean of ~0.5): down to -1 % of the mean they are set to 0 and
// counted; beyond, the pixel is an error (BadPixelsAreNamed: -1 at mean 1).
TEST(EnvironmentMap, CompressionRingingIsClampedAndCounted) {
    std::vector<float> px = constantPixels(8, 4, 1.0F);
    px[3 * (1 * 8 + 3) + 2] = -0.005F;
    const EnvironmentMap map = EnvironmentMap::fromPixels(8, 4, std::move(px), "sky.exr");
    EXPECT_EQ(map.clampedNegatives(), 1U);
    std::vector<float> worse = constantPixels(8, 4, 1.0F);
    worse[5] = -0.02F;  // 2 % of the mean
    EXPECT_THROW((void)EnvironmentMap::fromPixels(8, 4, std::move(worse), "sky.exr"), InputError);
}

void writeExr(const std::filesystem::path& file, int w, int h, const std::vector<float>& rgb) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    const OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(file.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    ASSERT_TRUE(out->close());
}

TEST(EnvironmentMap, FilesRoundTripAndBadFilesAreNamed) {
    const test::TempDir dir;
    Environment spec;
    spec.file = dir.path() / "grey.exr";
    writeExr(spec.file, 16, 8, constantPixels(16, 8, 0.5F));
    const EnvironmentMap env = EnvironmentMap::load(spec);
    EXPECT_EQ(env.width(), 16);
    EXPECT_NEAR(env.radiance({0.3, 0.4, 0.5}).y(), 0.5, 1e-6);

    std::vector<float> with_inf = constantPixels(16, 8, 0.5F);
    with_inf[3 * 20] = std::numeric_limits<float>::infinity();
    spec.file = dir.path() / "inf.exr";
    writeExr(spec.file, 16, 8, with_inf);
    EXPECT_THROW((void)EnvironmentMap::load(spec), InputError);
    try {
        (void)EnvironmentMap::load(spec);
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("inf.exr"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("infinite"), std::string::npos) << e.what();
    }

    for (const char* name : {"not-an-image.exr", "missing.exr"}) {
        spec.file = dir.path() / name;
        if (std::string(name) == "not-an-image.exr") dir.write(name, "this is text, not OpenEXR");
        try {
            (void)EnvironmentMap::load(spec);
            FAIL() << "accepted " << name;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace paintlab::raymaps
