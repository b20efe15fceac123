// Production sheets against a hand computation (production.h gives the
// formulas): tests/data/valid_minimal.json, one 20 µm layer of binder
// 'acrylic' with pigment 'red' (phi 0.10) and mirror flake 'aluminium'
// (phi 0.05), with densities chosen here. Mass balance (the masses add up to
// the batch, the dry volume fractions to 1) is checked on every demo recipe.

#include "db_test_support.h"

#include "paintlab/database/demo.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/production.h"
#include "paintlab/database/recipes.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>

namespace paintlab::db {
namespace {

using test::TempDir;

// Stores the minimal recipe's ingredients with their optical data and the
// given densities, then the recipe itself (so its rows link to them).
void storeMinimal(Database& db, std::optional<double> red_density = 5.0) {
    const Recipe recipe = test::minimalRecipe();
    const Layer& layer = recipe.layers.at(0);
    Ingredient binder;
    binder.name = "acrylic";
    binder.density_g_cm3 = 1.2;
    binder.solids_mass_fraction = 0.5;
    binder.volatile_density_g_cm3 = 0.8;
    binder.data = layer.binder;
    createIngredient(db, binder);
    Ingredient red;
    red.name = "red";
    red.density_g_cm3 = red_density;
    red.limits.max_volume_fraction = 0.08;  // the recipe's 0.10 is above it: a warning
    Pigment pigment = std::get<Pigment>(layer.components.at(0));
    pigment.volume_fraction = 0.0;
    red.data = pigment;
    createIngredient(db, red);
    Ingredient aluminium;
    aluminium.name = "aluminium";
    aluminium.density_g_cm3 = 2.7;
    MirrorFlake flake = std::get<MirrorFlake>(layer.components.at(1));
    flake.volume_fraction = 0.0;
    aluminium.data = flake;
    createIngredient(db, aluminium);
    SaveOptions save;
    save.author = "tester";
    saveRecipeVersion(db, recipe, save);
}

// The minimal recipe's sheet for a 1 kg batch of its newest version.
ProductionSheet minimalSheetPerKg(Database& db) {
    storeMinimal(db);
    ProductionOptions options;
    options.batch_kg = 1.0;
    return productionSheet(db, "test basecoat", std::nullopt, options);
}

const ProductionLine& line(const ProductionLayer& layer, const std::string& name) {
    for (const auto& l : layer.lines)
        if (l.name == name) return l;
    throw std::runtime_error("no line " + name);
}

// Per cm3 of dry film: m_red = 0.10 * 5.0 = 0.5 g, m_Al = 0.05 * 2.7 = 0.135 g,
// binder solids m_b = 0.85 * 1.2 = 1.02 g, as bought m_b / 0.5 = 2.04 g with
// 1.02 g of volatiles = 1.275 cm3 at 0.8 g/cm3. m_dry = 1.655 g, m_wet = 2.675 g.
// Tolerances: 1e-12 relative, rounding of a handful of double operations.
TEST(Production, BatchByMassMatchesTheHandComputation) {
    TempDir dir;
    Database db = Database::open(dir / "p.db");
    const ProductionSheet sheet = minimalSheetPerKg(db);
    EXPECT_EQ(sheet.version.version, 1);
    EXPECT_EQ(sheet.version.checksum_sha256.size(), 64U);
    ASSERT_EQ(sheet.layers.size(), 1U);
    const ProductionLayer& layer = sheet.layers[0];
    constexpr double kTol = 1e-12;
    EXPECT_NEAR(line(layer, "red").mass_kg, 0.5 / 2.675, kTol);
    EXPECT_NEAR(line(layer, "aluminium").mass_kg, 0.135 / 2.675, kTol);
    EXPECT_NEAR(line(layer, "acrylic").mass_kg, 2.04 / 2.675, kTol);
    EXPECT_EQ(layer.lines.front().kind, "binder");
    EXPECT_NEAR(line(layer, "acrylic").dry_volume_fraction, 0.85, kTol);
    EXPECT_NEAR(line(layer, "red").dry_mass_fraction, 0.5 / 1.655, kTol);
    EXPECT_NEAR(layer.pigment_volume_concentration, 0.15, kTol);
    EXPECT_NEAR(layer.solids_mass_fraction, 1.655 / 2.675, kTol);
    ASSERT_TRUE(layer.solids_volume_fraction.has_value());
    EXPECT_NEAR(*layer.solids_volume_fraction, 1.0 / 2.275, kTol);
    EXPECT_NEAR(*layer.wet_film_thickness_um, 20.0 * 2.275, 1e-10);
    EXPECT_NEAR(layer.dry_film_density_g_cm3, 1.655, kTol);
    EXPECT_NEAR(*layer.wet_density_g_cm3, 2.675 / 2.275, kTol);
    EXPECT_NEAR(layer.coating_weight_g_m2, 33.1, 1e-10);
    EXPECT_NEAR(layer.spreading_rate_m2_kg, 1000.0 / (20.0 * 2.675), 1e-10);
    ASSERT_EQ(layer.warnings.size(), 1U);
    EXPECT_NE(layer.warnings[0].find("layers[0].components[0] (pigment 'red'): volume fraction 0.1 is above "
                                     "its technological maximum 0.08"),
              std::string::npos)
        << layer.warnings[0];
}

// 2 m2 at 20 µm = 40 cm3 of dry film = 107 g of wet paint; half of it lands
// (transfer efficiency 0.5): 0.214 kg.
TEST(Production, BatchByAreaMatchesTheHandComputation) {
    TempDir dir;
    Database db = Database::open(dir / "p.db");
    storeMinimal(db);
    ProductionOptions options;
    options.area_m2 = 2.0;
    options.transfer_efficiency = 0.5;
    const auto sheet = productionSheet(db, "test basecoat", 1, options);
    EXPECT_NEAR(sheet.layers[0].batch_mass_kg, 0.214, 1e-12);
    EXPECT_NEAR(line(sheet.layers[0], "red").mass_kg, 0.214 * 0.5 / 2.675, 1e-12);
}

TEST(Production, MassBalanceHoldsForEveryDemoRecipe) {
    TempDir dir;
    Database db = Database::open(dir / "demo.db");
    initDemoDatabase(db);
    ProductionOptions options;
    options.batch_kg = 2.5;
    int sheets = 0;
    for (const auto& recipe : listRecipes(db)) {
        if (recipe.name.find("slab") != std::string::npos) continue;  // a raw medium: no composition
        const auto sheet = productionSheet(db, recipe.name, std::nullopt, options);
        for (const auto& layer : sheet.layers) {
            double mass = 0.0;
            double volume = 0.0;
            double dry_mass = 0.0;
            for (const auto& l : layer.lines) {
                mass += l.mass_kg;
                volume += l.dry_volume_fraction;
                dry_mass += l.dry_mass_fraction;
                EXPECT_GT(l.mass_kg, 0.0) << recipe.name << " " << l.name;
            }
            // Sums of a few terms of order 1: 1e-12 covers their rounding.
            EXPECT_NEAR(mass, 2.5, 1e-12) << recipe.name << " " << layer.name;
            EXPECT_NEAR(volume, 1.0, 1e-12) << recipe.name << " " << layer.name;
            EXPECT_NEAR(dry_mass, 1.0, 1e-12) << recipe.name << " " << layer.name;
        }
        ++sheets;
    }
    EXPECT_EQ(sheets, 4);
}

TEST(Production, MissingDensityUnlinkedIngredientAndRawMediumAreNamed) {
    TempDir dir;
    Database db = Database::open(dir / "p.db");
    storeMinimal(db, std::nullopt);
    ProductionOptions options;
    options.batch_kg = 1.0;
    try {
        productionSheet(db, "test basecoat", std::nullopt, options);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "p.db: layers[0].components[0] (pigment 'red'): the ingredient has no density"),
                  std::string::npos)
            << e.what();
    }
    SaveOptions save;
    save.author = "tester";
    saveRecipeVersion(db, test::minimalRecipe("unlinked"), save);
    Database other = Database::open(dir / "other.db");
    saveRecipeVersion(other, test::minimalRecipe(), save);
    try {
        productionSheet(other, "test basecoat", std::nullopt, options);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("layers[0].components[0] (pigment 'red'): not in the database"),
                  std::string::npos)
            << e.what();
    }
    // Ingredients added after the version was saved (unlinked) are found by kind and name.
    storeMinimal(other);
    EXPECT_NEAR(line(productionSheet(other, "test basecoat", 1, options).layers.at(0), "red").mass_kg,
                0.5 / 2.675, 1e-12);
    initDemoDatabase(other);  // already holds a recipe: adds nothing
    Database demo = Database::open(dir / "demo.db");
    initDemoDatabase(demo);
    for (const auto& recipe : listRecipes(demo)) {
        if (recipe.name.find("slab") != std::string::npos) {
            EXPECT_THROW(productionSheet(demo, recipe.name, std::nullopt, options), InputError);
        }
    }
    ProductionOptions both;
    both.batch_kg = 1.0;
    both.area_m2 = 1.0;
    EXPECT_THROW(validateProductionOptions(both), InputError);
    ProductionOptions negative;
    negative.batch_kg = -1.0;
    EXPECT_THROW(validateProductionOptions(negative), InputError);
}

