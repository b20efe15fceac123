// Ingredient repository: every kind round-trips with its provenance, search
// filters by name, kind and tags, hostile names are data (never SQL), bad
// ingredients are refused naming the field, used ingredients cannot be deleted.

#include "db_test_support.h"

#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/recipes.h"

#include <gtest/gtest.h>

namespace paintlab::db {
namespace {

using test::TempDir;

const std::string kHostile =
    "Robert'); DROP TABLE ingredient;-- \"quoted\" ; SELECT * FROM spectrum; 50% _x_ \\ é";

Ingredient pigment(const std::string& name) {
    Ingredient ing;
    ing.name = name;
    ing.description = "test pigment";
    ing.source = "made up for the test";
    ing.density_g_cm3 = 4.23;
    ing.density_source = "CRC";
    ing.tags = {"white", "Pigment"};
    ing.limits.max_volume_fraction = 0.25;
    Pigment data;
    data.name = name;
    data.source = ing.source;
    data.sigma_a_per_um = Spectrum({400, 500, 700}, {0.1, 0.2, 0.3});
    data.sigma_s_per_um = Spectrum(20.0);
    data.hg_g = 0.5;
    data.particle_diameter_um = 0.23;
    ing.data = data;
    ing.spectrum_info["sigma_a_per_um"] = {"1/µm", "Mie; Devore (1951)", "1951"};
    return ing;
}

std::vector<Ingredient> oneOfEachKind() {
    std::vector<Ingredient> out;
    Ingredient binder;
    binder.name = "PMMA";
    binder.tags = {"binder"};
    binder.limits = {std::nullopt, 10.0, 50.0};
    binder.data = Binder{"PMMA", Spectrum({380, 780}, {1.50, 1.48}), Spectrum(0.0)};
    out.push_back(binder);
    out.push_back(pigment("rutile"));
    Ingredient mirror;
    mirror.name = "Al flake";
    mirror.source = "Rakic 1995";
    mirror.diameter_sd_um = 6.0;
    MirrorFlake m;
    m.name = "Al flake";
    m.source = "Rakic 1995";
    m.diameter_um = 18;
    m.thickness_um = 0.3;
    m.orientation_spread_deg = 12;
    m.metal_n = Spectrum({400, 600}, {0.49, 1.2});
    m.metal_k = Spectrum({400, 600}, {4.8, 7.2});
    mirror.data = m;
    out.push_back(mirror);
    Ingredient pearl;
    pearl.name = "blue pearl";
    pearl.diameter_sd_um = 5.0;
    InterferenceFlake p;
    p.name = "blue pearl";
    p.diameter_um = 18;
    p.orientation_spread_deg = 10;
    p.mica_thickness_nm = 350;
    p.mica_thickness_spread_nm = 40;
    p.tio2_thickness_nm = 120;
    p.tio2_thickness_spread_nm = 8;
    pearl.data = p;
    out.push_back(pearl);
    for (const Substrate& s : {Substrate{LambertianSubstrate{Spectrum(0.3)}},
                               Substrate{MetalSubstrate{Spectrum(1.2), Spectrum(7.0)}},
                               Substrate{BlackSubstrate{}}, Substrate{TransparentSubstrate{1.52}}}) {
        Ingredient substrate;
        substrate.name = "substrate " + std::string(substrateKind(s));
        substrate.data = s;
        out.push_back(substrate);
    }
    return out;
}

// What reading gives back: the ids, and the provenance filled in with its defaults.
void expectSame(const Ingredient& stored, const Ingredient& original) {
    Ingredient expected = original;
    expected.id = stored.id;
    std::sort(expected.tags.begin(), expected.tags.end(),
              [](const std::string& a, const std::string& b) { return a < b; });
    for (const auto& [key, info] : stored.spectrum_info) {
        if (expected.spectrum_info.count(key) == 0) {
            EXPECT_EQ(info.source, original.source) << key;
            expected.spectrum_info[key] = info;
        }
    }
    EXPECT_TRUE(stored == expected) << "ingredient '" << original.name << "' did not round-trip";
}

TEST(Ingredients, EveryKindRoundTrips) {
    TempDir dir;
    Database db = Database::open(dir / "i.db");
    for (const auto& ingredient : oneOfEachKind()) {
        const auto id = createIngredient(db, ingredient);
        const Ingredient stored = readIngredient(db, id);
        EXPECT_EQ(stored.kind(), ingredient.kind());
        expectSame(stored, ingredient);
        const auto found = findIngredient(db, ingredient.kind(), ingredient.name);
        ASSERT_TRUE(found.has_value());
        EXPECT_EQ(found->id, id);
    }
    const auto rutile = findIngredient(db, IngredientKind::Pigment, "rutile");
    ASSERT_TRUE(rutile);
    EXPECT_EQ(rutile->spectrum_info.at("sigma_a_per_um"),
              (SpectrumInfo{"1/µm", "Mie; Devore (1951)", "1951"}));
    EXPECT_EQ(rutile->spectrum_info.at("sigma_s_per_um").unit, "1/µm");  // from the parameter declaration
    EXPECT_EQ(ingredientSpectra(db, rutile->id).size(), 2U);
    EXPECT_TRUE(db.integrityCheck().empty());
}

TEST(Ingredients, HostileNamesAreDataNotSql) {
    TempDir dir;
    Database db = Database::open(dir / "hostile.db");
    Ingredient ing = pigment(kHostile);
    ing.tags = {kHostile, "a'b", "DROP TABLE tag;"};
    ing.description = kHostile;
    const auto id = createIngredient(db, ing);
    const Ingredient stored = readIngredient(db, id);
    EXPECT_EQ(stored.name, kHostile);
    EXPECT_EQ(stored.description, kHostile);
    EXPECT_EQ(stored.tags.size(), 3U);
    // The LIKE wildcards in the search text are literal.
    EXPECT_EQ(searchIngredients(db, {"50% _x_", std::nullopt, {}}).size(), 1U);
    EXPECT_EQ(searchIngredients(db, {"%", std::nullopt, {}}).size(), 1U);
    createIngredient(db, pigment("plain"));
    EXPECT_EQ(searchIngredients(db, {"%", std::nullopt, {}}).size(), 1U);
    EXPECT_EQ(searchIngredients(db, {"_", std::nullopt, {}}).size(), 1U);
    EXPECT_EQ(searchIngredients(db, {"", std::nullopt, {"DROP TABLE tag;"}}).size(), 1U);
    EXPECT_TRUE(db.integrityCheck().empty());
}

TEST(Ingredients, SearchByNameKindAndTags) {
    TempDir dir;
    Database db = Database::open(dir / "search.db");
    for (const auto& ingredient : oneOfEachKind()) createIngredient(db, ingredient);
    Ingredient red = pigment("iron oxide red");
    red.tags = {"red", "pigment"};
    createIngredient(db, red);

    EXPECT_EQ(searchIngredients(db).size(), 9U);
    EXPECT_EQ(searchIngredients(db, {"", IngredientKind::Substrate, {}}).size(), 4U);
    EXPECT_EQ(searchIngredients(db, {"", std::nullopt, {"PIGMENT"}}).size(), 2U);  // tags ignore case
    const auto white = searchIngredients(db, {"", std::nullopt, {"pigment", "white"}});
    ASSERT_EQ(white.size(), 1U);
    EXPECT_EQ(white[0].name, "rutile");
    EXPECT_EQ(searchIngredients(db, {"OXIDE", IngredientKind::Pigment, {}}).size(), 1U);
    EXPECT_TRUE(searchIngredients(db, {"oxide", IngredientKind::Binder, {}}).empty());
    EXPECT_TRUE(searchIngredients(db, {"", std::nullopt, {"no such tag"}}).empty());
}

TEST(Ingredients, UpdateReplacesEverythingInOneGo) {
    TempDir dir;
    Database db = Database::open(dir / "update.db");
    const auto id = createIngredient(db, pigment("p"));
    const auto spectra_before = test::rawQuery(db.file(), "SELECT count(*) FROM spectrum");
    Ingredient changed = pigment("p renamed");
    changed.id = id;
    changed.tags = {"new"};
    changed.limits = {};
    std::get<Pigment>(changed.data).hg_g = -0.2;
    updateIngredient(db, changed);
    expectSame(readIngredient(db, id), changed);
    // The old spectra went with the old data.
    EXPECT_EQ(test::rawQuery(db.file(), "SELECT count(*) FROM spectrum"), spectra_before);

    changed.id = 999;
    EXPECT_THROW(updateIngredient(db, changed), InputError);
}

TEST(Ingredients, BadIngredientsAreRefusedNamingTheField) {
    TempDir dir;
    Database db = Database::open(dir / "bad.db");
    auto expectRefusal = [&](const Ingredient& ingredient, const std::string& field) {
        try {
            createIngredient(db, ingredient);
            FAIL() << "accepted, expected a complaint about " << field;
        } catch (const InputError& e) {
            EXPECT_NE(e.field().find(field), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.db"), std::string::npos) << e.what();
        }
    };
    Ingredient bad = pigment("p");
    std::get<Pigment>(bad.data).hg_g = 1.5;
    expectRefusal(bad, "hg_g");
    bad = pigment("p");
    bad.density_g_cm3 = -1.0;
    expectRefusal(bad, "density_g_cm3");
    bad = pigment("p");
    bad.limits = {0.0, std::nullopt, std::nullopt};
    expectRefusal(bad, "max_volume_fraction");
    bad = pigment("p");
    bad.limits = {std::nullopt, 30.0, 10.0};
    expectRefusal(bad, "limits");
    bad = pigment("");
    expectRefusal(bad, "name");
    Ingredient both = oneOfEachKind()[2];
    std::get<MirrorFlake>(both.data).reflectance = Spectrum(0.9);
    expectRefusal(both, "reflectance");

    createIngredient(db, pigment("p"));
    expectRefusal(pigment("p"), "name");  // duplicate kind + name
    EXPECT_EQ(searchIngredients(db).size(), 1U);
    EXPECT_EQ(test::rawQuery(db.file(), "SELECT count(*) FROM spectrum"), "2");  // nothing half written
}

TEST(Ingredients, UsedIngredientCannotBeDeleted) {
    TempDir dir;
    Database db = Database::open(dir / "delete.db");
    Ingredient acrylic;
    acrylic.name = "acrylic";  // the binder of the minimal recipe
    acrylic.data = Binder{"acrylic", Spectrum(1.5), Spectrum(0.0)};
    const auto used = createIngredient(db, acrylic);
    const auto unused = createIngredient(db, pigment("unused"));
    saveRecipeVersion(db, test::minimalRecipe(), {"tester", "", false, ""});
    EXPECT_THROW(deleteIngredient(db, used), InputError);
    EXPECT_NO_THROW(readIngredient(db, used));
    deleteIngredient(db, unused);
    EXPECT_THROW(readIngredient(db, unused), InputError);
    EXPECT_EQ(test::rawQuery(db.file(), "SELECT count(*) FROM spectrum"), "2");  // the binder's two
    EXPECT_THROW(deleteIngredient(db, unused), InputError);
}

TEST(Ingredients, StandaloneSpectra) {
    TempDir dir;
    Database db = Database::open(dir / "spectra.db");
    const Spectrum measured({400, 410.5, 700}, {0.1, 0.123456789012345, 0.3});
    const auto id = addSpectrum(db, "reflectance", measured, {"1", "X-Rite MA-T12, panel 7", "2026-11-20"});
    const auto stored = readSpectrum(db, id);
    EXPECT_EQ(stored.spectrum, measured);  // doubles read back exactly
    EXPECT_EQ(stored.quantity, "reflectance");
    EXPECT_EQ(stored.info.source, "X-Rite MA-T12, panel 7");
    EXPECT_THROW(readSpectrum(db, id + 1), InputError);
}

TEST(IngredientJson, WriteThenReadGivesEqualIngredients) {
    const auto ingredients = oneOfEachKind();
    const auto parsed = parseIngredientsJson(ingredientsToJson(ingredients), "<test>");
    ASSERT_EQ(parsed.size(), ingredients.size());
    for (std::size_t i = 0; i < parsed.size(); ++i) {
        Ingredient expected = ingredients[i];
        // The writer fills in the provenance defaults explicitly.
        for (const auto& [key, info] : parsed[i].spectrum_info)
            if (expected.spectrum_info.count(key) == 0) expected.spectrum_info[key] = info;
        EXPECT_TRUE(parsed[i] == expected) << ingredients[i].name;
    }
}

TEST(IngredientJson, ErrorsNameSourceAndField) {
    auto expectError = [](const std::string& text, const std::string& field) {
        try {
            parseIngredientsJson(text, "lab.json");
            FAIL() << text;
        } catch (const InputError& e) {
            EXPECT_EQ(e.source(), "lab.json");
            EXPECT_NE(e.field().find(field), std::string::npos) << e.what();
        }
    };
    expectError("{", "");
    expectError(R"({"format": "x", "format_version": 1, "ingredients": []})", "format");
    expectError(
        R"({"format": "paintlab-ingredients", "format_version": 1, "ingredients": [{"kind": "glue"}]})",
        "ingredients[0].kind");
    expectError(R"({"format": "paintlab-ingredients", "format_version": 1, "ingredients": [
        {"kind": "binder", "name": "b", "colour": "red", "spectra": {
          "refractive_index": {"unit": "1", "source": "s", "value": 1.5},
          "absorption_per_um": {"unit": "1/µm", "source": "s", "value": 0}}}]})",
                "ingredients[0].colour");
    expectError(R"({"format": "paintlab-ingredients", "format_version": 1, "ingredients": [
        {"kind": "binder", "name": "b", "spectra": {
          "refractive_index": {"unit": "1", "source": "s", "wavelengths_nm": [500, 400], "values": [1, 2]},
          "absorption_per_um": {"unit": "1/µm", "source": "s", "value": 0}}}]})",
                "spectra.refractive_index");
}

TEST(IngredientJson, DemoLibraryParsesAndEveryIngredientIsValid) {
    const auto path = std::filesystem::path(PAINTLAB_DEMO_DIR) / "ingredients" / "demo-ingredients.json";
    const auto ingredients = parseIngredientsJson(test::fileBytes(path), path.string());
    EXPECT_EQ(ingredients.size(), 16U);
    TempDir dir;
    Database db = Database::open(dir / "demo-lib.db");
    for (const auto& ingredient : ingredients) {
        EXPECT_FALSE(ingredient.spectrum_info.empty() && ingredient.kind() != IngredientKind::Substrate)
            << ingredient.name;
        for (const auto& [key, info] : ingredient.spectrum_info) EXPECT_FALSE(info.source.empty()) << key;
        expectSame(readIngredient(db, createIngredient(db, ingredient)), ingredient);
    }
}

}  // namespace
}  // namespace paintlab::db
