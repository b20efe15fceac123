#pragma once
// The data part of a measurement as JSON (measurement.data_json) and the
// whole measurement as a file (measurement_files.h). Private to the database library.

#include "paintlab/database/measurements.h"

#include <nlohmann/json.hpp>

#include <string>

namespace paintlab::db::detail {

// with_description: also name, kind, instrument, ... (the file form).
nlohmann::ordered_json measurementJson(const Measurement& measurement, bool with_description);
// Reads the data part (and, if with_description, the description) into
// measurement; the kind must be set when with_description is false.
// Throws InputError(source, field, ...) for a structural problem or an unknown key.
void readMeasurementJson(const nlohmann::json& json, bool with_description, Measurement& measurement,
                         const std::string& source);

}  // namespace paintlab::db::detail
