#pragma once
// Recipe files: JSON with a schema version (Recipe::kSchemaVersion). Reading
// then writing gives the same text; writing then reading gives an equal Recipe.
// The format is documented in docs/RECIPE_FORMAT.md.

#include "paintlab/engine/recipe.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace paintlab {

// Recipe files are small (a few hundred kB with many tabulated spectra);
// anything larger is rejected before it is read.
inline constexpr std::size_t kMaxRecipeFileBytes = std::size_t{16} << 20;

// Parses a recipe document: structure, types, required fields, unknown
// fields, schema version. Does not check value ranges (see recipe_validation.h).
// Throws InputError naming source and the field.
Recipe parseRecipeJson(std::string_view text, const std::string& source = "<recipe>");

// Reads and parses a recipe file (as parseRecipeJson; ranges not checked).
// Throws InputError naming the file: missing, empty, too large, malformed.
Recipe parseRecipeFile(const std::filesystem::path& path);

// Reads, parses and validates a recipe file. Throws InputError naming the
// file and the field for every kind of bad input (validateRecipe's errors too).
Recipe loadRecipeFile(const std::filesystem::path& path);

// The canonical JSON text of a recipe (2-space indent, every field written).
std::string recipeToJson(const Recipe& recipe);

// Writes the recipe atomically: a temporary file beside the target is
// renamed over it, so an existing file is never left half written.
// Throws Error if the file cannot be written.
void saveRecipeFile(const Recipe& recipe, const std::filesystem::path& path);

}  // namespace paintlab
