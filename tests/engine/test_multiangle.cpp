#include "paintlab/engine/multiangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab {
namespace {

// A Lambertian BRDF rho(lambda)/pi: its reflectance factor is rho at every geometry.
class LambertianBrdf final : public SpectralBrdf {
public:
    explicit LambertianBrdf(std::vector<double> rho)
        : m_rho(std::move(rho)), m_nm(visibleBands(m_rho.size())) {}
    std::span<const double> wavelengthsNm() const override { return m_nm; }
    void eval(const Direction& wi, const Direction& wo, std::span<double> out) const override {
        for (std::size_t i = 0; i < out.size(); ++i)
            out[i] = wi.z > 0.0 && wo.z > 0.0 ? m_rho[i] / std::numbers::pi : 0.0;
    }

private:
    std::vector<double> m_rho;
    std::vector<double> m_nm;
};

// A "flake-like" BRDF bright near the specular direction only.
class SpecularLobeBrdf final : public SpectralBrdf {
public:
    std::span<const double> wavelengthsNm() const override { return m_nm; }
    void eval(const Direction& wi, const Direction& wo, std::span<double> out) const override {
        const Direction mirror{-wi.x, -wi.y, wi.z};
        const double cos_to_mirror = mirror.x * wo.x + mirror.y * wo.y + mirror.z * wo.z;
        for (double& v : out) v = 0.02 + 5.0 * std::pow(std::max(0.0, cos_to_mirror), 40.0);
    }

private:
    std::vector<double> m_nm = visibleBands(41);
};

TEST(MultiAngle, GeometriesFollowTheAspecularConvention) {
    // 45as45 looks along the normal; 45as110 from 65° on the light's side; 45as-15 from 60° opposite.
    EXPECT_NEAR(multiAngleGeometry(45.0).wo.z, 1.0, 1e-15);
    const auto g110 = multiAngleGeometry(110.0);
    EXPECT_NEAR(std::acos(g110.wo.z) * 180.0 / std::numbers::pi, 65.0, 1e-12);
    EXPECT_GT(g110.wo.x, 0.0);  // same side as the light (wi.x > 0)
    const auto g_15 = multiAngleGeometry(-15.0);
    EXPECT_NEAR(std::acos(g_15.wo.z) * 180.0 / std::numbers::pi, 60.0, 1e-12);
    EXPECT_LT(g_15.wo.x, 0.0);
    // Aspecular angle = angle between wo and the mirror direction of wi.
    for (double as : kAspecularAnglesDeg) {
        const auto g = multiAngleGeometry(as);
        const double cos_as = -g.wi.x * g.wo.x - g.wi.y * g.wo.y + g.wi.z * g.wo.z;
        EXPECT_NEAR(std::acos(std::clamp(cos_as, -1.0, 1.0)) * 180.0 / std::numbers::pi, std::abs(as), 1e-9);
    }
    EXPECT_THROW(multiAngleGeometry(140.0), std::invalid_argument);
}

constexpr double kDeg = std::numbers::pi / 180.0;

double angleDeg(const Direction& a, const Direction& b) {
    return std::acos(std::clamp(a.x * b.x + a.y * b.y + a.z * b.z, -1.0, 1.0)) / kDeg;
}

void expectDirection(const Direction& actual, const Direction& expected, double tolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(MultiAngle, OutOfPlaneDetectorTurnsAboutTheSpecularDirection) {
    // 45as25az90 by hand: the specular direction r = (-sin 45, 0, cos 45); the
    // detector 25° from r in the plane through r perpendicular to the plane of
    // incidence, on the -y side (multiangle.h). 1e-15: rounding of a few sines.
    const double s45 = std::sin(45.0 * kDeg);
    const double c25 = std::cos(25.0 * kDeg);
    const double s25 = std::sin(25.0 * kDeg);
    const MultiAngleGeometry plus = multiAngleDirections(45.0, 25.0, 90.0);
    expectDirection(plus.wi, {s45, 0.0, s45}, 1e-15);
    expectDirection(plus.wo, {-s45 * c25, -s25, s45 * c25}, 1e-15);
    expectDirection(multiAngleDirections(45.0, 25.0, -90.0).wo, {-s45 * c25, s25, s45 * c25}, 1e-15);
    // Not a turn about the normal (which would keep the in-plane polar angle of 20°).
    EXPECT_NEAR(detectorPolarAngleDeg(plus), std::acos(s45 * c25) / kDeg, 1e-12);
    EXPECT_GT(detectorPolarAngleDeg(plus), 50.0);
    // Every azimuth keeps the detector as far from the specular direction.
    const Direction mirror{-plus.wi.x, -plus.wi.y, plus.wi.z};
    for (double az : {-170.0, -90.0, -30.0, 10.0, 60.0, 135.0})
        EXPECT_NEAR(angleDeg(multiAngleDirections(45.0, 25.0, az).wo, mirror), 25.0, 1e-9) << az;
}

TEST(MultiAngle, OutOfPlaneDirectionsAreXRitesNames) {
    // X-Rite's direction vectors for its out-of-plane names (colorimetry tests
    // of a public X-Rite web application, docs/ARCHITECTURE.md "Multi-angle
    // geometries"), light along (sin θi, 0, -cos θi): detector A =
    // (0.640856, 0.422618, 0.640856) is 45as25az90 and 15as38.3az43, B =
    // (0, 0.707, 0.707) is 45as60az125.3 and 15as46.9az104.5, their mirror
    // images in y the negative azimuths. Our light is at phi 0 where X-Rite's
    // is at phi 180: the same vectors turned 180° about the normal.
    const Direction a{-0.640856, -0.422618, 0.640856};
    const Direction b{0.0, -std::sqrt(0.5), std::sqrt(0.5)};
    // X-Rite rounds the names to 0.1° (and A to 6 digits): 2e-3 in each coordinate.
    expectDirection(multiAngleDirections(45.0, 25.0, 90.0).wo, a, 2e-3);
    expectDirection(multiAngleDirections(15.0, 38.3, 43.0).wo, a, 2e-3);
    expectDirection(multiAngleDirections(45.0, 60.0, 125.3).wo, b, 2e-3);
    expectDirection(multiAngleDirections(15.0, 46.9, 104.5).wo, b, 2e-3);
    expectDirection(multiAngleDirections(45.0, 25.0, -90.0).wo, {a.x, -a.y, a.z}, 2e-3);
    expectDirection(multiAngleDirections(15.0, 38.3, -43.0).wo, {a.x, -a.y, a.z}, 2e-3);
    expectDirection(multiAngleDirections(45.0, 60.0, -125.3).wo, {b.x, -b.y, b.z}, 2e-3);
    expectDirection(multiAngleDirections(15.0, 46.9, -104.5).wo, {b.x, -b.y, b.z}, 2e-3);
}

TEST(MultiAngle, AzimuthZeroAndHalfTurnAreTheInPlaneGeometry) {
    for (double as : kAspecularAnglesDeg) {
        const MultiAngleGeometry in_plane = multiAngleGeometry(as);
        // Azimuth 0 is the in-plane geometry exactly (the same formula as before azimuths).
        expectDirection(multiAngleDirections(45.0, as, 0.0).wo, in_plane.wo, 0.0);
        // A half turn about the specular direction from the far side is the in-plane +as (multiangle.h).
        expectDirection(multiAngleDirections(45.0, as, 180.0).wo, in_plane.wo, 1e-15);
        expectDirection(multiAngleDirections(45.0, as, -180.0).wo, in_plane.wo, 1e-15);
    }
    // Below the horizon: reported through the polar angle, never thrown.
    EXPECT_GE(detectorPolarAngleDeg(multiAngleDirections(75.0, 60.0, 30.0)), 90.0);
}

// Rounding noise in a file's azimuth (1e-12) is the plane of incidence at +as,
// not the out-of-plane formula's limit at -as (30° from the normal instead of 60°).
TEST(MultiAngle, AzimuthRoundingNoiseStaysInThePlane) {
    for (double as : kAspecularAnglesDeg)
        for (double noise : {1e-12, -1e-9, 5e-8}) {
            const MultiAngleGeometry g = multiAngleDirections(45.0, as, noise);
            expectDirection(g.wo, multiAngleGeometry(as).wo, 0.0);
        }
    EXPECT_NEAR(detectorPolarAngleDeg(multiAngleDirections(45.0, 15.0, 1e-12)), 30.0, 1e-12);
    // From 1e-7 on the azimuth counts: the same limit as X-Rite's naming.
    EXPECT_FALSE(isInPlane(kInPlaneAzimuthDeg));
}

// The forms that repeat another name's direction are refused, X-Rite's are not.
TEST(MultiAngle, OutOfPlaneNamesHaveOneForm) {
    EXPECT_EQ(outOfPlaneFormProblem(25.0, 90.0), "");
    EXPECT_EQ(outOfPlaneFormProblem(25.0, -90.0), "");
    EXPECT_EQ(outOfPlaneFormProblem(180.0, 45.0), "");
    // 45as-25az90 is 45as25az-90.
    expectDirection(multiAngleDirections(45.0, -25.0, 90.0).wo, multiAngleDirections(45.0, 25.0, -90.0).wo,
                    1e-15);
    EXPECT_NE(outOfPlaneFormProblem(-25.0, 90.0), "");
    EXPECT_NE(outOfPlaneFormProblem(0.0, 90.0), "");  // the specular direction at any azimuth
    EXPECT_NE(outOfPlaneFormProblem(200.0, 90.0), "");
    EXPECT_NE(outOfPlaneFormProblem(25.0, 180.0), "");  // the in-plane 45as25
    EXPECT_NE(outOfPlaneFormProblem(25.0, -180.0), "");
}

TEST(MultiAngle, LambertianWhiteIsTheWhitePointEverywhereWithNoFlop) {
    const LambertianBrdf white(std::vector<double>(41, 1.0));
    const auto report = multiAngleColours(white);
    ASSERT_EQ(report.colours.size(), 6u);
    for (const auto& c : report.colours) {
        // The perfect diffuser is the reference white: L* = 100, a* = b* = 0
        // (1e-6: the 10 nm BRDF grid resampled to the 5 nm tables is exact for a constant).
        EXPECT_NEAR(c.lab.L, 100.0, 1e-6);
        EXPECT_NEAR(c.lab.a, 0.0, 1e-6);
        EXPECT_NEAR(c.lab.b, 0.0, 1e-6);
    }
    EXPECT_EQ(report.flop_index, 0.0);
}

TEST(MultiAngle, GreyCardHasTheClosedFormLightness) {
    // Y = 0.18 gives L* = 116 * 0.18^(1/3) - 16 (CIE 15, above the linear branch).
    const auto report = multiAngleColours(LambertianBrdf(std::vector<double>(41, 0.18)));
    for (const auto& c : report.colours) EXPECT_NEAR(c.lab.L, 116.0 * std::cbrt(0.18) - 16.0, 1e-6);
}

TEST(MultiAngle, FlopIndexOfASpecularLobe) {
    const auto report = multiAngleColours(SpecularLobeBrdf());
    // Near-specular much lighter than far-from-specular: a metallic-like flop.
    EXPECT_GT(report.colours[1].lab.L, report.colours[5].lab.L);
    const double expected =
        flopIndex(report.colours[1].lab.L, report.colours[3].lab.L, report.colours[5].lab.L);
    EXPECT_DOUBLE_EQ(report.flop_index, expected);
    EXPECT_GT(report.flop_index, 5.0);
}

TEST(MultiAngle, FlopIndexFormula) {
    // Direct evaluation of X-Rite's definition at round numbers.
    EXPECT_NEAR(flopIndex(120.0, 60.0, 20.0), 2.69 * std::pow(100.0, 1.11) / std::pow(60.0, 0.86), 1e-12);
    EXPECT_EQ(flopIndex(50.0, 50.0, 50.0), 0.0);
    EXPECT_EQ(flopIndex(10.0, 0.0, 5.0), 0.0);
}

}  // namespace
}  // namespace paintlab
