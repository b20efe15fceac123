#include "temp_dir.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/recipe_validation.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

namespace paintlab {
namespace {

namespace fs = std::filesystem;

fs::path dataDir() { return PAINTLAB_TEST_DATA_DIR; }

std::vector<fs::path> demoRecipes() {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(fs::path(PAINTLAB_DEMO_DIR) / "recipes"))
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    return files;
}

TEST(RecipeJson, ParsesTheMinimalRecipe) {
    const Recipe r = loadRecipeFile(dataDir() / "valid_minimal.json");
    EXPECT_EQ(r.name, "test basecoat");
    ASSERT_EQ(r.layers.size(), 1u);
    EXPECT_EQ(r.layers[0].thickness_um, 20.0);
    ASSERT_EQ(r.layers[0].components.size(), 2u);
    const auto& pigment = std::get<Pigment>(r.layers[0].components[0]);
    EXPECT_EQ(pigment.sigma_a_per_um.values().size(), 4u);
    EXPECT_DOUBLE_EQ(pigment.sigma_a_per_um(590.0), 9.5);
    EXPECT_EQ(pigment.particle_diameter_um, params::kPigmentDiameter.defaultValue);  // absent -> default
    const auto& flake = std::get<MirrorFlake>(r.layers[0].components[1]);
    ASSERT_TRUE(flake.reflectance.has_value());
    EXPECT_FALSE(flake.metal_n.has_value());
    EXPECT_TRUE(std::holds_alternative<LambertianSubstrate>(r.substrate));
}

// Writing then reading gives an equal recipe, and the canonical text is a
// fixed point: read(write(r)) == r and write(read(write(r))) == write(r).
void expectRoundTrip(const Recipe& recipe) {
    const std::string text = recipeToJson(recipe);
    const Recipe again = parseRecipeJson(text, "round trip");
    EXPECT_EQ(again, recipe);
    EXPECT_EQ(recipeToJson(again), text);
}

TEST(RecipeJson, RoundTripsExactly) { expectRoundTrip(loadRecipeFile(dataDir() / "valid_minimal.json")); }

TEST(RecipeJson, RoundTripsEveryDemoRecipe) {
    const auto files = demoRecipes();
    ASSERT_GE(files.size(), 4u) << "the demo library must hold at least four recipes";
    for (const auto& file : files) {
        SCOPED_TRACE(file.string());
        expectRoundTrip(loadRecipeFile(file));
    }
}

TEST(RecipeJson, RoundTripsEveryKindAndAwkwardNumbers) {
    Recipe r;
    r.name = "every kind — ünïcode";
    r.description = "line\nbreak \"quoted\"";
    r.ambient_refractive_index = 1.0 + 1e-15;  // needs all 17 digits
    Layer layer;
    layer.name = "base";
    layer.thickness_um = 0.1 + 0.2;  // 0.30000000000000004
    layer.binder.refractive_index = Spectrum({380.0, 780.0}, {1.51, 1.49});
    Pigment p;
    p.name = "p";
    p.volume_fraction = 1.0 / 3.0;
    p.sigma_a_per_um = Spectrum(1e-300);
    p.sigma_s_per_um = Spectrum(123456.789e-3);
    p.depth_profile = DepthProfile{{0.0, 0.25, 1.0}, {2.0, 1.0, 0.5}};
    MirrorFlake m;
    m.name = "m";
    m.metal_n = Spectrum(1.2);
    m.metal_k = Spectrum({400.0, 700.0}, {4.9, 8.6});
    InterferenceFlake f;
    f.name = "f";
    f.mica_thickness_nm = 350.0;
    RawMedium raw;
    raw.name = "raw";
    raw.albedo = Spectrum(0.9);
    raw.optical_thickness = Spectrum(2.0);
    layer.components = {p, m, f, raw};
    r.layers = {layer};
    for (const Substrate& s : {Substrate{LambertianSubstrate{Spectrum(0.5)}}, Substrate{MetalSubstrate{}},
                               Substrate{BlackSubstrate{}}, Substrate{TransparentSubstrate{1.52}}}) {
        r.substrate = s;
        SCOPED_TRACE(std::string(substrateKind(s)));
        expectRoundTrip(r);
    }
}

TEST(RecipeJson, SaveIsAtomicAndReadable) {
    const fs::path dir = fs::temp_directory_path() / "paintlab_test_save";
    fs::create_directories(dir);
    const fs::path file = dir / "recipe.json";
    const Recipe r = loadRecipeFile(dataDir() / "valid_minimal.json");
    saveRecipeFile(r, file);
    EXPECT_EQ(loadRecipeFile(file), r);
    EXPECT_EQ(test::entriesOf(dir), std::vector<std::string>{"recipe.json"});  // no temporary left
    // A failing save (target directory missing) leaves nothing behind and throws.
    EXPECT_THROW(saveRecipeFile(r, dir / "missing" / "recipe.json"), Error);
    EXPECT_EQ(loadRecipeFile(file), r);  // the earlier save is intact
    fs::remove_all(dir);
}

TEST(RecipeJson, ErrorsNameTheSourceAndField) {
    try {
        parseRecipeJson(
            R"({"schema_version": 1, "name": "x", "layers": [{"name": "top"}], "substrate": {"kind": "black"}})",
            "inline.json");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), "inline.json");
        EXPECT_EQ(e.field(), "layers[0].thickness_um");
        EXPECT_NE(std::string(e.what()).find("missing required field"), std::string::npos);
    }
}

TEST(RecipeJson, RejectsBooleansAsNumbersAndNonObjects) {
    EXPECT_THROW(parseRecipeJson(R"([1, 2])", "a"), InputError);
    EXPECT_THROW(parseRecipeJson("garbage", "a"), InputError);
    EXPECT_THROW(parseRecipeJson(R"({"schema_version": 1.5})", "a"), InputError);
    EXPECT_THROW(
        parseRecipeJson(R"({"schema_version": 1, "name": "x", "layers": [{"name": "l", "thickness_um": true}],
                                    "substrate": {"kind": "black"}})",
                        "a"),
        InputError);
}

}  // namespace
}  // namespace paintlab
