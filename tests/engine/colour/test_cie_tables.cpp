// The CIE tables as read from colord-data, and what is computed from them:
// white points against published values, and spectral integration.

#include "paintlab/engine/colour/cie_tables.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace paintlab {
namespace {

constexpr std::array<Observer, 2> kObservers{Observer::Cie1931_2deg, Observer::Cie1964_10deg};
constexpr std::array<Illuminant, 3> kIlluminants{Illuminant::D65, Illuminant::D50, Illuminant::A};

// The figures the tables actually give, in the test log.
void report(Illuminant illuminant, Observer observer, const Xyz& white) {
    const std::string key = "white_" + std::string(toString(illuminant)) + "_" +
                            (observer == Observer::Cie1931_2deg ? "2deg" : "10deg");
    char text[96];
    std::snprintf(text, sizeof text, "%.7f %.7f %.7f", white.X, white.Y, white.Z);
    ::testing::Test::RecordProperty(key, text);
    std::printf("%s: X = %.7f  Y = %.7f  Z = %.7f\n", key.c_str(), white.X, white.Y, white.Z);
}

TEST(CieTables, ObserversAreOnTheir5nmGridWithCiePublishedValues) {
    for (const Observer observer : kObservers) {
        const ColourMatchingFunctions& functions = cmf(observer);
        const std::vector<double>& grid = functions.yBar.wavelengthsNm();
        ASSERT_EQ(grid.size(), 95U);
        EXPECT_EQ(grid.front(), 360.0);
        EXPECT_EQ(grid.back(), 830.0);
        EXPECT_EQ(grid[1] - grid[0], 5.0);  // exact: the grid is built from whole numbers
        EXPECT_EQ(functions.xBar.wavelengthsNm(), grid);
        EXPECT_EQ(functions.zBar.wavelengthsNm(), grid);
        // Both observers are normalised to a y-bar peak of about 1 (CIE 15:2004 tables).
        EXPECT_NEAR(functions.yBar.maxValue(), 1.0, 1e-3);
    }
    // Spot values of the CIE 1931 observer as printed by the CIE (5 decimals);
    // colord stores them via float, e.g. 0.9148501 for 0.91485: 1e-6 covers that.
    const ColourMatchingFunctions& cie1931 = cmf(Observer::Cie1931_2deg);
    EXPECT_NEAR(cie1931.yBar(555.0), 1.00000, 1e-6);
    EXPECT_NEAR(cie1931.xBar(600.0), 1.06220, 1e-6);
    EXPECT_NEAR(cie1931.zBar(445.0), 1.78260, 1e-6);
    EXPECT_NEAR(cie1931.yBar(535.0), 0.91485, 1e-6);
}

TEST(CieTables, IlluminantsAreNormalisedAt560nm) {
    // colord divides the CIE's S(560 nm) = 100 by 100; the files hold 1.0 exactly there.
    EXPECT_EQ(illuminantSpd(Illuminant::D65)(560.0), 1.0);
    EXPECT_EQ(illuminantSpd(Illuminant::D50)(560.0), 1.0);
    EXPECT_EQ(illuminantSpd(Illuminant::A)(560.0), 1.0);
    EXPECT_EQ(illuminantSpd(Illuminant::D65).wavelengthsNm().size(), 107U);  // 300-830 nm, 5 nm
    EXPECT_EQ(illuminantSpd(Illuminant::D50).wavelengthsNm().size(), 81U);   // 380-780 nm, 5 nm
    EXPECT_EQ(illuminantSpd(Illuminant::A).wavelengthsNm().size(), 531U);    // 300-830 nm, 1 nm
}

TEST(CieTables, IlluminantAMatchesItsDefiningPlanckFormula) {
    // CIE 15:2004 section 3.1: S_A(lambda) = 100 (560/lambda)^5 (exp(c2 / (2848 * 560)) - 1)
    // / (exp(c2 / (2848 lambda)) - 1), c2 = 1.435e7 nm K. An independent truth for the
    // parser's 1 nm grid and values (colord scales by 1/100).
    const Spectrum& a = illuminantSpd(Illuminant::A);
    const double c2 = 1.435e7;
    for (std::size_t i = 0; i < a.values().size(); ++i) {
        const double nm = a.wavelengthsNm()[i];
        EXPECT_EQ(nm, 300.0 + static_cast<double>(i));  // whole nanometres, exactly
        const double planck =
            std::pow(560.0 / nm, 5.0) * std::expm1(c2 / (2848.0 * 560.0)) / std::expm1(c2 / (2848.0 * nm));
        // The file prints 6 significant figures: half a unit in the 6th (plus rounding of the formula).
        const double halfUnit = 0.5 * std::pow(10.0, std::floor(std::log10(planck)) - 5.0);
        EXPECT_NEAR(a.values()[i], planck, halfUnit + 1e-12) << nm << " nm";
    }
}

TEST(CieTables, D65WhitePoint2deg) {
    const Xyz white = whitePoint(Illuminant::D65, Observer::Cie1931_2deg);
    report(Illuminant::D65, Observer::Cie1931_2deg, white);
    EXPECT_EQ(white.Y, 1.0);
    // Published: X = 0.95047, Z = 1.08883 (ASTM E308-01, D65 / 1931 observer; the values
    // used by most software). Summing colord's 5 nm tables over 360-830 nm per CIE 15 gives
    // X = 0.950467, Z = 1.088969. X agrees to 5 decimals (half a unit: 5e-6).
    EXPECT_NEAR(white.X, 0.95047, 5e-6);
    // Z is 1.4e-4 higher. Not a table or parsing error but the sampling interval: the
    // published figure comes from 1 nm data. Checked offline with the CIE 1931 1 nm table
    // (CVRL ciexyz31_1, 380-780 nm; D65 interpolated linearly to 1 nm; 360-375 nm at 5 nm):
    // Z = 1.08878, X = 0.95046, within 5e-5 of the published pair. The range matters as
    // much: summing the 5 nm tables over 380-780 nm only gives Z = 1.08880, X = 0.95043.
    // 2e-4 admits the 5 nm-vs-1 nm difference and nothing larger.
    EXPECT_NEAR(white.Z, 1.08883, 2e-4);
    // What the 5 nm tables give for Z, to 5 decimals (half a unit): a regression check of the sum.
    EXPECT_NEAR(white.Z, 1.08897, 5e-6);
}

TEST(CieTables, D65WhitePoint10deg) {
    const Xyz white = whitePoint(Illuminant::D65, Observer::Cie1964_10deg);
    report(Illuminant::D65, Observer::Cie1964_10deg, white);
    // Published (ASTM E308-01, D65 / 1964 observer): X = 0.94811, Z = 1.07304. The 5 nm
    // tables give X = 0.948120 and Z = 1.073244: the same 5 nm-vs-1 nm sampling difference
    // as for 2 degrees (Z +2.0e-4, X +1.0e-5); tolerances are those differences rounded up.
    EXPECT_NEAR(white.X, 0.94811, 2e-5);
    EXPECT_NEAR(white.Z, 1.07304, 3e-4);
}

TEST(CieTables, D50WhitePoint2deg) {
    const Xyz white = whitePoint(Illuminant::D50, Observer::Cie1931_2deg);
    report(Illuminant::D50, Observer::Cie1931_2deg, white);
    // Published (ASTM E308-01, D50 / 1931 observer): X = 0.96422, Z = 0.82521.
    // colord's CIE-D50.sp covers only 380-780 nm and is printed to 3 decimals (0.245 for the
    // CIE's 24.488 / 100 at 380 nm), so it gives X = 0.964125, Z = 0.824986. Truncating to
    // 380-780 nm alone moves the D65 Z by 1.7e-4 (measured above), the 3-decimal rounding a
    // few 1e-5 more: 2e-4 and 3e-4 admit those and nothing larger.
    EXPECT_NEAR(white.X, 0.96422, 2e-4);
    EXPECT_NEAR(white.Z, 0.82521, 3e-4);
}

TEST(CieTables, AWhitePointsAgreeWithPublishedValuesTo5Decimals) {
    // Illuminant A is smooth, and colord's table is its 1 nm formula: 5 nm sampling is enough
    // here, and the published ASTM E308-01 values (X = 1.09850, Z = 0.35585 for 2 degrees;
    // 1.11144, 0.35200 for 10 degrees) are reproduced to 5 decimals (half a unit: 5e-6, plus
    // the published figures' own rounding: 1e-5).
    const Xyz two = whitePoint(Illuminant::A, Observer::Cie1931_2deg);
    report(Illuminant::A, Observer::Cie1931_2deg, two);
    EXPECT_NEAR(two.X, 1.09850, 1e-5);
    EXPECT_NEAR(two.Z, 0.35585, 1e-5);
    const Xyz ten = whitePoint(Illuminant::A, Observer::Cie1964_10deg);
    report(Illuminant::A, Observer::Cie1964_10deg, ten);
    EXPECT_NEAR(ten.X, 1.11144, 1e-5);
    EXPECT_NEAR(ten.Z, 0.35200, 1e-5);
}

TEST(CieTables, PerfectWhiteReflectorGivesYOneAndTheWhitePoint) {
    for (const Illuminant illuminant : kIlluminants)
        for (const Observer observer : kObservers) {
            const Xyz white = whitePoint(illuminant, observer);
            const Xyz xyz = reflectanceToXyz(Spectrum(1.0), illuminant, observer);
            // The same ~95 products summed in one order vs divided once: a few ulp.
            EXPECT_NEAR(xyz.Y, 1.0, 1e-12);
            EXPECT_NEAR(xyz.X, white.X, 1e-12);
            EXPECT_NEAR(xyz.Z, white.Z, 1e-12);
        }
}

TEST(CieTables, GreyReflectorHasTheClosedFormLightness) {
    const Xyz white = whitePoint(Illuminant::D65, Observer::Cie1931_2deg);
    const Xyz grey = reflectanceToXyz(Spectrum(0.18), Illuminant::D65, Observer::Cie1931_2deg);
    const Lab lab = xyzToLab(grey, white);
    // 116 * 0.18^(1/3) - 16 = 49.496; rounding of ~95 products only.
    EXPECT_NEAR(lab.L, 116.0 * std::cbrt(0.18) - 16.0, 1e-10);
    EXPECT_NEAR(lab.a, 0.0, 1e-10);
    EXPECT_NEAR(lab.b, 0.0, 1e-10);
}

TEST(CieTables, ReflectanceOnAnotherGridIsSampledWithEndsHeld) {
    // A 41-band 380-780 nm reflectance (the fast model's colorimetry grid): its end values
    // are held out to 360 and 830 nm, so a flat one integrates like the constant.
    const std::vector<double> bands = visibleBands(41);
    const Spectrum flat(bands, std::vector<double>(bands.size(), 0.4));
    const Xyz fromBands = reflectanceToXyz(flat, Illuminant::D65, Observer::Cie1964_10deg);
    const Xyz fromConstant = reflectanceToXyz(Spectrum(0.4), Illuminant::D65, Observer::Cie1964_10deg);
    EXPECT_NEAR(fromBands.X, fromConstant.X, 1e-14);  // same products, same order
    EXPECT_NEAR(fromBands.Y, fromConstant.Y, 1e-14);
    EXPECT_NEAR(fromBands.Z, fromConstant.Z, 1e-14);
    // A long-pass reflectance (dark below 600 nm) is red: a* > 0, and darker than white.
    std::vector<double> longPass(bands.size());
    for (std::size_t i = 0; i < bands.size(); ++i) longPass[i] = bands[i] < 600.0 ? 0.05 : 0.9;
    const Lab red =
        xyzToLab(reflectanceToXyz(Spectrum(bands, longPass), Illuminant::D65, Observer::Cie1931_2deg),
                 whitePoint(Illuminant::D65, Observer::Cie1931_2deg));
    EXPECT_GT(red.a, 30.0);
    EXPECT_LT(red.L, 100.0);
}

TEST(CieTables, ConcurrentFirstUseIsSafeAndConsistent) {
    // Function-local statics make the first load thread-safe (C++11 [stmt.dcl]); every
    // thread must see the same tables.
    std::vector<std::thread> threads;
    std::vector<Xyz> results(8);
    for (std::size_t t = 0; t < results.size(); ++t)
        threads.emplace_back([&results, t] {
            const Illuminant illuminant = kIlluminants[t % kIlluminants.size()];
            const Observer observer = kObservers[t % kObservers.size()];
            results[t] = whitePoint(illuminant, observer);
        });
    for (auto& thread : threads) thread.join();
    for (std::size_t t = 0; t < results.size(); ++t) {
        const Xyz expected =
            whitePoint(kIlluminants[t % kIlluminants.size()], kObservers[t % kObservers.size()]);
        EXPECT_EQ(results[t].X, expected.X);  // the same cached numbers, bit for bit
        EXPECT_EQ(results[t].Z, expected.Z);
    }
}

}  // namespace
}  // namespace paintlab
