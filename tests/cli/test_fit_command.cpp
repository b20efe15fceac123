// `paintlab-cli fit` as labs script it (issue 28, part 2): a measurement
// file simulated from a known recipe, fitted from a wrong first guess, gives
// the known value back, in the JSON contract's fields, the --out file and the
// database (--save); every bad input exits 2 naming the field, and saves
// nothing. The process is run as a whole (front end, helper, exit code).

#include "temp_dir.h"

#include "paintlab/database/database.h"
#include "paintlab/database/measurement_files.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace paintlab {
namespace {

using test::TempDir;

const std::string kSolidRed = std::string(PAINTLAB_DEMO_DIR) + "/recipes/solid-red.json";
constexpr double kTrueBasecoatUm = 1.0;  // thin enough not to hide the primer: thickness is determined
const std::string kBasecoat = "layers[1].thickness_um";

struct CliRun {
    int exit_code = -1;
    std::string out;
    std::string err;
};

std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

CliRun runCli(const TempDir& dir, const std::vector<std::string>& args) {
    std::string line = std::string("'") + PAINTLAB_CLI + "'";
    for (const auto& a : args) line += " '" + a + "'";
    const auto out = dir / "stdout.txt";
    const auto err = dir / "stderr.txt";
    line += " >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status =
        std::system(line.c_str());  // NOLINT(cert-env33-c): the test runs the CLI as a user does
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// The recipe's multi-angle spectra at the standard preset, as an instrument
// file (spectra and CIELAB per geometry), without noise.
std::filesystem::path simulatedMeasurement(const TempDir& dir, const Recipe& truth, const std::string& name) {
    const LayeredBrdf brdf = computeLayeredBrdf(truth, presetSettings(Preset::Standard));
    const MultiAngleReport report = multiAngleColours(brdf);
    db::Measurement m;
    m.name = name;
    m.instrument = "simulated";
    const auto wavelengths = brdf.wavelengthsNm();
    m.wavelengths_nm.assign(wavelengths.begin(), wavelengths.end());
    for (const auto& c : report.colours)
        m.readings.push_back({45.0, c.aspecular_deg, c.lab.L, c.lab.a, c.lab.b, c.reflectance_factor});
    return dir.write(name + ".json", db::measurementToJson(m));
}

struct FitFiles {
    TempDir dir;
    std::filesystem::path template_file;
    std::filesystem::path measurement;
    std::filesystem::path db;
};

void prepare(FitFiles& s) {
    Recipe truth = loadRecipeFile(kSolidRed);
    truth.layers.at(1).thickness_um = kTrueBasecoatUm;
    s.measurement = simulatedMeasurement(s.dir, truth, "red panel");
    Recipe guess = truth;
    guess.layers.at(1).thickness_um = 2.0;
    s.template_file = s.dir.write("template.json", recipeToJson(guess));
    s.db = s.dir / "lab.db";
    db::Database::open(s.db);  // created empty: saves are counted below
}

TEST(FitCommand, RecoversAThicknessFromASimulatedInstrumentFileAndSavesIt) {
    FitFiles s;
    prepare(s);
    const auto out = s.dir / "fitted.json";
    const CliRun run =
        runCli(s.dir, {"fit", s.template_file.string(), "--measurement", s.measurement.string(), "--free",
                       kBasecoat + "=0.3:5", "--starts", "4", "--json", "--out", out.string(), "--save",
                       "--author", "tester", "--note", "round trip", "--db", s.db.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto result = nlohmann::json::parse(run.out);
    ASSERT_EQ(result.at("parameters").size(), 1U);
    const auto& p = result.at("parameters")[0];
    EXPECT_EQ(p.at("path"), kBasecoat);
    // Noise-free data simulated at the report's own preset: the minimum is the
    // truth itself, so 1 % only absorbs the solver's stopping tolerance (the
    // first guess was 100 % off).
    EXPECT_NEAR(p.at("value").get<double>(), kTrueBasecoatUm, 0.01 * kTrueBasecoatUm);
    ASSERT_TRUE(p.at("sigma").is_number()) << "a thin basecoat's thickness is determined";
    EXPECT_GT(p.at("sigma").get<double>(), 0.0);
    EXPECT_FALSE(p.at("at_bound").get<bool>());
    ASSERT_EQ(result.at("geometries").size(), 6U);
    for (const auto& g : result.at("geometries")) {
        EXPECT_TRUE(g.contains("aspecular_deg"));
        // Far below what anyone sees (1 ΔE00): a converged fit of exact data.
        EXPECT_LT(g.at("delta_e00").get<double>(), 0.05) << g.dump();
    }
    // --out: a valid recipe file with the fitted value.
    const Recipe fitted = loadRecipeFile(out);
    EXPECT_NEAR(fitted.layers.at(1).thickness_um, kTrueBasecoatUm, 0.01 * kTrueBasecoatUm);
    // --save: the measurement, one new version and one fit row.
    db::Database database = db::Database::open(s.db);
    const auto history = db::recipeHistory(database, fitted.name);
    ASSERT_EQ(history.size(), 1U);
    EXPECT_EQ(history[0].author, "tester");
    ASSERT_TRUE(db::findMeasurement(database, "red panel").has_value());
    const auto fits = db::fitsOfRecipe(database, fitted.name);
    ASSERT_EQ(fits.size(), 1U);
    EXPECT_EQ(fits[0].measurement_name, "red panel");
    EXPECT_EQ(fits[0].recipe_version, history[0].version);
    EXPECT_EQ(fits[0].residuals.size(), 6U);
    EXPECT_NEAR(fits[0].parameters.at(kBasecoat), kTrueBasecoatUm, 0.01 * kTrueBasecoatUm);
    EXPECT_TRUE(fits[0].parameters.contains(kBasecoat + ".sigma"));
}

TEST(FitCommand, HelpWithATemplateListsItsParameterPaths) {
    TempDir dir;
    const CliRun run = runCli(dir, {"fit", kSolidRed, "--help"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("layers[1].components[0].volume_fraction"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("layers[0].thickness_um"), std::string::npos) << run.out;
}

struct BadFit {
    std::string label;
    std::vector<std::string> args;  // after the template; $M: the good measurement file
    std::string expected;           // in stderr
    std::string measurement_file;   // written for the case when not empty ($B)
    std::string measurement_text;
};

void PrintTo(const BadFit& bad, std::ostream* os) { *os << bad.label; }

class BadFitInput : public ::testing::TestWithParam<BadFit> {};

TEST_P(BadFitInput, ExitsTwoNamingTheFieldAndSavesNothing) {
    const BadFit& bad = GetParam();
    FitFiles s;
    prepare(s);
    std::string template_file = s.template_file.string();
    std::vector<std::string> args{"fit"};
    std::filesystem::path bad_file;
    if (!bad.measurement_file.empty()) bad_file = s.dir.write(bad.measurement_file, bad.measurement_text);
    bool first = true;
    for (const auto& a : bad.args) {
        if (first && a.starts_with("TEMPLATE=")) {
            template_file = std::string(PAINTLAB_TEST_DATA_DIR) + "/" + a.substr(9);
            continue;
        }
        first = false;
        args.push_back(a == "$M" ? s.measurement.string() : a == "$B" ? bad_file.string() : a);
    }
    args.insert(args.begin() + 1, template_file);
    for (const std::string& extra : {std::string("--save"), std::string("--db"), s.db.string(),
                                     std::string("--starts"), std::string("1")})
        args.push_back(extra);
    const CliRun run = runCli(s.dir, args);
    EXPECT_EQ(run.exit_code, 2) << bad.label << ": " << run.err;
    EXPECT_NE(run.err.find(bad.expected), std::string::npos) << bad.label << ": " << run.err;
    db::Database database = db::Database::open(s.db);
    EXPECT_TRUE(db::listRecipes(database).empty()) << bad.label;
    EXPECT_TRUE(db::listMeasurements(database).empty()) << bad.label;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadFitInput,
    ::testing::Values(
        BadFit{
            "no such path", {"--measurement", "$M", "--free", "layers[5].thickness_um"}, "layers[5]", "", ""},
        BadFit{"not numeric", {"--measurement", "$M", "--free", "layers[1].name"}, "layers[1].name", "", ""},
        BadFit{"bounds outside the allowed range",
               {"--measurement", "$M", "--free", "layers[1].components[0].volume_fraction=0.01:2"},
               "layers[1].components[0].volume_fraction",
               "",
               ""},
        BadFit{
            "bounds not numbers", {"--measurement", "$M", "--free", kBasecoat + "=a:b"}, "--free[0]", "", ""},
        BadFit{"no parameter", {"--measurement", "$M"}, "--free", "", ""},
        BadFit{"no measurement", {"--free", kBasecoat}, "--measurement", "", ""},
        BadFit{"NaN",
               {"--measurement", "$B", "--free", kBasecoat},
               "line 2, column L",
               "nan.csv",
               "aspecular_deg,L,a,b\n15,nan,0,0\n"},
        BadFit{"negative reflectance",
               {"--measurement", "$B", "--free", kBasecoat},
               "readings[0].reflectance[1]",
               "neg.csv",
               "aspecular_deg,400,700\n15,0.5,-0.1\n"},
        BadFit{"no readings",
               {"--measurement", "$B", "--free", kBasecoat},
               "readings",
               "empty.json",
               R"({"format": "paintlab-measurement", "format_version": 1, "name": "x", "kind": "multiangle",
                   "readings": []})"},
        BadFit{"wavelengths outside the model's",
               {"--measurement", "$B", "--free", kBasecoat},
               "wavelength",
               "ir.csv",
               "aspecular_deg,900nm,1000nm\n15,0.5,0.5\n"},
        BadFit{"template does not validate",
               {"TEMPLATE=bad_recipes/negative_thickness.json", "--measurement", "$M", "--free", kBasecoat},
               "negative_thickness.json",
               "",
               ""}),
    [](const auto& test_info) {
        std::string name = test_info.param.label;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

}  // namespace
}  // namespace paintlab
