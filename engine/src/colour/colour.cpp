#include "paintlab/engine/colour/colour.h"

#include <array>
#include <cmath>
#include <numbers>

namespace paintlab {
namespace {

// CIE 15:2004 section 8.2.1: the exact rationals behind the rounded 0.008856
// and 903.3, so that the cube-root and linear branches meet continuously.
constexpr double kEpsilon = 216.0 / 24389.0;  // (6/29)^3
constexpr double kKappa = 24389.0 / 27.0;     // (29/3)^3

double labF(double t) noexcept { return t > kEpsilon ? std::cbrt(t) : (kKappa * t + 16.0) / 116.0; }

double labFInverse(double f) noexcept {
    const double cube = f * f * f;
    return cube > kEpsilon ? cube : (116.0 * f - 16.0) / kKappa;
}

using Matrix3 = std::array<std::array<double, 3>, 3>;

// IEC 61966-2-1:1999 section 5.2, CIE XYZ (D65, Y = 1) to linear sRGB, as published.
constexpr Matrix3 kXyzToSrgb{{
    {3.2406, -1.5372, -0.4986},
    {-0.9689, 1.8758, 0.0415},
    {0.0557, -0.2040, 1.0570},
}};

constexpr Matrix3 inverse(const Matrix3& m) {
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    return {{
        {c00 / det, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det,
         (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det},
        {c01 / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
         (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det},
        {c02 / det, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det,
         (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det},
    }};
}

// The exact inverse rather than the standard's separately rounded reverse
// matrix, so that XYZ -> sRGB -> XYZ is lossless.
constexpr Matrix3 kSrgbToXyz = inverse(kXyzToSrgb);

// IEC 61966-2-1 transfer function constants.
constexpr double kLinearLimit = 0.0031308;
constexpr double kEncodedLimit = 0.04045;
constexpr double kSlope = 12.92;
constexpr double kGamma = 2.4;
constexpr double kOffset = 0.055;

}  // namespace

Lab xyzToLab(const Xyz& xyz, const Xyz& white) noexcept {
    const double fx = labF(xyz.X / white.X);
    const double fy = labF(xyz.Y / white.Y);
    const double fz = labF(xyz.Z / white.Z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Xyz labToXyz(const Lab& lab, const Xyz& white) noexcept {
    const double fy = (lab.L + 16.0) / 116.0;
    const double fx = fy + lab.a / 500.0;
    const double fz = fy - lab.b / 200.0;
    return {white.X * labFInverse(fx), white.Y * labFInverse(fy), white.Z * labFInverse(fz)};
}

Lch labToLch(const Lab& lab) noexcept {
    const double C = std::hypot(lab.a, lab.b);
    double h_deg = (lab.a == 0.0 && lab.b == 0.0) ? 0.0 : std::atan2(lab.b, lab.a) * 180.0 / std::numbers::pi;
    if (h_deg < 0.0) h_deg += 360.0;
    return {lab.L, C, h_deg};
}

Lab lchToLab(const Lch& lch) noexcept {
    const double h_rad = lch.h_deg * std::numbers::pi / 180.0;
    return {lch.L, lch.C * std::cos(h_rad), lch.C * std::sin(h_rad)};
}

Rgb xyzToLinearSrgb(const Xyz& xyz) noexcept {
    const auto& m = kXyzToSrgb;
    return {m[0][0] * xyz.X + m[0][1] * xyz.Y + m[0][2] * xyz.Z,
            m[1][0] * xyz.X + m[1][1] * xyz.Y + m[1][2] * xyz.Z,
            m[2][0] * xyz.X + m[2][1] * xyz.Y + m[2][2] * xyz.Z};
}

Xyz linearSrgbToXyz(const Rgb& linear) noexcept {
    const auto& m = kSrgbToXyz;
    return {m[0][0] * linear.r + m[0][1] * linear.g + m[0][2] * linear.b,
            m[1][0] * linear.r + m[1][1] * linear.g + m[1][2] * linear.b,
            m[2][0] * linear.r + m[2][1] * linear.g + m[2][2] * linear.b};
}

double srgbEncode(double linear) noexcept {
    const double magnitude = std::fabs(linear);
    const double encoded = magnitude <= kLinearLimit
                               ? kSlope * magnitude
                               : (1.0 + kOffset) * std::pow(magnitude, 1.0 / kGamma) - kOffset;
    return std::copysign(encoded, linear);
}

double srgbDecode(double encoded) noexcept {
    const double magnitude = std::fabs(encoded);
    const double linear = magnitude <= kEncodedLimit
                              ? magnitude / kSlope
                              : std::pow((magnitude + kOffset) / (1.0 + kOffset), kGamma);
    return std::copysign(linear, encoded);
}

Rgb linearToSrgbEncoded(const Rgb& linear) noexcept {
    return {srgbEncode(linear.r), srgbEncode(linear.g), srgbEncode(linear.b)};
}

Rgb srgbEncodedToLinear(const Rgb& encoded) noexcept {
    return {srgbDecode(encoded.r), srgbDecode(encoded.g), srgbDecode(encoded.b)};
}

}  // namespace paintlab
