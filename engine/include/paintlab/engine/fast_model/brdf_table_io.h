#pragma once
// The tabulated-BRDF file (`brdf --out`, `mc --table --out`, and any program
// that exports a LayeredBrdf): a regular grid of incidence and exit angles
// 0..85 deg and azimuth differences 0..180 deg, f (1/sr, mirror term
// excluded) per band; JSON (with the settings and the top interface's mirror
// reflectance) or CSV (one row per direction pair).

#include "paintlab/engine/fast_model/layered_brdf.h"

#include <string>
#include <string_view>
#include <vector>

namespace paintlab {

// The file's text. `csv` selects CSV; `settings_json` is the text of a JSON
// object stored as the JSON file's "settings" (CSV has none). With `batches`
// (a Monte Carlo table's per-batch tables, montecarlo/mc_table.h) every value
// also gets its standard error from their spread: JSON
// "brdf_std_error_per_sr" of the same shape, CSV columns se_<nm>nm_per_sr
// after the values. Throws InputError if step_deg is not in [0.5, 45] (field
// --step), Error if settings_json is not a JSON object.
std::string brdfTableText(const LayeredBrdf& brdf, const std::string& recipe_path,
                          std::string_view settings_json, double step_deg, bool csv,
                          const std::vector<LayeredBrdf>* batches = nullptr);

// Whether an output path asks for the CSV form (ends in .csv).
bool isBrdfTableCsvPath(std::string_view path);

}  // namespace paintlab
