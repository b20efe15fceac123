#pragma once
// The CLI's side of the tabulated-BRDF file (the format itself is the
// engine's, fast_model/brdf_table_io.h) and of writing --out files.

#include "paintlab/engine/fast_model/layered_brdf.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace paintlab::cli {

// The engine's brdfTableText with the settings given as a JSON object.
std::string brdfTableText(const LayeredBrdf& brdf, const std::string& recipe_path,
                          const nlohmann::ordered_json& settings, double step_deg, bool csv,
                          const std::vector<LayeredBrdf>* batches = nullptr);

// Whether the output path asks for CSV (ends in .csv).
bool isCsvPath(const std::string& path);

// Writes text to path atomically (io/atomic_file.h); InputError (field
// `option`) if it cannot be created, Error if writing fails.
void writeTextFile(const std::string& path, const std::string& text, const std::string& option);

}  // namespace paintlab::cli
