#pragma once
// Colour at the multi-angle geometries of lab goniospectrophotometers
// (ASTM E2194 / DIN 6175-2): illumination at 45° from the normal, detection
// in the plane of incidence at aspecular angles -15, 15, 25, 45, 75 and 110°,
// measured from the specular direction towards the illuminator (45as110 looks
// from 65° on the light's side, 45as45 along the normal). The reflectance
// factor at a geometry is pi * f(wi, wo): 1 for the perfect diffuser.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/colour/colour.h"

#include <array>
#include <vector>

namespace paintlab {

inline constexpr double kMultiAngleIlluminationDeg = 45.0;
inline constexpr std::array<double, 6> kAspecularAnglesDeg{-15.0, 15.0, 25.0, 45.0, 75.0, 110.0};

struct MultiAngleGeometry {
    double aspecular_deg = 0.0;
    Direction wi;  // towards the light: theta 45°, phi 0
    Direction wo;  // towards the detector, in the plane of incidence
};

// Throws std::invalid_argument if the detector would be below the horizon
// (aspecular angle outside (-45, 135)).
MultiAngleGeometry multiAngleGeometry(double aspecular_deg);

struct MultiAngleColour {
    double aspecular_deg = 0.0;
    std::vector<double> reflectance_factor;  // pi f, at the BRDF's wavelengths
    Xyz xyz;
    Lab lab;
};

struct MultiAngleReport {
    Illuminant illuminant = Illuminant::D65;
    Observer observer = Observer::Cie1964_10deg;
    std::vector<MultiAngleColour> colours;  // in kAspecularAnglesDeg order
    double flop_index = 0.0;
};

// Instruments report D65 / 10° by default. Lab is relative to the
// illuminant's white for the observer.
MultiAngleReport multiAngleColours(const SpectralBrdf& brdf, Illuminant illuminant = Illuminant::D65,
                                   Observer observer = Observer::Cie1964_10deg);

// X-Rite's flop index (used by the MA-T and MA-9x instruments):
// FI = 2.69 (L*15 - L*110)^1.11 / (L*45)^0.86; 0 for L*15 <= L*110 (no flop)
// and for L*45 = 0.
double flopIndex(double L15, double L45, double L110) noexcept;

}  // namespace paintlab