TEST(Production, SheetsNameTheVersionAndChecksumAndEscapeNames) {
    TempDir dir;
    Database db = Database::open(dir / "p.db");
    const auto sheet = minimalSheetPerKg(db);
    const std::string html = productionHtml(sheet);
    EXPECT_NE(html.find(sheet.version.checksum_sha256), std::string::npos);
    EXPECT_NE(html.find("Recipe version</td><td class=\"text\">1<"), std::string::npos);
    EXPECT_NE(html.find("test basecoat"), std::string::npos);
    const auto json = nlohmann::json::parse(productionJson(sheet));
    EXPECT_EQ(json["checksum_sha256"], sheet.version.checksum_sha256);
    EXPECT_EQ(json["version"], 1);
    EXPECT_NEAR(json["layers"][0]["ingredients"][1]["mass_kg"].get<double>(), 0.5 / 2.675, 1e-12);
    const std::string csv = productionCsv(sheet);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);  // header + 3 ingredients
    EXPECT_NE(csv.find(sheet.version.checksum_sha256), std::string::npos);

    ProductionSheet hostile = sheet;
    hostile.version.recipe_name = "<script>alert('x')</script> & \"co\"";
    const std::string escaped = productionHtml(hostile);
    EXPECT_EQ(escaped.find("<script>"), std::string::npos);
    EXPECT_NE(escaped.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;co&quot;"),
              std::string::npos);
}

}  // namespace
}  // namespace paintlab::db
