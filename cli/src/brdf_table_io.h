#pragma once
// The tabulated-BRDF file of `brdf --out` and `mc --table --out`: a regular
// grid of incidence and exit angles 0..85 deg and azimuth differences
// 0..180 deg, f (1/sr, mirror term excluded) per band; JSON (with the
// settings and the top interface's mirror reflectance) or CSV (one row per
// direction pair). Both commands write through here, so the format is one.

#include "paintlab/engine/layered_brdf.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace paintlab::cli {

// The file's text. `csv` selects CSV; `settings` is stored as the JSON's
// "settings" object (CSV has none). With `batches` (a Monte Carlo table's
// per-batch tables, mc_table.h) every value also gets its standard error
// from their spread: JSON "brdf_std_error_per_sr" of the same shape, CSV
// columns se_<nm>nm_per_sr after the values. Throws InputError if step_deg
// is not in [0.5, 45] (field --step).
std::string brdfTableText(const LayeredBrdf& brdf, const std::string& recipe_path,
                          const nlohmann::ordered_json& settings, double step_deg, bool csv,
                          const std::vector<LayeredBrdf>* batches = nullptr);

// Whether the output path asks for CSV (ends in .csv).
bool isCsvPath(const std::string& path);

// Writes text to path; InputError (field `option`) if it cannot be opened, Error if writing fails.
void writeTextFile(const std::string& path, const std::string& text, const std::string& option);

}  // namespace paintlab::cli
