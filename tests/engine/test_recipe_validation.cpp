#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/recipe_paths.h"
#include "paintlab/engine/recipe_validation.h"

#include <gtest/gtest.h>

#include <cmath>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

namespace paintlab {
namespace {

namespace fs = std::filesystem;

struct BadRecipeCase {
    const char* file;
    const char* field;    // must appear in InputError::field() (or the message for parse errors)
    const char* message;  // must appear in the message
};

// One file per kind of bad input the foundation issue lists, plus a few more.
const BadRecipeCase kBadRecipes[] = {
    {"missing_thickness.json", "thickness_um", "missing required field"},
    {"wrong_type.json", "thickness_um", "expected a number"},
    {"nan_value.json", "volume_fraction", "NaN"},
    {"infinity_value.json", "thickness_um", "Infinity"},
    {"overflow_value.json", "thickness_um", "too large to be finite"},
    {"negative_thickness.json", "layers[0].thickness_um", "-5 must be above 0"},
    {"zero_layers.json", "layers", "no layers"},
    {"unknown_component_kind.json", "kind", "unknown component kind 'glitter'"},
    {"concentration_above_limit.json", "layers[0].components[1].volume_fraction",
     "0.45 is above the maximum 0.3"},
    {"total_volume_fraction_above_one.json", "components", "total volume fraction 1.1"},
    {"orientation_spread_out_of_range.json", "orientation_spread_deg", "120 is above the maximum 90"},
    {"unsupported_schema_version.json", "schema_version", "unsupported schema version 99"},
    {"truncated.json", "", "truncated"},
    {"empty.json", "", "empty"},
    {"unknown_field.json", "thicknes_um", "unknown field"},
    {"spectrum_length_mismatch.json", "sigma_a_per_um", "4 wavelengths but 3 values"},
    {"flake_both_reflectance_and_nk.json", "reflectance", "exactly one"},
    {"profile_peak_above_limit.json", "depth_profile", "peak volume fraction 0.4"},
    {"deep_nesting.json", "", "nested deeper"},
};

// Readable test names and failure messages instead of a byte dump.
void PrintTo(const BadRecipeCase& c, std::ostream* os) { *os << c.file; }

class BadRecipe : public testing::TestWithParam<BadRecipeCase> {};

TEST_P(BadRecipe, IsRejectedWithTheFieldNamed) {
    const BadRecipeCase& c = GetParam();
    const fs::path file = fs::path(PAINTLAB_TEST_DATA_DIR) / "bad_recipes" / c.file;
    ASSERT_TRUE(fs::exists(file)) << file;
    try {
        loadRecipeFile(file);
        FAIL() << c.file << " was accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.source(), file.string());
        EXPECT_NE(what.find(c.field), std::string::npos) << what;
        EXPECT_NE(what.find(c.message), std::string::npos) << what;
    }
}

INSTANTIATE_TEST_SUITE_P(Files, BadRecipe, testing::ValuesIn(kBadRecipes),
                         [](const testing::TestParamInfo<BadRecipeCase>& param_info) {
                             std::string name = param_info.param.file;
                             name = name.substr(0, name.find('.'));
                             return name;
                         });

TEST(BadRecipeFile, HugeGarbageIsRejectedFromItsSizeWithoutReadingIt) {
    // A sparse 100 MB file: rejecting it must not depend on reading 100 MB.
    const fs::path file = fs::temp_directory_path() / "paintlab_garbage_100mb.json";
    { std::ofstream(file, std::ios::binary) << "garbage"; }
    fs::resize_file(file, std::uintmax_t{100} << 20);
    try {
        loadRecipeFile(file);
        FAIL() << "accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("104857600 bytes"), std::string::npos) << e.what();
    }
    fs::remove(file);
}

TEST(BadRecipeFile, RandomBytesBelowTheSizeCapAreRejected) {
    const fs::path file = fs::temp_directory_path() / "paintlab_garbage_random.json";
    std::mt19937 rng(7);
    std::string bytes(4u << 20, '\0');
    for (auto& b : bytes) b = static_cast<char>(rng() & 0xFF);
    bytes[0] = '{';  // get past the first-character check into the parser
    { std::ofstream(file, std::ios::binary) << bytes; }
    EXPECT_THROW(loadRecipeFile(file), InputError);
    fs::remove(file);
}

TEST(BadRecipeFile, MissingFileAndDirectoryAreNamed) {
    EXPECT_THROW(loadRecipeFile("/nonexistent/recipe.json"), InputError);
    EXPECT_THROW(loadRecipeFile(fs::temp_directory_path()), InputError);
}

Recipe minimal() { return loadRecipeFile(fs::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json"); }

TEST(RecipeFieldPaths, ReaderAndValidatorNameAFieldTheSameWay) {
    // One recipe, one field: a string where the number goes (the JSON
    // reader's message) and a number out of range (the validator's message).
    const fs::path file = fs::path(PAINTLAB_TEST_DATA_DIR) / "bad_recipes" / "concentration_above_limit.json";
    std::ifstream in(file);
    std::ostringstream contents;
    contents << in.rdbuf();
    const std::string text = contents.str();
    const std::string out_of_range = R"("volume_fraction": 0.45)";
    const std::size_t at = text.find(out_of_range);
    ASSERT_NE(at, std::string::npos);
    const std::string expected = componentPath(0, 1) + ".volume_fraction";
    ASSERT_EQ(expected, "layers[0].components[1].volume_fraction");
    std::string as_string = text;
    as_string.replace(at, out_of_range.size(), R"("volume_fraction": "0.45")");
    try {
        (void)parseRecipeJson(as_string);
        FAIL() << "a string volume fraction was read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), expected) << e.what();
    }
    try {
        validateRecipe(parseRecipeJson(text), "<recipe>");
        FAIL() << "a volume fraction of 0.45 passed";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), expected) << e.what();
    }
}

TEST(RecipeFieldPaths, BuildAndSplit) {
    EXPECT_EQ(layerPath(0), "layers[0]");
    EXPECT_EQ(binderPath(2), "layers[2].binder");
    EXPECT_EQ(depthProfilePath(1, 0), "layers[1].components[0].depth_profile");
    EXPECT_EQ(fieldPath("", "substrate"), "substrate");
    EXPECT_EQ(elementPath("depth_profile", "weight", 2), "depth_profile.weight[2]");
    EXPECT_EQ(ingredientLabel(componentPath(0, 1), "pigment", "red"),
              "layers[0].components[1] (pigment 'red')");

    const auto component = splitLayerPath("layers[1].components[10].depth_profile.weight[2]");
    ASSERT_TRUE(component.has_value());
    EXPECT_EQ(component->layer, 1U);
    EXPECT_EQ(component->component, std::optional<std::size_t>(10));
    EXPECT_EQ(component->rest, ".depth_profile.weight[2]");
    const auto layer = splitLayerPath("layers[3].components");
    ASSERT_TRUE(layer.has_value());
    EXPECT_EQ(layer->layer, 3U);
    EXPECT_FALSE(layer->component.has_value());
    EXPECT_EQ(layer->rest, ".components");
    EXPECT_FALSE(splitLayerPath("substrate.reflectance").has_value());
    EXPECT_FALSE(splitLayerPath("layers").has_value());
    EXPECT_FALSE(splitLayerPath("layers[x].name").has_value());
    EXPECT_FALSE(splitLayerPath("layers[0]name").has_value());
}

TEST(RecipeValidation, MinimalRecipeHasNoProblems) { EXPECT_TRUE(checkRecipe(minimal()).empty()); }

TEST(RecipeValidation, OutsideTypicalRangeIsOnlyAWarning) {
    Recipe r = minimal();
    r.layers[0].thickness_um = 300.0;  // thick but possible (e.g. a filler)
    const auto problems = checkRecipe(r);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].severity, Severity::Warning);
    EXPECT_NO_THROW(validateRecipe(r, "test"));
}

