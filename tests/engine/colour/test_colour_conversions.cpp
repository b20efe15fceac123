// CIELAB and sRGB conversions: closed forms, round trips, and the anchors the
// standards define (CIE 15:2004 section 8.2.1, IEC 61966-2-1:1999).

#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/colour/colour.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace paintlab {
namespace {

// IEC 61966-2-1 section 5.2 states its reference white as these 4-decimal
// XYZ values (x = 0.3127, y = 0.3290, Y = 1).
constexpr Xyz kIecD65White{0.9505, 1.0000, 1.0890};

TEST(CieLab, WhiteIsL100AndNeutral) {
    const Lab lab = xyzToLab(kIecD65White, kIecD65White);
    // t = 1 exactly, cbrt(1) = 1 exactly: no rounding anywhere.
    EXPECT_EQ(lab.L, 100.0);
    EXPECT_EQ(lab.a, 0.0);
    EXPECT_EQ(lab.b, 0.0);
}

TEST(CieLab, Grey18PercentHasTheClosedFormLightness) {
    const Xyz white = whitePoint(Illuminant::D65, Observer::Cie1931_2deg);
    const Xyz grey{0.18 * white.X, 0.18 * white.Y, 0.18 * white.Z};
    const Lab lab = xyzToLab(grey, white);
    const double expectedL = 116.0 * std::cbrt(0.18) - 16.0;  // 49.496..., above the linear branch
    // Same arithmetic up to the rounding of 0.18 * white / white: a few ulp.
    EXPECT_NEAR(lab.L, expectedL, 1e-12);
    EXPECT_NEAR(lab.L, 49.496, 1e-3);  // the commonly quoted "L* of 18 % grey is about 49.5"
    EXPECT_NEAR(lab.a, 0.0, 1e-12);    // a neutral: rounding only
    EXPECT_NEAR(lab.b, 0.0, 1e-12);
}

TEST(CieLab, LinearBranchMeetsTheCubeRootBranch) {
    // With the exact epsilon and kappa both branches give L* = 8 at Y/Yn = 216/24389.
    const double yBreak = 216.0 / 24389.0;
    const Lab below = xyzToLab({0.0, yBreak * (1.0 - 1e-12), 0.0}, {1.0, 1.0, 1.0});
    const Lab above = xyzToLab({0.0, yBreak * (1.0 + 1e-12), 0.0}, {1.0, 1.0, 1.0});
    // A 2e-12 relative step in Y moves L* by ~1e-11; a jump between branches would be far larger
    // (with the rounded 0.008856 and 903.3 it is 3.3e-5).
    EXPECT_NEAR(below.L, 8.0, 1e-9);
    EXPECT_NEAR(above.L, 8.0, 1e-9);
}

TEST(CieLab, RoundTripThroughXyz) {
    const Xyz white = whitePoint(Illuminant::D50, Observer::Cie1931_2deg);
    std::mt19937_64 random(1976);
    std::uniform_real_distribution<double> lightness(0.0, 100.0);
    std::uniform_real_distribution<double> opponent(-128.0, 128.0);
    for (int i = 0; i < 5000; ++i) {
        // Includes the dark linear branch and, for strong b*, negative Z: both must invert exactly.
        const Lab lab{lightness(random), opponent(random), opponent(random)};
        const Lab back = xyzToLab(labToXyz(lab, white), white);
        // cbrt of a cube and the linear branch each lose a few ulp on values up to ~200.
        EXPECT_NEAR(back.L, lab.L, 1e-10);
        EXPECT_NEAR(back.a, lab.a, 1e-10);
        EXPECT_NEAR(back.b, lab.b, 1e-10);
    }
}

TEST(CieLab, LchRoundTripAndHueConvention) {
    const Lch lch = labToLch(Lab{50.0, 0.0, -20.0});
    EXPECT_NEAR(lch.C, 20.0, 1e-12);       // hypot: exact up to rounding
    EXPECT_NEAR(lch.h_deg, 270.0, 1e-12);  // hue in [0, 360), not -90
    EXPECT_EQ(labToLch(Lab{50.0, 0.0, 0.0}).h_deg, 0.0);
    const Lab back = lchToLab(lch);
    // sin/cos of 3 pi / 2 carry ~1e-16 relative error, times C = 20.
    EXPECT_NEAR(back.a, 0.0, 1e-12);
    EXPECT_NEAR(back.b, -20.0, 1e-12);
}

TEST(Srgb, D65WhiteMapsToOneOneOne) {
    // The 4-decimal matrix of IEC 61966-2-1 section 5.2 moves each channel by at most
    // 3 x 5e-5 x ~1.09 = 1.6e-4 from the unrounded value; the standard's own white
    // actually lands within 6e-5 of 1, and our 5 nm table white within 9e-5, so 1e-4
    // holds for both without hiding a wrong matrix entry (which would be off by >= 1e-3).
    const Rgb iec = xyzToLinearSrgb(kIecD65White);
    EXPECT_NEAR(iec.r, 1.0, 1e-4);
    EXPECT_NEAR(iec.g, 1.0, 1e-4);
    EXPECT_NEAR(iec.b, 1.0, 1e-4);
    const Rgb table = xyzToLinearSrgb(whitePoint(Illuminant::D65, Observer::Cie1931_2deg));
    EXPECT_NEAR(table.r, 1.0, 1e-4);
    EXPECT_NEAR(table.g, 1.0, 1e-4);
    EXPECT_NEAR(table.b, 1.0, 1e-4);
    // Encoded white is white too: the transfer function maps 1 to 1.055 - 0.055 = 1.
    const Rgb encoded = linearToSrgbEncoded({1.0, 1.0, 1.0});
    EXPECT_NEAR(encoded.r, 1.0, 1e-15);  // 1.055 - 0.055 in binary floating point: 1 ulp at most
}

TEST(Srgb, InverseMatrixAgreesWithThePublishedReverseMatrix) {
    // IEC 61966-2-1 section 5.3 (reverse transformation) publishes its own 4-decimal
    // matrix; ours is the exact inverse of the forward one, so they agree to the
    // rounding of both: a few 1e-5 on each entry, hence 1e-4 per unit input.
    constexpr std::array<std::array<double, 3>, 3> kReverse{{
        {0.4124, 0.3576, 0.1805},
        {0.2126, 0.7152, 0.0722},
        {0.0193, 0.1192, 0.9505},
    }};
    for (int column = 0; column < 3; ++column) {
        const Rgb unit{column == 0 ? 1.0 : 0.0, column == 1 ? 1.0 : 0.0, column == 2 ? 1.0 : 0.0};
        const Xyz xyz = linearSrgbToXyz(unit);
        const auto c = static_cast<std::size_t>(column);
        EXPECT_NEAR(xyz.X, kReverse[0][c], 1e-4);
        EXPECT_NEAR(xyz.Y, kReverse[1][c], 1e-4);
        EXPECT_NEAR(xyz.Z, kReverse[2][c], 1e-4);
    }
}

TEST(Srgb, MatrixRoundTripIsLossless) {
    std::mt19937_64 random(61966);
    std::uniform_real_distribution<double> unit(-0.2, 1.2);
    for (int i = 0; i < 2000; ++i) {
        const Xyz xyz{unit(random), unit(random), unit(random)};
        const Xyz back = linearSrgbToXyz(xyzToLinearSrgb(xyz));
        // Exact inverse in double; two 3x3 products with entries up to 3.2 lose ~1e-15.
        EXPECT_NEAR(back.X, xyz.X, 1e-12);
        EXPECT_NEAR(back.Y, xyz.Y, 1e-12);
        EXPECT_NEAR(back.Z, xyz.Z, 1e-12);
    }
}

TEST(Srgb, TransferFunctionRoundTripAndAnchors) {
    for (int i = -100; i <= 1100; ++i) {
        const double linear = i / 1000.0;
        // Away from the threshold both branches invert exactly: pow and rounding only.
        EXPECT_NEAR(srgbDecode(srgbEncode(linear)), linear, 1e-14) << linear;
        const Rgb back = srgbEncodedToLinear(linearToSrgbEncoded({linear, linear, linear}));
        EXPECT_NEAR(back.g, linear, 1e-14) << linear;
    }
    // The standard rounds its two thresholds separately (12.92 x 0.0031308 = 0.040449936, not
    // 0.04045), so linear values in a 5e-9 wide band just above 0.0031308 go out on the power
    // branch and come back on the linear one. The branches differ there by 2.3e-9 at most
    // (measured on this scan), far below an 8-bit step; 3e-9 bounds it. Kept as the standard
    // has it rather than "fixed", so our values match other sRGB implementations.
    for (int i = 0; i <= 20000; ++i) {
        const double linear = 0.0031307 + i * 1e-11;
        EXPECT_NEAR(srgbDecode(srgbEncode(linear)), linear, 3e-9) << linear;
    }
    EXPECT_EQ(srgbEncode(0.0), 0.0);
    EXPECT_EQ(srgbEncode(0.002), 12.92 * 0.002);    // linear segment, same expression
    EXPECT_EQ(srgbEncode(-0.5), -srgbEncode(0.5));  // odd extension, by construction
    // The formula evaluated independently (1.055 * 0.5^(1/2.4) - 0.055 and
    // ((0.5 + 0.055) / 1.055)^2.4, to 12 digits): 1e-11 covers the digits written here.
    EXPECT_NEAR(srgbEncode(0.5), 0.735356983052, 1e-11);
    EXPECT_NEAR(srgbDecode(0.5), 0.214041140482, 1e-11);
}

}  // namespace
}  // namespace paintlab
