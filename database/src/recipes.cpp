// Recipe versions (recipes.h): canonical JSON + checksum + layer/component
// rows linking ingredients, written in one transaction and never changed.

#include "paintlab/database/recipes.h"

#include "paintlab/database/ingredients.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/recipe_paths.h"
#include "paintlab/engine/recipe_validation.h"

#include "sha256.h"
#include "sqlite.h"

namespace paintlab::db {

namespace {

using detail::Connection;
using detail::Statement;
using detail::Transaction;

std::optional<std::int64_t> ingredientId(const Connection& c, std::string_view kind, std::string_view name) {
    Statement s(c, "SELECT id FROM ingredient WHERE kind = ?1 AND name = ?2");
    s.bind(1, kind).bind(2, name);
    if (!s.step()) return std::nullopt;
    return s.integer(0);
}

RecipeVersionInfo versionInfo(const Statement& s, int first_column) {
    RecipeVersionInfo info;
    info.recipe_name = s.text(first_column);
    info.version = static_cast<int>(s.integer(first_column + 1));
    info.author = s.text(first_column + 2);
    info.created_at = s.text(first_column + 3);
    info.note = s.text(first_column + 4);
    info.checksum_sha256 = s.text(first_column + 5);
    return info;
}

constexpr const char* kVersionColumns =
    "SELECT r.name, v.version, v.author, v.created_at, v.note, v.checksum_sha256, v.id, v.recipe_json "
    "FROM recipe_version v JOIN recipe r ON r.id = v.recipe_id ";

std::vector<LayerLink> readLinks(const Connection& c, std::int64_t version_id) {
    std::vector<LayerLink> layers;
    Statement s(c, "SELECT id, name, thickness_um, binder_name, binder_ingredient_id FROM recipe_layer "
                   "WHERE recipe_version_id = ?1 ORDER BY position");
    s.bind(1, version_id);
    Statement components(c, "SELECT kind, name, volume_fraction, ingredient_id FROM recipe_component "
                            "WHERE recipe_layer_id = ?1 ORDER BY position");
    while (s.step()) {
        LayerLink layer{s.text(1), s.real(2), s.text(3), s.optionalInteger(4), {}};
        components.reset();
        components.bind(1, s.integer(0));
        while (components.step())
            layer.components.push_back(
                {components.text(0), components.text(1), components.real(2), components.optionalInteger(3)});
        layers.push_back(std::move(layer));
    }
    return layers;
}

}  // namespace

SavedVersion saveRecipeVersion(Database& db, const Recipe& recipe, const SaveOptions& options) {
    const Connection& c = db.impl().connection;
    const std::string source = options.source.empty() ? "<recipe>" : options.source;
    validateRecipe(recipe, source);
    if (options.author.empty()) throw InputError(source, "author", "a saved recipe version needs an author");
    if (recipe.name.empty()) throw InputError(source, "name", "a saved recipe needs a name");
    if (db.isReadOnly())
        throw DatabaseError(c.file(), DatabaseError::Reason::ReadOnly,
                            "cannot save recipe '" + recipe.name + "': the database file is read-only");

    SavedVersion saved;
    saved.recipe_name = recipe.name;
    const std::string json = recipeToJson(recipe);
    saved.checksum_sha256 = detail::sha256Hex(json);

    Transaction transaction(c, Transaction::Mode::Write);
    Statement find(c, "SELECT id FROM recipe WHERE name = ?1");
    find.bind(1, recipe.name);
    std::int64_t recipe_id = 0;
    if (find.step()) {
        recipe_id = find.integer(0);
    } else {
        Statement insert(c, "INSERT INTO recipe (name) VALUES (?1)");
        insert.bind(1, recipe.name).run();
        recipe_id = c.lastInsertId();
    }
    Statement latest(c, "SELECT version, checksum_sha256 FROM recipe_version WHERE recipe_id = ?1 "
                        "ORDER BY version DESC LIMIT 1");
    latest.bind(1, recipe_id);
    int latest_version = 0;
    if (latest.step()) {
        latest_version = static_cast<int>(latest.integer(0));
        if (latest.text(1) == saved.checksum_sha256) {
            // Saving the same recipe again makes no new version.
            saved.version = latest_version;
            saved.created = false;
            transaction.commit();
            return saved;
        }
    }
    saved.version = latest_version + 1;
    saved.created = true;

    Statement version(c, "INSERT INTO recipe_version (recipe_id, version, author, note, recipe_json, "
                         "checksum_sha256, substrate_kind) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
    version.bind(1, recipe_id)
        .bind(2, saved.version)
        .bind(3, options.author)
        .bind(4, options.note)
        .bind(5, json)
        .bind(6, saved.checksum_sha256)
        .bind(7, substrateKind(recipe.substrate))
        .run();
    const std::int64_t version_id = c.lastInsertId();

    Statement layer_row(
        c, "INSERT INTO recipe_layer (recipe_version_id, position, name, thickness_um, binder_name, "
           "binder_ingredient_id) VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
    Statement component_row(c, "INSERT INTO recipe_component (recipe_layer_id, position, kind, name, "
                               "volume_fraction, ingredient_id) VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
    for (std::size_t i = 0; i < recipe.layers.size(); ++i) {
        const Layer& layer = recipe.layers[i];
        const auto binder_id = ingredientId(c, ingredientKindName(IngredientKind::Binder), layer.binder.name);
        if (!binder_id) saved.unlinked.push_back(ingredientLabel(binderPath(i), "binder", layer.binder.name));
        layer_row.reset();
        layer_row.bind(1, version_id)
            .bind(2, static_cast<std::int64_t>(i))
            .bind(3, layer.name)
            .bind(4, layer.thickness_um)
            .bind(5, layer.binder.name)
            .bind(6, binder_id)
            .run();
        const std::int64_t layer_id = c.lastInsertId();
        for (std::size_t j = 0; j < layer.components.size(); ++j) {
            const Component& component = layer.components[j];
            const std::string_view kind = componentKind(component);
            const std::string& name = componentName(component);
            // Raw media are validation slabs, not ingredients: never linked.
            std::optional<std::int64_t> id;
            if (parseIngredientKind(kind)) {
                id = ingredientId(c, kind, name);
                if (!id) saved.unlinked.push_back(ingredientLabel(componentPath(i, j), kind, name));
            }
            component_row.reset();
            component_row.bind(1, layer_id)
                .bind(2, static_cast<std::int64_t>(j))
                .bind(3, kind)
                .bind(4, name)
                .bind(5, componentVolumeFraction(component))
                .bind(6, id)
                .run();
        }
    }
    if (options.require_known_ingredients && !saved.unlinked.empty())
        throw InputError(
            source, saved.unlinked.front(),
            "this ingredient is not in the database " + c.file().string() +
                " (add it first, or save without requiring known ingredients); nothing was saved");
    transaction.commit();
    return saved;
}

StoredRecipeVersion loadRecipeVersion(Database& db, std::string_view name, std::optional<int> version) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c,
                std::string(kVersionColumns) +
                    "WHERE r.name = ?1 AND (?2 IS NULL OR v.version = ?2) ORDER BY v.version DESC LIMIT 1");
    s.bind(1, name);
    if (version)
        s.bind(2, *version);
    else
        s.bindNull(2);
    const std::string file = c.file().string();
    if (!s.step()) {
        Statement any(c, "SELECT 1 FROM recipe WHERE name = ?1");
        any.bind(1, name);
        if (version && any.step())
            throw InputError(file, "recipe '" + std::string(name) + "'",
                             "has no version " + std::to_string(*version));
        throw InputError(file, "recipe '" + std::string(name) + "'", "no such recipe");
    }
    StoredRecipeVersion out;
    out.info = versionInfo(s, 0);
    const std::int64_t version_id = s.integer(6);
    const std::string json = s.text(7);
    const std::string label =
        "recipe '" + out.info.recipe_name + "' version " + std::to_string(out.info.version);
    if (detail::sha256Hex(json) != out.info.checksum_sha256)
        throw DatabaseError(c.file(), DatabaseError::Reason::Corrupt,
                            label + ": the stored JSON does not match its SHA-256 checksum");
    std::string source = file;
    source.append(": ").append(label);
    out.recipe = parseRecipeJson(json, source);
    validateRecipe(out.recipe, source);
    out.layers = readLinks(c, version_id);
    transaction.commit();
    return out;
}

std::vector<RecipeVersionInfo> recipeHistory(Database& db, std::string_view name) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, std::string(kVersionColumns) + "WHERE r.name = ?1 ORDER BY v.version");
    s.bind(1, name);
    std::vector<RecipeVersionInfo> out;
    while (s.step()) out.push_back(versionInfo(s, 0));
    transaction.commit();
    if (out.empty())
        throw InputError(c.file().string(), "recipe '" + std::string(name) + "'", "no such recipe");
    return out;
}

std::vector<RecipeSummary> listRecipes(Database& db) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, "SELECT r.name, v.version, v.created_at, v.author FROM recipe r "
                   "JOIN recipe_version v ON v.recipe_id = r.id "
                   "WHERE v.version = (SELECT max(version) FROM recipe_version WHERE recipe_id = r.id) "
                   "ORDER BY r.name");
    std::vector<RecipeSummary> out;
    while (s.step()) out.push_back({s.text(0), static_cast<int>(s.integer(1)), s.text(2), s.text(3)});
    transaction.commit();
    return out;
}

}  // namespace paintlab::db
