#pragma once
// Colour at the multi-angle geometries of lab goniospectrophotometers
// (ASTM E2194 / DIN 6175-2): illumination at 45° from the normal, detection
// in the plane of incidence at aspecular angles -15, 15, 25, 45, 75 and 110°,
// measured from the specular direction towards the illuminator (45as110 looks
// from 65° on the light's side, 45as45 along the normal); and any other
// geometry of an instrument, out of the plane of incidence too
// (multiAngleDirections). The reflectance factor at a geometry is
// pi * f(wi, wo): 1 for the perfect diffuser.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/fast_model/brdf_colour.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace paintlab {

inline constexpr double kMultiAngleIlluminationDeg = 45.0;
inline constexpr std::array<double, 6> kAspecularAnglesDeg{-15.0, 15.0, 25.0, 45.0, 75.0, 110.0};

// A multi-angle geometry and its directions. The light is in the x-z plane
// (wi at phi 0) at illumination_deg from the normal; its specular direction r
// is at phi 180. In the plane of incidence (azimuth_deg 0) the detector is
// aspecular_deg from r, positive towards the normal and the light. Out of that
// plane (the "az" of names such as 45as25az90) the detector is rotated about
// the specular direction r, not about the normal: it stays aspecular_deg from
// r, and with u the in-plane direction perpendicular to r pointing away from
// the normal,
//     wo = cos(as) r + sin(as) (cos(az) u + sin(az) (r x u)),
// so az +-180 is the in-plane geometry at +as and az +-90 leaves the plane at a
// right angle (45as25az90: 50.1° from the normal, at -y here). This is X-Rite's
// definition for its MA-T12 (45as25az+-90) and MA98 geometries ("azimuth =
// rotation of view direction around reflection direction", with published
// direction vectors; docs/ARCHITECTURE.md, "Multi-angle geometries", gives
// the source). Azimuth 0 means in the plane, as the names without "az": the
// out-of-plane formula approaches the in-plane -as as az approaches 0.
struct MultiAngleGeometry {
    double aspecular_deg = 0.0;
    Direction wi;  // towards the light: theta illumination_deg, phi 0
    Direction wo;  // towards the detector
    double illumination_deg = kMultiAngleIlluminationDeg;
    double azimuth_deg = 0.0;
};

// An azimuth this close to 0 is the plane of incidence, as in X-Rite's own
// naming: rounding noise in a file must not send 45as15 to the far side of
// the specular direction (the out-of-plane formula tends to -as as az -> 0).
inline constexpr double kInPlaneAzimuthDeg = 1e-7;
inline bool isInPlane(double azimuth_deg) noexcept { return std::abs(azimuth_deg) < kInPlaneAzimuthDeg; }

// The largest detector polar angle a multi-angle reading may have (deg), for
// every check of one (the database, the importers, the fit): at the horizon a
// reflectance factor is 0/0.
inline constexpr double kMaxDetectorPolarDeg = 89.9;

// Why an out-of-plane geometry is not in its one form, or empty. X-Rite's
// names have 0 < aspecular <= 180 and 0 < |azimuth| < 180; the rest repeat
// a direction (as az is -as az+-180, az +-180 is the in-plane +as) and
// would be stored as two geometries at one direction.
std::string outOfPlaneFormProblem(double aspecular_deg, double azimuth_deg);

// The one conversion of a multi-angle geometry to directions (the colour
// report, the fit, the database's checks, the importers and the fast model's
// validity boundary use it). Never
// throws: wo.z <= 0 when the detector is at or below the horizon, for the
// caller to report with its field name.
MultiAngleGeometry multiAngleDirections(double illumination_deg, double aspecular_deg,
                                        double azimuth_deg = 0.0) noexcept;

// The detector's polar angle in degrees from the normal (90 or more: at or below the horizon).
double detectorPolarAngleDeg(const MultiAngleGeometry& geometry) noexcept;

// The in-plane geometry at 45° illumination. Throws std::invalid_argument if
// the detector would be below the horizon (aspecular angle outside (-45, 135)).
MultiAngleGeometry multiAngleGeometry(double aspecular_deg);

struct MultiAngleColour {
    double aspecular_deg = 0.0;
    std::vector<double> reflectance_factor;  // pi f, at the BRDF's wavelengths
    Xyz xyz;
    Lab lab;
    double illumination_deg = kMultiAngleIlluminationDeg;
    double azimuth_deg = 0.0;
};

struct MultiAngleReport {
    Illuminant illuminant = Illuminant::D65;
    Observer observer = Observer::Cie1964_10deg;
    std::vector<MultiAngleColour> colours;  // in kAspecularAnglesDeg order
    double flop_index = 0.0;
};

// The colour at one geometry (any illumination, in or out of the plane).
MultiAngleColour multiAngleColour(const SpectralBrdf& brdf, const MultiAngleGeometry& geometry,
                                  const ColourConditions& conditions);

// Instruments report D65 / 10° by default. Lab is relative to the
// illuminant's white for the observer.
MultiAngleReport multiAngleColours(const SpectralBrdf& brdf, Illuminant illuminant = Illuminant::D65,
                                   Observer observer = Observer::Cie1964_10deg);

// X-Rite's flop index (used by the MA-T and MA-9x instruments):
// FI = 2.69 (L*15 - L*110)^1.11 / (L*45)^0.86; 0 for L*15 <= L*110 (no flop)
// and for L*45 = 0.
double flopIndex(double L15, double L45, double L110) noexcept;

}  // namespace paintlab
