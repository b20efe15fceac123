// Recipe versions: saved whole with a checksum, never overwritten (also at
// the SQL level), linked to ingredients by kind and name, loaded back equal;
// the demo database holds the five demo recipes exactly.

#include "db_test_support.h"
#include "sha256.h"

#include "paintlab/database/demo.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/recipe_json.h"

#include <gtest/gtest.h>

namespace paintlab::db {
namespace {

using test::rawExec;
using test::TempDir;

SaveOptions by(const std::string& author, const std::string& note = "") {
    return {author, note, false, "test"};
}

TEST(Recipes, VersionsAreAddedNeverOverwritten) {
    TempDir dir;
    Database db = Database::open(dir / "r.db");
    const auto v1 = saveRecipeVersion(db, test::minimalRecipe("r", 20.0), by("alice", "first"));
    EXPECT_TRUE(v1.created);
    EXPECT_EQ(v1.version, 1);
    EXPECT_EQ(v1.checksum_sha256, detail::sha256Hex(recipeToJson(test::minimalRecipe("r", 20.0))));
    const auto again = saveRecipeVersion(db, test::minimalRecipe("r", 20.0), by("bob"));
    EXPECT_FALSE(again.created);  // identical: no new version
    EXPECT_EQ(again.version, 1);
    const auto v2 = saveRecipeVersion(db, test::minimalRecipe("r", 25.0), by("bob", "thicker"));
    EXPECT_EQ(v2.version, 2);

    const auto history = recipeHistory(db, "r");
    ASSERT_EQ(history.size(), 2U);
    EXPECT_EQ(history[0].author, "alice");
    EXPECT_EQ(history[0].note, "first");
    EXPECT_EQ(history[1].author, "bob");
    EXPECT_EQ(history[1].note, "thicker");
    EXPECT_FALSE(history[1].created_at.empty());
    EXPECT_EQ(loadRecipeVersion(db, "r", 1).recipe, test::minimalRecipe("r", 20.0));
    EXPECT_EQ(loadRecipeVersion(db, "r").recipe, test::minimalRecipe("r", 25.0));
    EXPECT_EQ(loadRecipeVersion(db, "r").info.version, 2);
    EXPECT_THROW(loadRecipeVersion(db, "r", 3), InputError);
    EXPECT_THROW(loadRecipeVersion(db, "nope"), InputError);
    EXPECT_THROW(recipeHistory(db, "nope"), InputError);
    ASSERT_EQ(listRecipes(db).size(), 1U);
    EXPECT_EQ(listRecipes(db)[0].latest_version, 2);
}

TEST(Recipes, SavedVersionsAreImmutableInSql) {
    TempDir dir;
    const auto file = dir / "immutable.db";
    {
        Database db = Database::open(file);
        saveRecipeVersion(db, test::minimalRecipe("r", 20.0), by("alice"));
    }
    const auto before = test::rawQuery(file, "SELECT recipe_json || checksum_sha256 FROM recipe_version");
    for (const char* sql :
         {"UPDATE recipe_version SET note = 'changed'", "UPDATE recipe_version SET recipe_json = '{}'",
          "DELETE FROM recipe_version", "UPDATE recipe_layer SET thickness_um = 1",
          "DELETE FROM recipe_layer", "UPDATE recipe_component SET volume_fraction = 0.9",
          "DELETE FROM recipe_component", "UPDATE recipe SET name = 'other'", "DELETE FROM recipe"}) {
        std::string error;
        EXPECT_EQ(rawExec(file, sql, &error), SQLITE_CONSTRAINT) << sql;
        EXPECT_NE(error.find("immutable"), std::string::npos) << sql << ": " << error;
    }
    EXPECT_EQ(test::rawQuery(file, "SELECT recipe_json || checksum_sha256 FROM recipe_version"), before);
    Database db = Database::open(file);
    EXPECT_EQ(loadRecipeVersion(db, "r").recipe, test::minimalRecipe("r", 20.0));
}

TEST(Recipes, TamperedJsonIsDetectedByItsChecksum) {
    TempDir dir;
    const auto file = dir / "tampered.db";
    {
        Database db = Database::open(file);
        saveRecipeVersion(db, test::minimalRecipe("r", 20.0), by("alice"));
    }
    // Someone who drops the trigger can still edit the row; the checksum tells.
    ASSERT_EQ(rawExec(file, "DROP TRIGGER recipe_version_no_update; "
                            "UPDATE recipe_version SET recipe_json = replace(recipe_json, '20', '21')"),
              SQLITE_OK);
    Database db = Database::open(file);
    try {
        loadRecipeVersion(db, "r");
        FAIL();
    } catch (const DatabaseError& e) {
        EXPECT_EQ(e.reason(), DatabaseError::Reason::Corrupt);
        EXPECT_NE(std::string(e.what()).find("tampered.db"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
    }
}

TEST(Recipes, HostileNamesRoundTrip) {
    TempDir dir;
    Database db = Database::open(dir / "hostile.db");
    const std::string name =
        "'; DROP TABLE recipe_version; -- \"Red\" ; SELECT 1 UNION SELECT sql FROM sqlite_schema";
    Recipe recipe = test::minimalRecipe(name);
    recipe.description = "It's \"fine\"; DELETE FROM recipe; --";
    recipe.layers[0].name = "base'; --";
    recipe.layers[0].binder.name = "acrylic\"); DROP TABLE ingredient; --";
    saveRecipeVersion(db, recipe, by("O'Brien; DROP TABLE recipe", "note with 'quotes' and ; semicolons"));
    const auto stored = loadRecipeVersion(db, name);
    EXPECT_EQ(stored.recipe, recipe);
    EXPECT_EQ(stored.info.author, "O'Brien; DROP TABLE recipe");
    EXPECT_EQ(stored.layers.at(0).binder_name, recipe.layers[0].binder.name);
    EXPECT_EQ(recipeHistory(db, name).size(), 1U);
    EXPECT_TRUE(db.integrityCheck().empty());
}

TEST(Recipes, IngredientsAreLinkedByKindAndName) {
    TempDir dir;
    Database db = Database::open(dir / "links.db");
    Ingredient acrylic;
    acrylic.name = "acrylic";
    acrylic.data = Binder{"acrylic", Spectrum(1.5), Spectrum(0.0)};
    const auto binder_id = createIngredient(db, acrylic);
    Ingredient red;  // a mirror flake named "red" must not link to the pigment "red"
    red.name = "red";
    MirrorFlake flake;
    flake.diameter_um = 10;
    flake.reflectance = Spectrum(0.9);
    red.data = flake;
    createIngredient(db, red);

    // Strict: the pigment 'red' and the flake 'aluminium' are unknown -> refused, nothing saved.
    SaveOptions strict = by("alice");
    strict.require_known_ingredients = true;
    try {
        saveRecipeVersion(db, test::minimalRecipe("r"), strict);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(e.field().find("pigment 'red'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("links.db"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(listRecipes(db).empty());

    // Default: saved with the recipe's own data; the unknown ones are reported and unlinked.
    const auto saved = saveRecipeVersion(db, test::minimalRecipe("r"), by("alice"));
    ASSERT_EQ(saved.unlinked.size(), 2U);
    EXPECT_EQ(saved.unlinked[0], "layers[0].components[0] (pigment 'red')");
    EXPECT_EQ(saved.unlinked[1], "layers[0].components[1] (mirror_flake 'aluminium')");
    const auto stored = loadRecipeVersion(db, "r");
    ASSERT_EQ(stored.layers.size(), 1U);
    EXPECT_EQ(stored.layers[0].binder_ingredient_id, binder_id);
    ASSERT_EQ(stored.layers[0].components.size(), 2U);
    EXPECT_EQ(stored.layers[0].components[0].kind, "pigment");
    EXPECT_FALSE(stored.layers[0].components[0].ingredient_id.has_value());
    EXPECT_DOUBLE_EQ(stored.layers[0].components[0].volume_fraction, 0.1);
}

TEST(Recipes, InvalidRecipeIsRefusedBeforeAnyWrite) {
    TempDir dir;
    Database db = Database::open(dir / "invalid.db");
    Recipe bad = test::minimalRecipe("bad");
    bad.layers[0].thickness_um = -1.0;
    try {
        saveRecipeVersion(db, bad, {"alice", "", false, "bad.json"});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), "bad.json");
        EXPECT_NE(e.field().find("thickness_um"), std::string::npos) << e.what();
    }
    EXPECT_THROW(saveRecipeVersion(db, test::minimalRecipe(), {"", "", false, ""}), InputError);  // no author
    EXPECT_TRUE(listRecipes(db).empty());
}

TEST(DemoDatabase, HoldsTheDemoRecipesLinkedToTheirIngredients) {
    TempDir dir;
    Database db = Database::open(dir / "demo.db");
    const auto summary = initDemoDatabase(db);
    EXPECT_EQ(summary.ingredients_added, 16);
    EXPECT_EQ(summary.recipes_added, 5);
    EXPECT_TRUE(initDemoDatabase(db).already_initialised);  // a second run adds nothing
    EXPECT_EQ(searchIngredients(db).size(), 16U);

    const auto recipes_dir = std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes";
    int checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(recipes_dir)) {
        const Recipe expected = loadRecipeFile(entry.path());
        const auto stored = loadRecipeVersion(db, expected.name);
        EXPECT_EQ(stored.recipe, expected) << entry.path();
        EXPECT_EQ(stored.info.version, 1);
        for (const auto& layer : stored.layers) {
            // Every ingredient of a paint is in the demo library; the validation slab's are not.
            const bool validation_slab = expected.name == "Raw medium slab (validation)";
            EXPECT_EQ(layer.binder_ingredient_id.has_value(), !validation_slab) << layer.binder_name;
            for (const auto& component : layer.components)
                EXPECT_EQ(component.ingredient_id.has_value(), !validation_slab) << component.name;
        }
        ++checked;
    }
    EXPECT_EQ(checked, 5);
    const auto al = findIngredient(db, IngredientKind::MirrorFlake, "aluminium flakes");
    ASSERT_TRUE(al);
    EXPECT_NE(al->spectrum_info.at("n").source.find("Rakić"), std::string::npos);
    EXPECT_EQ(al->density_g_cm3, 2.70);
    EXPECT_TRUE(db.integrityCheck().empty());
}

TEST(DemoDatabase, DefaultPathFollowsXdg) {
    ASSERT_EQ(setenv("XDG_DATA_HOME", "/data/home", 1), 0);  // NOLINT(concurrency-mt-unsafe)
    EXPECT_EQ(defaultDatabasePath(), std::filesystem::path("/data/home/paintlab/paintlab.db"));
    ASSERT_EQ(setenv("XDG_DATA_HOME", "relative/path", 1), 0);  // NOLINT(concurrency-mt-unsafe): ignored
    ASSERT_EQ(setenv("HOME", "/home/lab", 1), 0);               // NOLINT(concurrency-mt-unsafe)
    EXPECT_EQ(defaultDatabasePath(), std::filesystem::path("/home/lab/.local/share/paintlab/paintlab.db"));
    ASSERT_EQ(unsetenv("XDG_DATA_HOME"), 0);  // NOLINT(concurrency-mt-unsafe)
    EXPECT_EQ(defaultDatabasePath(), std::filesystem::path("/home/lab/.local/share/paintlab/paintlab.db"));
}

TEST(DatabaseBackup, CopyHoldsEverythingAndNeverOverwrites) {
    TempDir dir;
    Database db = Database::open(dir / "live.db");
    initDemoDatabase(db);
    saveRecipeVersion(db, test::minimalRecipe(), by("alice"));
    db.backupTo(dir / "copy.db");
    EXPECT_THROW(db.backupTo(dir / "copy.db"), DatabaseError);
    Database copy = Database::open(dir / "copy.db");
    EXPECT_EQ(listRecipes(copy).size(), 6U);
    EXPECT_EQ(searchIngredients(copy).size(), 16U);
    EXPECT_TRUE(copy.integrityCheck().empty());
}

}  // namespace
}  // namespace paintlab::db
