#pragma once
// Ingredient files: JSON documents { "format": "paintlab-ingredients",
// "format_version": 1, "ingredients": [ ... ] }, as written by
// packaging/demo/ingredients/make_demo_ingredients.py (the demo library) and,
// later, by `db export`. One ingredient:
//
//   { "kind": "pigment" | "binder" | "mirror_flake" | "interference_flake" | "substrate",
//     "name": "...", "description": "...", "source": "...", "tags": ["..."],
//     "density_g_cm3": 4.23, "density_source": "...",
//     "limits": { "max_volume_fraction": 0.25, "min_thickness_um": 10, "max_thickness_um": 30 },
//     <the kind's scalars, named as in recipe files: "hg_g", "diameter_um", ...,
//      plus "diameter_sd_um" for flakes, "substrate_kind" for substrates, and for
//      binders the optional "solids_mass_fraction" and "volatile_density_g_cm3">,
//     "spectra": { "<recipe field key>": { "unit": "1/µm", "source": "...", "date": "1995",
//                                          "wavelengths_nm": [...], "values": [...] } | { ..., "value": 1.58
//                                          } } }
//
// Unknown keys, wrong types and missing fields are errors, and so are a
// wavelength <= 0 and a unit that is unknown or of another dimension than the
// field's (units are converted to the field's own, spectrum_checks.h); value
// ranges are checked when the ingredient is stored (createIngredient).

#include "paintlab/database/ingredients.h"

#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

// Throws InputError naming source and the field ("ingredients[3] 'Al
// flake'.spectra.n.values") for every structural problem.
std::vector<Ingredient> parseIngredientsJson(std::string_view text, const std::string& source);

// The ingredient file of these ingredients (ids are not written): reading it
// back gives equal ingredients, ids aside.
std::string ingredientsToJson(const std::vector<Ingredient>& ingredients);

}  // namespace paintlab::db
