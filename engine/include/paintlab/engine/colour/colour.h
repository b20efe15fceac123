#pragma once
// Colour coordinates and the closed-form conversions between them: CIE XYZ,
// CIELAB and its cylindrical form LCh, and sRGB. Nothing here reads a file or
// throws; the CIE observers and illuminants (and so white points and spectral
// integration) are in cie_tables.h, colour differences in ciede2000.h.
//
// Conventions: XYZ is relative, Y = 1 for the perfect white (not 100); L* is
// 0..100; hue angles are in degrees, in [0, 360).

namespace paintlab {

// CIE 1931 (or 1964, with the 10 degree observer) tristimulus values.
struct Xyz {
    double X = 0.0;
    double Y = 0.0;
    double Z = 0.0;
};

// CIE 1976 L*a*b* (CIE 15:2004, section 8.2.1, CIELAB).
struct Lab {
    double L = 0.0;
    double a = 0.0;
    double b = 0.0;
};

// CIELAB in cylindrical coordinates: chroma C*ab and hue angle h_ab in degrees.
struct Lch {
    double L = 0.0;
    double C = 0.0;
    double h_deg = 0.0;
};

// sRGB channel values; linear or encoded depending on the function that made them.
struct Rgb {
    double r = 0.0;
    double g = 0.0;
    double b = 0.0;
};

// CIE 15:2004 section 8.2.1 with the exact constants epsilon = 216/24389 and
// kappa = 24389/27 (the rounded 0.008856 / 903.3 make the two branches meet
// with a small jump). white is the reference white in the same scale as xyz;
// its components must be > 0.
Lab xyzToLab(const Xyz& xyz, const Xyz& white) noexcept;
// The exact inverse of xyzToLab.
Xyz labToXyz(const Lab& lab, const Xyz& white) noexcept;

// h is 0 for a = b = 0 (the hue of a neutral is undefined; CIE 15 gives none).
Lch labToLch(const Lab& lab) noexcept;
Lab lchToLab(const Lch& lch) noexcept;

// IEC 61966-2-1:1999 section 5.2: XYZ (D65-relative, Y = 1 for the D65 white)
// to linear sRGB with the standard's 4-decimal matrix. No clipping: out-of-gamut
// colours give channels outside [0, 1]. XYZ relative to another white must be
// chromatically adapted to D65 first.
Rgb xyzToLinearSrgb(const Xyz& xyz) noexcept;
// The exact (double precision) inverse of xyzToLinearSrgb, so that round trips
// are lossless; it agrees with the standard's own rounded reverse matrix
// (section 5.3 reverse transformation) to 1e-4.
Xyz linearSrgbToXyz(const Rgb& linear) noexcept;

// IEC 61966-2-1 transfer function (12.92 below 0.0031308, else
// 1.055 v^(1/2.4) - 0.055) and its inverse (threshold 0.04045). No clipping:
// a negative value maps to minus the value of its magnitude, so out-of-gamut
// colours survive a round trip; clip for display where needed.
double srgbEncode(double linear) noexcept;
double srgbDecode(double encoded) noexcept;
Rgb linearToSrgbEncoded(const Rgb& linear) noexcept;
Rgb srgbEncodedToLinear(const Rgb& encoded) noexcept;

}  // namespace paintlab