TEST(RecipeValidation, MetalFlakeNeedsBothNAndK) {
    Recipe r = minimal();
    auto& flake = std::get<MirrorFlake>(r.layers[0].components[1]);
    flake.reflectance.reset();
    flake.metal_n = Spectrum(1.2);
    EXPECT_THROW(validateRecipe(r, "test"), InputError);
    flake.metal_k = Spectrum(7.0);
    EXPECT_NO_THROW(validateRecipe(r, "test"));
}

TEST(RecipeValidation, DepthProfileShapeKeepsTheMean) {
    // w(z) = 2 - 2z (linear ramp): mean 1, peak 2, so the local volume fraction
    // is 2c at the top and 0 at the bottom while the mean stays c.
    const DepthProfile ramp{{0.0, 1.0}, {2.0, 0.0}};
    EXPECT_DOUBLE_EQ(ramp.meanWeight(), 1.0);
    EXPECT_DOUBLE_EQ(ramp.peakRelativeConcentration(), 2.0);
    EXPECT_DOUBLE_EQ(ramp.weightAt(0.25), 1.5);
    Recipe r = minimal();
    std::get<Pigment>(r.layers[0].components[0]).depth_profile = DepthProfile{{0.0, 0.5}, {1.0, 1.0}};
    EXPECT_THROW(validateRecipe(r, "test"), InputError);  // does not reach depth 1
}

