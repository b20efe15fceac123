#pragma once
// Recipes with immutable versions. A version holds the canonical recipe JSON
// (engine recipe_json.h: the single source of truth, checksummed with
// SHA-256) plus one row per layer and component linking the ingredients it
// uses. Saving never overwrites: it adds version N+1 with author, time and
// note (schema triggers refuse UPDATE and DELETE of a saved version).
//
// Ingredients are matched by kind and name (the binder of a layer as a
// binder, a pigment as a pigment, ...). A recipe may use an ingredient the
// database does not hold: the recipe JSON carries all its optical data, so
// the version is saved, the component row has no ingredient link, and
// SavedVersion::unlinked names it (the CLI prints a warning). Pass
// SaveOptions::require_known_ingredients to refuse such a recipe instead.
// Raw media (validation slabs) and substrates are never linked.

#include "paintlab/database/database.h"
#include "paintlab/engine/recipe.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

struct SaveOptions {
    std::string author;  // who saved it; required (not empty)
    std::string note;    // what changed and why
    bool require_known_ingredients = false;
    // Where the recipe came from, for error messages ("basecoat.json"); default "<recipe>".
    std::string source;
};

struct SavedVersion {
    std::string recipe_name;
    int version = 0;
    std::string checksum_sha256;
    bool created = false;  // false: identical to the latest version, nothing was written
    std::vector<std::string>
        unlinked;  // "layers[1].components[0] (pigment 'X')" for every unmatched ingredient
};

struct RecipeVersionInfo {
    std::string recipe_name;
    int version = 0;
    std::string author;
    std::string created_at;  // ISO 8601 UTC
    std::string note;
    std::string checksum_sha256;
};

struct ComponentLink {
    std::string kind;  // the engine's component kind
    std::string name;
    double volume_fraction = 0.0;
    std::optional<std::int64_t> ingredient_id;
};

struct LayerLink {
    std::string name;
    double thickness_um = 0.0;
    std::string binder_name;
    std::optional<std::int64_t> binder_ingredient_id;
    std::vector<ComponentLink> components;
};

struct StoredRecipeVersion {
    RecipeVersionInfo info;
    Recipe recipe;                  // parsed from the stored JSON and validated
    std::vector<LayerLink> layers;  // the version's layer and component rows, top first
};

struct RecipeSummary {
    std::string name;
    int latest_version = 0;
    std::string latest_created_at;
    std::string latest_author;
};

// Validates the recipe (validateRecipe, InputError naming options.source and
// the field), then saves it as the next version of the recipe with its name
// in one transaction. Throws DatabaseError naming the file when SQLite
// fails; nothing is written then.
SavedVersion saveRecipeVersion(Database& db, const Recipe& recipe, const SaveOptions& options);

// The given version (or the latest), read in one transaction so that it is
// never seen half saved. Throws InputError naming the file if there is no
// such recipe or version, DatabaseError (Reason::Corrupt) if the stored JSON
// does not match its checksum.
StoredRecipeVersion loadRecipeVersion(Database& db, std::string_view name,
                                      std::optional<int> version = std::nullopt);

// Every version of a recipe, oldest first. Throws InputError if there is no such recipe.
std::vector<RecipeVersionInfo> recipeHistory(Database& db, std::string_view name);

// Every recipe, by name.
std::vector<RecipeSummary> listRecipes(Database& db);

}  // namespace paintlab::db
