#pragma once
// Measurements of real panels and fits of recipe versions to them (schema
// tables measurement and fit). Two kinds of measurement:
//
// - multiangle: CIELAB at the geometries of a multi-angle spectrophotometer
//   (ASTM E2194 / DIN 6175-2: illumination 45° from the normal, aspecular
//   angles -15, 15, 25, 45, 75, 110°; 12-geometry instruments add 15°
//   illumination and geometries out of the plane of incidence such as
//   45as25az90), as BYK-mac or MA-T instruments export it, and optionally the
//   spectral reflectance factor per geometry (what such instruments measure;
//   CIELAB follows from it);
// - brdf: goniophotometer samples f(wi, wo) in 1/sr at (theta_i, phi_i,
//   theta_o, phi_o) in degrees, spectral (one value per wavelength) or RGB.
//
// A measurement's data are stored as JSON in measurement.data_json, its
// description in the columns. Names are unique (a measurement is found by
// name; createMeasurement refuses a taken one).

#include "paintlab/database/database.h"
#include "paintlab/engine/colour/cie_tables.h"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

enum class MeasurementKind { Brdf, MultiAngle };
std::string_view measurementKindName(MeasurementKind kind);  // "brdf", "multiangle"
std::optional<MeasurementKind> parseMeasurementKind(std::string_view name);

struct MultiAngleReading {
    double illumination_deg = 45.0;  // from the normal
    double aspecular_deg = 0.0;      // detector from the specular direction, towards the light positive
    double L = 0.0;                  // CIELAB under the measurement's illuminant and observer
    double a = 0.0;
    double b = 0.0;
    // Spectral reflectance factor (pi f relative to the perfect diffuser, 1 =
    // white; above 1 near the specular direction), one per
    // Measurement::wavelengths_nm; empty when only CIELAB was measured.
    std::vector<double> reflectance;
    // The detector's rotation about the specular direction out of the plane
    // of incidence, -180 to 180 (0: in the plane; "az" of 45as25az90; the
    // convention is engine/multiangle.h's, X-Rite's). Last, so that positional
    // initialisers written before it keep their meaning.
    double azimuth_deg = 0.0;
    friend bool operator==(const MultiAngleReading&, const MultiAngleReading&) = default;
};

// A multi-angle geometry by its instrument name: "45as15", "45as-15", with
// the spellings instruments and their software use ("r45as15", "45asMinus15",
// "r15as_45", "45as25az90", "45as25azMinus90"; case and a degree sign
// ignored). Illumination in the plane of incidence at illumination_deg from
// the normal, the detector aspecular_deg from the specular direction and
// azimuth_deg turned about it out of that plane (MultiAngleReading; 0: in the plane).
struct MultiAngleGeometry {
    double illumination_deg = 45.0;
    double aspecular_deg = 0.0;
    double azimuth_deg = 0.0;
};
// nullopt when the text is not a geometry name (never throws; the ranges are
// validateMeasurement's).
std::optional<MultiAngleGeometry> parseMultiAngleGeometry(std::string_view name);
// "45as-15", "15as80", "45as25az-90" (shortest numbers; "az" only when the
// azimuth is not 0): parseMultiAngleGeometry reads it back.
std::string multiAngleGeometryName(double illumination_deg, double aspecular_deg, double azimuth_deg = 0.0);

struct BrdfSample {
    double theta_i_deg = 0.0;  // light direction: polar angle from the normal, 0 to 90
    double phi_i_deg = 0.0;    // its azimuth
    double theta_o_deg = 0.0;  // view direction
    double phi_o_deg = 0.0;
    std::vector<double> values;  // f in 1/sr, one per channel (Measurement::channels)
    friend bool operator==(const BrdfSample&, const BrdfSample&) = default;
};

struct Measurement {
    std::int64_t id = 0;  // 0 until stored
    std::string name;
    MeasurementKind kind = MeasurementKind::MultiAngle;
    std::string instrument;   // "BYK-mac i", "in-house goniophotometer"
    std::string geometry;     // "45as-15,15,25,45,75,110", a gonio description
    std::string sample;       // the panel measured
    std::string measured_at;  // ISO 8601 date
    std::string source;       // file or lab notebook reference
    // multiangle
    std::string illuminant = "D65";
    std::string observer = "10deg";  // "2deg" or "10deg"
    std::vector<MultiAngleReading> readings;
    // brdf: channel names ("R", "G", "B") or wavelengths (nm); exactly one of them.
    // multiangle: wavelengths (nm) of the readings' spectra, or empty.
    std::vector<std::string> channels;
    std::vector<double> wavelengths_nm;
    std::vector<BrdfSample> samples;
    friend bool operator==(const Measurement&, const Measurement&) = default;
};

struct MeasurementSummary {
    std::int64_t id = 0;
    std::string name;
    MeasurementKind kind = MeasurementKind::MultiAngle;
    std::string instrument;
    std::string sample;
    std::string measured_at;
    std::size_t points = 0;  // readings or BRDF samples
    std::size_t fits = 0;
};

// Checks a measurement: name, kind-specific data present and finite, angles
// in range (a multi-angle detector above the horizon, azimuth -180 to 180), BRDF values and reflectance
// factors >= 0 and one per channel or wavelength (all readings spectral or none). Throws InputError(source,
// field, ...).
void validateMeasurement(const Measurement& measurement, const std::string& source);

// Each throws DatabaseError naming the file when SQLite fails and InputError
// naming the file and the field when the input is wrong; nothing is written then.
std::int64_t createMeasurement(Database& db, const Measurement& measurement);
std::optional<Measurement> findMeasurement(Database& db, std::string_view name);
std::vector<MeasurementSummary> listMeasurements(Database& db);  // by name

// The measurement's illuminant and observer as the colour code names them
// (validateMeasurement has checked the names).
Illuminant measurementIlluminant(const Measurement& measurement);
Observer measurementObserver(const Measurement& measurement);

// CIELAB of every spectral reading from its reflectance factor, under the
// measurement's illuminant and observer (for files that give only spectra).
void labFromSpectra(Measurement& measurement, const std::string& source);

// A fit of a recipe version to a measurement: how the recipe's prediction
// compared with the measured points.
struct Fit {
    std::int64_t id = 0;
    std::string recipe_name;
    int recipe_version = 0;
    std::string measurement_name;
    std::string method;                        // "fast model, Nelder-Mead", "dE2000 per angle", ...
    std::optional<double> residual_rms;        // >= 0, in the unit of the residuals
    std::vector<double> residuals;             // one per measured point
    std::map<std::string, double> parameters;  // fitted parameter values by key
    std::string note;
    std::string created_at;  // set when stored
};

// Stores a fit; the recipe version and the measurement must exist (InputError otherwise).
std::int64_t recordFit(Database& db, const Fit& fit);
// Oldest first.
std::vector<Fit> fitsOfMeasurement(Database& db, std::string_view measurement_name);
std::vector<Fit> fitsOfRecipe(Database& db, std::string_view recipe_name);

}  // namespace paintlab::db
