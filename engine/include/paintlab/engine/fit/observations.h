#pragma once
// What a fit compares the model with: multi-angle instrument readings and
// BRDF samples, each with its noise and the side of the panel it was taken
// from. Plain data, no database type: the database and the CLI fill these
// from their records and files.
//
// Noise defaults (used where a noise field is 0) and why:
//   - reflectance factor: 1 % of the value plus 0.001 absolute, per
//     wavelength. At L* 50 a 1 % change of Y is about 0.25 ΔE00, the
//     inter-instrument agreement multi-angle spectrophotometers quote
//     (0.2-0.4 ΔE); 0.001 keeps the dark flop angles from being weighted
//     beyond any instrument's stray-light floor.
//   - CIELAB (when only L*a*b* is given): 0.3 per coordinate, the same
//     inter-instrument agreement.
//   - BRDF samples: a 5 % relative error of the sample's mean channel, the
//     accuracy goniophotometers report (MERL and RGL quote a few per cent),
//     carried to the log residual ln(1 + f cos θi): 0.05 x / (1 + x) with
//     x = f cos θi, at least 0.002 (the floor keeps black samples from
//     being weighted beyond any instrument's dynamic range). A constant
//     0.05 on the log residual, the first default, was 5 % of 1/sr absolute
//     over the diffuse part of every paint and left fits colour-blind on dark
//     paints (docs/VALIDATION.md, "Real measurements").

#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/colour/colour.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::fit {

inline constexpr double kDefaultReflectanceRelativeNoise = 0.01;
inline constexpr double kDefaultReflectanceAbsoluteNoise = 0.001;
inline constexpr double kDefaultLabNoise = 0.3;
inline constexpr double kDefaultBrdfLogNoise = 0.05;  // the relative error above
inline constexpr double kDefaultBrdfLogNoiseFloor = 0.002;

// The default noise on ln(1 + f cos θi) of a BRDF sample (above), from its
// values (1/sr) and the cosine of its incidence.
double defaultBrdfLogNoise(const std::vector<double>& values, double cos_i);

// Top: the coating seen from its air side. Bottom: seen from below through a
// transparent substrate (the recipe's substrate must be `transparent`); the
// model is the same stack seen from below (recipeSeenFromBelow, fit.h).
enum class Side { Top, Bottom };
std::string_view sideName(Side side);

// One geometry of a multi-angle instrument: illumination at
// illumination_deg from the normal, detection at aspecular_deg from the
// specular direction towards the illuminator, and azimuth_deg, the
// detector's rotation about the specular direction out of the plane of
// incidence (0: in the plane; the convention of multiangle.h: 45as15 looks
// 15° off specular, 45as25az90 25° off specular, at right angles to the plane).
struct MultiAngleReading {
    double illumination_deg = 45.0;
    double aspecular_deg = 0.0;
    // Spectral reflectance factors (pi f; 1 = perfect diffuser) at
    // wavelengths_nm (strictly ascending, within 380-780 nm after overlap with
    // the model's). Empty: the reading has CIELAB only.
    std::vector<double> wavelengths_nm;
    std::vector<double> reflectance_factor;
    // CIELAB for the measurement's illuminant and observer. With spectra it is
    // reported (ΔE00 against it) but not fitted; without spectra it is fitted.
    std::optional<Lab> lab;
    // Noise; 0: the defaults above.
    double reflectance_relative_noise = 0.0;
    double reflectance_absolute_noise = 0.0;
    double lab_noise = 0.0;
    double azimuth_deg = 0.0;  // last, so that positional initialisers keep their meaning
};

struct MultiAngleMeasurement {
    std::string name;  // for messages and results ("panel 7, top")
    Side side = Side::Top;
    Illuminant illuminant = Illuminant::D65;
    Observer observer = Observer::Cie1964_10deg;
    std::vector<MultiAngleReading> readings;
};

// One BRDF sample: directions in degrees (theta from the normal, phi from
// the x axis; both directions away from the surface), values either linear
// sRGB (D65, the model's spectral BRDF converted as brdf_colour.h does: 3
// values, 1/sr) or per wavelength of the measurement (1/sr).
struct BrdfSample {
    double theta_i_deg = 0.0;
    double phi_i_deg = 0.0;
    double theta_o_deg = 0.0;
    double phi_o_deg = 0.0;
    std::vector<double> values;
    double log_noise = 0.0;  // on ln(1 + f cos θi); 0: the default above
};

enum class BrdfValues { LinearSrgb, Spectral };

struct BrdfMeasurement {
    std::string name;
    Side side = Side::Top;
    BrdfValues values = BrdfValues::LinearSrgb;
    std::vector<double> wavelengths_nm;  // Spectral only: the values' wavelengths
    std::vector<BrdfSample> samples;
};

struct Observations {
    std::vector<MultiAngleMeasurement> multi_angle;
    std::vector<BrdfMeasurement> brdf;
};

}  // namespace paintlab::fit
