#include "paintlab/engine/multiangle.h"

#include <gtest/gtest.h>

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
