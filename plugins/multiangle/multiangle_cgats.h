#pragma once
// Multi-angle spectrophotometer exports in CGATS.17 text (X-Rite MA-T6/MA-T12,
// MA98, BYK-mac i and their software): one data set (row) per geometry, read
// into a multi-angle db::Measurement with the reflectance factor per geometry
// and/or CIELAB.
//
// What a file needs (names of DATA_FORMAT fields, any case):
// - the geometry of each row, one of
//     GEOMETRY / MEASUREMENT_GEOMETRY / MEAS_GEOMETRY / ANGLE: "45as15",
//       "45as-15", "r45as15", "45asMinus15", "r15as_45" (db::parseMultiAngleGeometry),
//     ILLUMINATION_ANGLE and ASPECULAR_ANGLE in degrees,
//     or SAMPLE_NAME ending in such a name ("blue pearl 45as15");
//   the six geometries of ASTM E2194 / DIN 6175-2 (45as-15 ... 45as110), the
//   15° ones of 12-geometry instruments (15as-45, 15as-30, 15as-15, 15as15,
//   15as45, 15as80) and their out-of-plane ones (45as25az90, 45as25az-90:
//   the detector turned about the specular direction, engine/multiangle.h)
//   are the usual ones; any geometry whose detector is above the horizon is read.
// - LAB_L, LAB_A, LAB_B and/or spectral fields (SPECTRAL_NM400, SPECTRAL_400,
//   NM400, ...; db::cgatsSpectralWavelength), reflectance factors (1 = the
//   perfect diffuser; above 1 near the specular direction).
// The unit of the spectra: ReadOptions::cgats.unit ("%" or "1") if given, else
// the keyword PAINTLAB_UNIT, else the scale whose CIELAB agrees with the
// file's LAB_L (when the file has it), else percent when a value far from the
// specular direction (aspecular >= 45°) is above 2; otherwise the file is
// refused until the unit is given. CIELAB missing from a spectral file is
// computed from the spectra.
// Illuminant and observer: the keywords ILLUMINANT / OBSERVER or
// MEASUREMENT_SOURCE "Illumination=D65 ObserverAngle=10" when present, else
// the caller's description. Instrument, date and sample from INSTRUMENTATION,
// CREATED and SAMPLE_NAME unless the caller gives them.
// A file of several samples (SAMPLE_NAME values) is read for the one named by
// the description's `sample`, else refused with the list.

#include "paintlab/plugins/plugin.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace paintlab::plugins::multiangle {

inline constexpr const char* kFormatId = "multiangle-cgats";
// Far above any instrument export (a 12-geometry spectral row is ~400 bytes); refused before reading.
inline constexpr std::size_t kMaxFileBytes = std::size_t{16} << 20;

// How sure we are that a file is a multi-angle CGATS export, from its first
// bytes: 0.95 with a geometry field, 0.9 with geometry names in its rows,
// 0.1 for other CGATS, 0 otherwise. Never throws.
double probe(std::string_view head);

// Throws InputError naming source and the field (a keyword, DATA_FORMAT, or
// "data set N (45as15).FIELD") for every problem.
db::Measurement parse(std::string_view text, const std::string& source, const ReadOptions& options);

// Reads at most kMaxFileBytes, then parse(); the measurement's name is the
// file's stem unless the description names it.
db::Measurement readFile(const std::filesystem::path& file, const ReadOptions& options);

}  // namespace paintlab::plugins::multiangle
