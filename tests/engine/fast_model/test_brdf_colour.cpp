// Spectral -> XYZ / CIELAB / linear sRGB of a BRDF (brdf_colour.h) against closed forms.
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/spectrum.h"

#include "test_recipes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace paintlab {
namespace {

// A Lambertian BRDF rho/pi, its reflectance factor rho at every geometry.
class LambertianBrdf final : public SpectralBrdf {
public:
    explicit LambertianBrdf(double rho) : m_rho(rho) {}
    std::span<const double> wavelengthsNm() const override { return m_nm; }
    void eval(const Direction& wi, const Direction& wo, std::span<double> out) const override {
        for (double& v : out) v = wi.z > 0.0 && wo.z > 0.0 ? m_rho / std::numbers::pi : 0.0;
    }

private:
    double m_rho;
    std::vector<double> m_nm = visibleBands(41);
};

const Direction kWi = directionFromAnglesDeg(45.0, 0.0);
const Direction kWo = directionFromAnglesDeg(30.0, 180.0);

// sRGB(D65 white) = (1, 1, 1) holds to the standard's 4-decimal matrix (1e-4) and
// colord's 5 nm D65, whose Z is 1.08897 instead of the published 1.08883 (VALIDATION.md,
// colour science): together below 3e-4 per channel.
constexpr double kSrgbWhiteTolerance = 3e-4;

TEST(BrdfColour, PerfectDiffuserIsTheWhitePoint) {
    const LambertianBrdf white(1.0);
    for (const ColourConditions& conditions :
         {ColourConditions{}, ColourConditions{Illuminant::D65, Observer::Cie1931_2deg},
          ColourConditions{Illuminant::A, Observer::Cie1964_10deg},
          ColourConditions{Illuminant::D50, Observer::Cie1931_2deg}}) {
        const SpectralColour c = reflectanceFactorColour(white, kWi, kWo, conditions);
        const Xyz w = whitePoint(conditions.illuminant, conditions.observer);
        // pi f = 1 at every wavelength: the object is the reference white itself. 1e-12:
        // the same sums as whitePoint, rounding only.
        for (double r : c.reflectance) EXPECT_NEAR(r, 1.0, 1e-15);
        EXPECT_NEAR(c.xyz.X, w.X, 1e-12);
        EXPECT_NEAR(c.xyz.Y, 1.0, 1e-12);
        EXPECT_NEAR(c.xyz.Z, w.Z, 1e-12);
        EXPECT_NEAR(c.lab.L, 100.0, 1e-9);
        EXPECT_NEAR(c.lab.a, 0.0, 1e-9);
        EXPECT_NEAR(c.lab.b, 0.0, 1e-9);
        // sRGB is always the D65 / 2° colour (brdf_colour.h): white is (1, 1, 1) whatever
        // illuminant and observer Lab uses.
        EXPECT_NEAR(c.linear_srgb.r, 1.0, kSrgbWhiteTolerance);
        EXPECT_NEAR(c.linear_srgb.g, 1.0, kSrgbWhiteTolerance);
        EXPECT_NEAR(c.linear_srgb.b, 1.0, kSrgbWhiteTolerance);
    }
}

TEST(BrdfColour, GreyCardFollowsTheClosedForms) {
    const double rho = 0.18;
    const SpectralColour grey = reflectanceFactorColour(LambertianBrdf(rho), kWi, kWo);
    const SpectralColour white = reflectanceFactorColour(LambertianBrdf(1.0), kWi, kWo);
    // A constant reflectance scales XYZ and linear sRGB (both linear in the spectrum):
    // Y = rho, L* = 116 rho^(1/3) - 16 (CIE 15, above the linear branch), a* = b* = 0.
    EXPECT_NEAR(grey.xyz.Y, rho, 1e-12);
    EXPECT_NEAR(grey.lab.L, 116.0 * std::cbrt(rho) - 16.0, 1e-9);
    EXPECT_NEAR(grey.lab.a, 0.0, 1e-9);
    EXPECT_NEAR(grey.lab.b, 0.0, 1e-9);
    EXPECT_NEAR(grey.linear_srgb.r, rho * white.linear_srgb.r, 1e-12);
    EXPECT_NEAR(grey.linear_srgb.g, rho * white.linear_srgb.g, 1e-12);
    EXPECT_NEAR(grey.linear_srgb.b, rho * white.linear_srgb.b, 1e-12);
    // Encoded, 0.18 is the familiar mid grey 1.055 * 0.18^(1/2.4) - 0.055 = 0.4614 (IEC 61966-2-1).
    EXPECT_NEAR(srgbEncode(grey.linear_srgb.g), 1.055 * std::pow(rho, 1.0 / 2.4) - 0.055, 1e-3);
}

TEST(BrdfColour, SpectrumColourIsLinearInTheSpectrum) {
    // XYZ is a linear functional of the reflectance: the colour of a sum is the sum of the
    // colours (rounding only). Two complementary steps at 550 nm add up to the white.
    const std::vector<double> nm = visibleBands(81);
    std::vector<double> blue(nm.size());
    std::vector<double> red(nm.size());
    std::vector<double> sum(nm.size());
    for (std::size_t i = 0; i < nm.size(); ++i) {
        blue[i] = nm[i] < 550.0 ? 0.9 : 0.1;
        red[i] = 0.7 - 0.5 * blue[i];
        sum[i] = blue[i] + red[i];
    }
    const SpectralColour b = spectrumColour(nm, blue);
    const SpectralColour r = spectrumColour(nm, red);
    const SpectralColour s = spectrumColour(nm, sum);
    EXPECT_NEAR(b.xyz.X + r.xyz.X, s.xyz.X, 1e-12);
    EXPECT_NEAR(b.xyz.Y + r.xyz.Y, s.xyz.Y, 1e-12);
    EXPECT_NEAR(b.xyz.Z + r.xyz.Z, s.xyz.Z, 1e-12);
    EXPECT_NEAR(b.linear_srgb.r + r.linear_srgb.r, s.linear_srgb.r, 1e-12);
    EXPECT_NEAR(b.linear_srgb.b + r.linear_srgb.b, s.linear_srgb.b, 1e-12);
    // And the hues go where they must: the short-wavelength step is blue (b* < 0, B > R),
    // the other yellowish-red (b* > 0, R > B).
    EXPECT_LT(b.lab.b, 0.0);
    EXPECT_GT(b.linear_srgb.b, b.linear_srgb.r);
    EXPECT_GT(r.lab.b, 0.0);
    EXPECT_GT(r.linear_srgb.r, r.linear_srgb.b);
}

TEST(BrdfColour, AlbedoOfALosslessPaintIsWhite) {
    // A clear coat over a perfectly white Lambertian base loses nothing: the albedo,
    // mirror term included, is 1 at every wavelength and incidence (energy conservation of
    // the fast model, 1e-6 in test_layered_brdf.cpp), so its colour is the white point.
    Recipe r = test::oneLayerRecipe(1.5, 40.0, LambertianSubstrate{Spectrum(1.0)});
    FastModelSettings s;
    s.nodes = 16;
    s.orders = 4;
    s.bands = 8;
    const LayeredBrdf brdf = computeLayeredBrdf(r, s);
    for (double theta : {0.0, 45.0, 75.0}) {
        const SpectralColour c = albedoColour(brdf, directionFromAnglesDeg(theta, 0.0));
        // L* = 116 Y^(1/3) - 16 moves by 116/3 dY near Y = 1: 1e-6 in albedo is 4e-5 in L*.
        EXPECT_NEAR(c.lab.L, 100.0, 1e-4) << theta;
        EXPECT_NEAR(c.lab.a, 0.0, 1e-4) << theta;
        EXPECT_NEAR(c.lab.b, 0.0, 1e-4) << theta;
    }
    // The reflectance factor of the same paint at a multi-angle geometry is what
    // multiAngleColours reports there (it is computed by this helper).
    const MultiAngleReport report = multiAngleColours(brdf);
    const MultiAngleGeometry g = multiAngleGeometry(report.colours[2].aspecular_deg);
    const SpectralColour c = reflectanceFactorColour(brdf, g.wi, g.wo);
    EXPECT_EQ(c.lab.L, report.colours[2].lab.L);
    EXPECT_EQ(c.reflectance, report.colours[2].reflectance_factor);
}

TEST(BrdfColour, RejectsMismatchedSpectra) {
    const std::vector<double> nm{400.0, 500.0, 600.0};
    auto field = [&](std::vector<double> values, std::vector<double> grid) {
        try {
            spectrumColour(grid, values);
        } catch (const InputError& e) {
            return e.field();
        }
        return std::string();
    };
    EXPECT_EQ(field({0.5, 0.5, 0.5}, nm), "");
    EXPECT_EQ(field({0.5, 0.5}, nm), "reflectance");
    EXPECT_EQ(field({0.5, std::nan(""), 0.5}, nm), "reflectance");
    EXPECT_EQ(field({0.5, 0.5, 0.5}, {400.0, 400.0, 600.0}), "reflectance");
    EXPECT_EQ(field({}, {}), "reflectance");
}

}  // namespace
}  // namespace paintlab
