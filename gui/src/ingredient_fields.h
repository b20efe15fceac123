#pragma once
// The editable fields of an ingredient, for the ingredient editor: its own
// fields (name, provenance, density, technological limits, binder solids,
// flake diameter spread) and the scalars of its optical data found through
// the engine structs' traversal hooks (recipe.h), with the units of their
// declarations (parameters.h). Spectra are not edited here (they come in
// through the importers). Qt-free: the tests use it directly.
//
// Parsing only turns text into values; the value ranges are checked by the
// database when the ingredient is stored (updateIngredient), which names
// the same field keys.

#include "paintlab/database/ingredients.h"

#include <string>
#include <string_view>
#include <vector>

namespace paintlab::gui {

struct IngredientField {
    enum class Type {
        Text,            // one line
        LongText,        // several lines (description)
        Tags,            // comma-separated list
        Number,          // required number
        OptionalNumber,  // empty = absent
    };
    std::string key;    // as in ingredient files and database errors: "density_g_cm3",
                        // "limits.min_thickness_um", "hg_g"
    std::string label;  // "Density"
    std::string unit;   // "g/cm³", "µm"; empty for text and dimensionless numbers
    Type type = Type::Text;
    std::string help;
};

// "binder", "pigment", "mirror flake", "interference flake", "substrate".
std::string ingredientKindLabel(db::IngredientKind kind);

// Every editable field of this ingredient's kind, in display order.
std::vector<IngredientField> ingredientFields(const db::Ingredient& ingredient);

// The field's value as text (numbers in the shortest form that reads back
// exactly; an absent optional number is empty).
std::string fieldText(const db::Ingredient& ingredient, const IngredientField& field);

// Sets the field from text. Throws InputError(source, "ingredient '<name>'.<key>",
// ...) when the text is not a number (or empty for a required one); the
// ingredient is unchanged then.
void setFieldText(db::Ingredient& ingredient, const IngredientField& field, std::string_view text,
                  const std::string& source);

// Which field a database error is about: the key of the field whose key ends
// the error's field path ("ingredient 'X'.limits.max_volume_fraction" ->
// "limits.max_volume_fraction"); empty if none.
std::string fieldKeyOfError(const std::vector<IngredientField>& fields, std::string_view error_field);

}  // namespace paintlab::gui
