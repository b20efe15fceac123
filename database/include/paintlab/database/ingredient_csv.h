#pragma once
// Ingredient files as CSV, for spreadsheets and lab scripts: one record per
// spectrum sample ("tidy" long form), the ingredient's own fields repeated on
// each of its records, so one file holds whole ingredients. Columns (the
// keys of the JSON ingredient file, ingredient_json.h):
//
//   kind, name, description, source, tags ('|' between tags), density_g_cm3,
//   density_source, max_volume_fraction, min_thickness_um, max_thickness_um,
//   solids_mass_fraction, volatile_density_g_cm3, substrate_kind, hg_g,
//   particle_diameter_um, diameter_um, diameter_sd_um, thickness_um,
//   orientation_spread_deg, mica_thickness_nm, mica_thickness_spread_nm,
//   tio2_thickness_nm, tio2_thickness_spread_nm, refractive_index,
//   spectrum (the field key: "sigma_a_per_um", "metal_n", ...), unit,
//   spectrum_source, spectrum_date, wavelength_nm, value
//
// An empty field is an absent value. A constant spectrum is one record with
// an empty wavelength_nm; an ingredient without spectra (black or
// transparent substrate) is one record with an empty spectrum. kind, name,
// spectrum, wavelength_nm and value are required columns, the others may be
// left out; an unknown column is an error. Records of one ingredient (same
// kind and name) need not be adjacent, but its own fields must agree on all
// of them; the samples of a spectrum are in increasing wavelength.

#include "paintlab/database/ingredients.h"

#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

// Throws InputError naming source, the line and the column (or the field of
// the ingredient) for every problem: missing or unknown column, a number
// that is not finite, a wavelength <= 0 or not increasing, disagreeing
// ingredient fields, an unclosed quote or a short last record (truncated file).
std::vector<Ingredient> parseIngredientsCsv(std::string_view text, const std::string& source);

// Every column is written; reading the text back gives equal ingredients, ids
// aside. Throws InputError if a tag contains '|'.
std::string ingredientsToCsv(const std::vector<Ingredient>& ingredients);

}  // namespace paintlab::db