TEST(RecipeValidation, DepthProfileNodesAreNamed) {
    // Each malformed profile names the node and says what is wrong with it,
    // in a file (checkRecipe's field path) as in the workstation's editor.
    struct Case {
        DepthProfile profile;
        std::string field;    // relative to the profile
        std::string message;  // a part of it
    };
    const std::vector<Case> cases = {
        {{{0.0, 0.5, 1.0}, {1.0, 1.0}}, "", "3 depths but 2 weights"},
        {{{0.0}, {1.0}}, "depth", "at least two nodes"},
        {{{0.0, std::nan(""), 1.0}, {1.0, 1.0, 1.0}}, "depth[1]", "not a finite number"},
        {{{0.1, 1.0}, {1.0, 1.0}}, "depth[0]", "0.1; the first node must be at 0"},
        {{{0.0, 0.9}, {1.0, 1.0}}, "depth[1]", "0.9; the last node must be at 1"},
        {{{0.0, 0.6, 0.4, 1.0}, {1.0, 1.0, 1.0, 1.0}}, "depth[2]", "0.4 is not below depth[1] (0.6)"},
        {{{0.0, 0.5, 1.0}, {1.0, -0.5, 1.0}}, "weight[1]", "-0.5 is below 0"},
        {{{0.0, 1.0}, {1.0, 2000.0}}, "weight[1]", "2000 is above the maximum 1000"},
        {{{0.0, 1.0}, {0.0, 0.0}}, "weight", "all weights are zero"},
    };
    for (const Case& c : cases) {
        const RecipeProblem p = depthProfileNodeProblem(c.profile);
        EXPECT_EQ(p.severity, Severity::Error);
        EXPECT_EQ(p.field, c.field) << c.message;
        EXPECT_NE(p.message.find(c.message), std::string::npos) << p.message;
        Recipe r = minimal();
        std::get<Pigment>(r.layers[0].components[0]).depth_profile = c.profile;
        const auto problems = checkRecipe(r);
        ASSERT_FALSE(problems.empty()) << c.message;
        const std::string where = c.field.empty() ? "depth_profile" : "depth_profile." + c.field;
        EXPECT_EQ(problems.front().field, "layers[0].components[0]." + where);
        EXPECT_EQ(problems.front().message, p.message);
    }
    EXPECT_TRUE(depthProfileNodeProblem(DepthProfile{{0.0, 0.3, 1.0}, {1.0, 0.0, 2.0}}).message.empty());
}

TEST(RecipeValidation, LocalTotalVolumeFractionWithProfiles) {
    // Means sum to 0.6 and each peak (0.6) is below the pigment maximum 0.64,
    // but both ramps peak at the top: 2 * 0.3 + 2 * 0.3 = 1.2.
    Recipe r = minimal();
    auto& pigment = std::get<Pigment>(r.layers[0].components[0]);
    pigment.volume_fraction = 0.3;
    pigment.depth_profile = DepthProfile{{0.0, 1.0}, {2.0, 0.0}};
    Pigment second = pigment;
    second.name = "second";
    r.layers[0].components = {pigment, second};
    try {
        validateRecipe(r, "test");
        FAIL() << "accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("local total volume fraction reaches 1.2"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace paintlab
