#pragma once
// Measurement files (measurements.h):
//
// - JSON: { "format": "paintlab-measurement", "format_version": 1, "name": "...",
//           "kind": "multiangle" | "brdf", "instrument", "geometry", "sample",
//           "measured_at", "source" (strings, optional but name and kind),
//           multiangle: "illuminant": "D65", "observer": "10deg",
//                       optional "wavelengths_nm": [...] for spectral readings,
//                       "readings": [ { "illumination_deg": 45, "aspecular_deg": 15,
//                                       "azimuth_deg": 90 (optional, 0: in-plane),
//                                       "L": 92.1, "a": -0.4, "b": 1.2,
//                                       "reflectance": [...] (optional) } ]
//                       (a spectral reading may leave L, a, b out: computed)
//           brdf:       "channels": ["R", "G", "B"] or "wavelengths_nm": [...],
//                       "samples": [ { "theta_i_deg", "phi_i_deg", "theta_o_deg",
//                                      "phi_o_deg", "values": [...] } ] }
// - CSV, as instruments export a table:
//   multiangle: columns aspecular_deg (or geometry "45as15", "45as25az90"),
//               optional illumination_deg (default 45) and azimuth_deg
//               (default 0, in-plane; written only when a reading has one),
//               L, a, b (or L*, a*, b*),
//               and/or one reflectance-factor column per wavelength ("400",
//               "400nm"; without L, a, b they are computed from the spectra);
//   brdf:       columns theta_i_deg, phi_i_deg, theta_o_deg, phi_o_deg, then
//               either R, G, B or one column per wavelength ("380", "380nm").
//   The kind follows from the columns; name, instrument etc. come from the
//   caller (the CLI's options, the file name).

#include "paintlab/database/measurements.h"

#include <string>
#include <string_view>

namespace paintlab::db {

// Throws InputError naming source, the record and the field for every problem
// (validateMeasurement's included).
Measurement parseMeasurementJson(std::string_view text, const std::string& source);
// description: name, instrument, geometry, sample, measured_at, source,
// illuminant, observer of the measurement (its data fields are ignored).
Measurement parseMeasurementCsv(std::string_view text, const std::string& source,
                                const Measurement& description);

std::string measurementToJson(const Measurement& measurement);
std::string measurementToCsv(const Measurement& measurement);

}  // namespace paintlab::db
