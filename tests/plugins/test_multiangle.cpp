// The multi-angle CGATS plugin (plugins/multiangle): the made-up 6- and
// 12-geometry exports of tests/plugins read into measurements whose spectra
// reproduce the files' CIELAB, stored and read back unchanged; a file
// simulated from a known recipe at 15° and 45° illumination fitted back to
// that recipe; every kind of bad file refused naming the field.

#include "multiangle_cgats.h"

#include "paintlab/database/database.h"
#include "paintlab/database/fit_observations.h"
#include "paintlab/database/measurements.h"
#include "paintlab/engine/brdf.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/fit/fit.h"
#include "paintlab/engine/fit/parameter_paths.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/plugins/registry.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

namespace paintlab::plugins {
namespace {

using test::TempDir;

const std::filesystem::path kSix =
    std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "multiangle/multiangle_6.cgats";
const std::filesystem::path kTwelve =
    std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "multiangle/multiangle_12.cgats";
const std::filesystem::path kOutOfPlane =
    std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "multiangle/multiangle_12_out_of_plane.cgats";

std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The InputError's field when parsing throws one, "" otherwise (a test failure then).
std::string errorField(const std::string& text, const ReadOptions& options = {}) {
    try {
        (void)multiangle::parse(text, "bad.cgats", options);
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), "bad.cgats") << e.what();
        return e.field().empty() ? "<file>" : e.field();
    }
    ADD_FAILURE() << "accepted:\n" << text.substr(0, 400);
    return "";
}

// A minimal file: the header, DATA_FORMAT fields and rows as given.
std::string cgats(const std::string& fields, const std::vector<std::string>& rows,
                  const std::string& header = "") {
    std::string out = "CGATS.17\n" + header;
    const auto count = std::count(fields.begin(), fields.end(), ' ') + 1;
    out += "NUMBER_OF_FIELDS " + std::to_string(count) + "\nBEGIN_DATA_FORMAT\n" + fields +
           "\nEND_DATA_FORMAT\nNUMBER_OF_SETS " + std::to_string(rows.size()) + "\nBEGIN_DATA\n";
    for (const auto& row : rows) out += row + "\n";
    return out + "END_DATA\n";
}

TEST(MultiAngleGeometry, InstrumentSpellings) {
    const auto expect = [](std::string_view name, double illumination, double aspecular,
                           double azimuth = 0.0) {
        const auto g = db::parseMultiAngleGeometry(name);
        ASSERT_TRUE(g) << name;
        EXPECT_EQ(g->illumination_deg, illumination) << name;
        EXPECT_EQ(g->aspecular_deg, aspecular) << name;
        EXPECT_EQ(g->azimuth_deg, azimuth) << name;
    };
    expect("45as-15", 45, -15);
    expect("45as110", 45, 110);
    expect("r45as15", 45, 15);
    expect("R15AS-45", 15, -45);
    expect("45asMinus15", 45, -15);
    expect("r15as_45", 15, -45);
    expect("45\xC2\xB0"
           "as25\xC2\xB0",
           45, 25);
    expect("45as25az90", 45, 25, 90);
    expect("15as46.9az-104.5", 15, 46.9, -104.5);
    for (const std::string_view bad :
         {"", "as15", "45as", "45", "class", "45as1x", "-45as15", "45as--15", "45as15az"})
        EXPECT_FALSE(db::parseMultiAngleGeometry(bad)) << bad;
    expect("r45as25azMinus90", 45, 25, -90);
    EXPECT_EQ(db::multiAngleGeometryName(45, -15), "45as-15");
    EXPECT_EQ(db::multiAngleGeometryName(15, 80), "15as80");
    EXPECT_EQ(db::multiAngleGeometryName(45, 25, 90), "45as25az90");
}

TEST(MultiAngleCgats, ProbeSaysHowSure) {
    EXPECT_EQ(multiangle::probe(slurp(kSix)), 0.95);
    EXPECT_EQ(multiangle::probe(slurp(kTwelve)), 0.95);
    // Geometry only in the sample names.
    EXPECT_EQ(
        multiangle::probe(cgats("SAMPLE_ID SAMPLE_NAME LAB_L LAB_A LAB_B", {"1 \"blue 45as15\" 50 1 -20"})),
        0.9);
    // Spectra of single samples: CGATS, but not ours as far as the probe sees.
    EXPECT_EQ(multiangle::probe(slurp(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "db/panels.cgats")),
              0.1);
    EXPECT_EQ(multiangle::probe("{\"format\": \"paintlab-measurement\"}"), 0.0);
    std::mt19937 random(7);
    std::string noise(3000, '\0');
    for (char& c : noise) c = static_cast<char>(random());
    EXPECT_EQ(multiangle::probe(noise), 0.0);
}

TEST(MultiAngleCgats, SixGeometriesInPercentWithCielab) {
    const db::Measurement m = multiangle::readFile(kSix, {});
    EXPECT_EQ(m.name, "multiangle_6");
    EXPECT_EQ(m.kind, db::MeasurementKind::MultiAngle);
    EXPECT_EQ(m.instrument, "made-up 6-angle instrument");
    EXPECT_EQ(m.sample, "Blue metallic B-17");
    EXPECT_EQ(m.measured_at, "2026-03-14");
    EXPECT_EQ(m.geometry, "45as-15,15,25,45,75,110");
    EXPECT_EQ(m.illuminant, "D65");
    EXPECT_EQ(m.observer, "10deg");
    ASSERT_EQ(m.readings.size(), 6U);
    ASSERT_EQ(m.wavelengths_nm.size(), 31U);
    EXPECT_EQ(m.wavelengths_nm.front(), 400.0);
    EXPECT_EQ(m.wavelengths_nm.back(), 700.0);
    const std::vector<double> aspecular{-15, 15, 25, 45, 75, 110};
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(m.readings[i].illumination_deg, 45.0);
        EXPECT_EQ(m.readings[i].aspecular_deg, aspecular[i]);
    }
    // The file's first value, 77.99 %, as a reflectance factor; its LAB_L as written.
    EXPECT_DOUBLE_EQ(m.readings[0].reflectance[0], 0.7799);
    EXPECT_EQ(m.readings[0].L, 84.99);
}

// The unit chosen must make the spectra reproduce the file's own CIELAB (the
// instrument computes one from the other): D65/10° CIELAB of every stored
// spectrum against the file's LAB_L/A/B, written with 2 decimals from spectra
// also rounded (0.01 % or 0.0001): within 0.05 ΔE*ab. The other unit is off by
// tens of ΔE.
void expectSpectraReproduceLab(const db::Measurement& m) {
    const ColourConditions conditions{Illuminant::D65, Observer::Cie1964_10deg};
    for (const auto& r : m.readings) {
        const Lab lab = spectrumColour(m.wavelengths_nm, r.reflectance, conditions).lab;
        EXPECT_NEAR(lab.L, r.L, 0.05);
        EXPECT_NEAR(lab.a, r.a, 0.05);
        EXPECT_NEAR(lab.b, r.b, 0.05);
    }
}

TEST(MultiAngleCgats, TwelveGeometriesAsFractionsAt15And45Degrees) {
    const db::Measurement m = multiangle::readFile(kTwelve, {});
    ASSERT_EQ(m.readings.size(), 12U);
    EXPECT_EQ(m.geometry, "45as-15,15,25,45,75,110; 15as-45,-30,-15,15,45,80");
    EXPECT_EQ(m.readings[6].illumination_deg, 15.0);
    EXPECT_EQ(m.readings[6].aspecular_deg, -45.0);
    EXPECT_EQ(m.readings[11].aspecular_deg, 80.0);
    EXPECT_DOUBLE_EQ(m.readings[7].reflectance[0], 0.0648);  // "0.0648" in the file: fractions, kept
    expectSpectraReproduceLab(m);
    expectSpectraReproduceLab(multiangle::readFile(kSix, {}));
}

// An MA-T12-style export with rows out of the plane of incidence (issue 29):
// read with their azimuths, and a measurement the fit takes as it is.
TEST(MultiAngleCgats, OutOfPlaneRowsAreReadAndTheFitAcceptsThem) {
    const db::Measurement m = multiangle::readFile(kOutOfPlane, {});
    ASSERT_EQ(m.readings.size(), 13U);
    EXPECT_EQ(m.geometry, "45as-15,15,25,45,75,110,25az90,25az-90; 15as-45,-15,15,45,80");
    EXPECT_EQ(m.readings[11].illumination_deg, 45.0);
    EXPECT_EQ(m.readings[11].aspecular_deg, 25.0);
    EXPECT_EQ(m.readings[11].azimuth_deg, 90.0);
    EXPECT_EQ(m.readings[12].azimuth_deg, -90.0);
    EXPECT_EQ(m.readings[2].azimuth_deg, 0.0);
    expectSpectraReproduceLab(m);
    fit::FitProblem problem;
    problem.recipe =
        loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes/pearlescent-two-layer.json");
    problem.free.push_back({"layers[1].components[0].orientation_spread_deg", std::nullopt, std::nullopt});
    db::addFitObservation(problem.observations, m, fit::Side::Top);
    ASSERT_EQ(problem.observations.multi_angle.at(0).readings.size(), 13U);
    EXPECT_EQ(problem.observations.multi_angle[0].readings[12].azimuth_deg, -90.0);
    EXPECT_NO_THROW(fit::validateFitProblem(problem));
}

TEST(MultiAngleCgats, StoredAndReadBackUnchanged) {
    const TempDir dir;
    db::Database database = db::Database::open(dir / "lab.db");
    for (const auto& file : {kSix, kTwelve, kOutOfPlane}) {
        const db::Measurement m = multiangle::readFile(file, {});
        db::createMeasurement(database, m);
        auto stored = db::findMeasurement(database, m.name);
        ASSERT_TRUE(stored);
        stored->id = 0;
        EXPECT_EQ(*stored, m);
    }
}

TEST(MultiAngleCgats, TheRegistryChoosesByContent) {
    Registry registry;
    registry.loadFile(std::filesystem::path(PAINTLAB_TEST_PLUGIN_DIR) / "libpaintlab-plugin-multiangle.so");
    ASSERT_TRUE(registry.refusals().empty());
    // Both kinds claim .cgats: a multi-angle export is a measurement, a spectra file stays spectra.
    const ImporterChoice six = registry.importerFor(kSix);
    ASSERT_NE(six.measurement, nullptr);
    EXPECT_EQ(six.measurement->format().id, "multiangle-cgats");
    const ImporterChoice panels =
        registry.importerFor(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "db/panels.cgats");
    ASSERT_NE(panels.spectra, nullptr);
    EXPECT_EQ(panels.spectra->format().id, "spectra-cgats");
    EXPECT_TRUE(panels.plugin->builtIn());
}

TEST(MultiAngleCgats, SpectraOnlyLabOnlyAndNamesCarryingTheGeometry) {
    const std::string fields = "SAMPLE_NAME SPECTRAL_NM400 SPECTRAL_NM550 SPECTRAL_NM700";
    const std::vector<std::string> rows{"\"p 45as15\" 40 50 60", "\"p 45as25\" 8 9 10",
                                        "\"p 45as110\" 1.5 1.6 1.8"};
    // Percent or fractions cannot be told without CIELAB or a value far from specular above 2.
    EXPECT_EQ(errorField(cgats(fields, rows)), "unit");
    ReadOptions percent;
    percent.cgats.unit = "%";
    const db::Measurement m = multiangle::parse(cgats(fields, rows), "p.cgats", percent);
    ASSERT_EQ(m.readings.size(), 3U);
    EXPECT_EQ(m.sample, "p");
    EXPECT_EQ(m.readings[2].aspecular_deg, 110.0);
    EXPECT_EQ(m.geometry, "45as15,25,110");
    EXPECT_DOUBLE_EQ(m.readings[1].reflectance[2], 0.1);
    // CIELAB computed from the spectra (a neutral-ish grey: L* between the Y of 8 % and 10 %).
    EXPECT_GT(m.readings[1].L, 30.0);
    EXPECT_LT(m.readings[1].L, 38.0);
    // Far from specular, 30 can only be percent.
    const db::Measurement far =
        multiangle::parse(cgats(fields, {"\"p 45as15\" 40 50 60", "\"p 45as75\" 30 30 30"}), "far.cgats", {});
    EXPECT_DOUBLE_EQ(far.readings[1].reflectance[0], 0.3);
    // CIELAB only, geometry as two angles.
    const db::Measurement lab = multiangle::parse(
        cgats("ILLUMINATION_ANGLE ASPECULAR_ANGLE LAB_L LAB_A LAB_B", {"45 -15 80 1 -2", "15 80 30 1 -2"}),
        "lab.cgats", {});
    EXPECT_TRUE(lab.wavelengths_nm.empty());
    EXPECT_EQ(lab.readings[1].illumination_deg, 15.0);
    EXPECT_EQ(lab.readings[1].L, 30.0);
}

TEST(MultiAngleCgats, SeveralSamplesNeedTheOneToRead) {
    const std::string text =
        cgats("SAMPLE_NAME GEOMETRY LAB_L LAB_A LAB_B",
              {"A \"45as15\" 50 0 0", "A \"45as45\" 30 0 0", "B \"45as15\" 60 0 0", "B \"45as45\" 40 0 0"});
    EXPECT_EQ(errorField(text), "SAMPLE_NAME");
    ReadOptions b;
    b.description.sample = "B";
    const db::Measurement m = multiangle::parse(text, "ab.cgats", b);
    ASSERT_EQ(m.readings.size(), 2U);
    EXPECT_EQ(m.readings[0].L, 60.0);
}

TEST(MultiAngleCgats, BadFilesAreRefusedNamingTheField) {
    const std::string six = slurp(kSix);
    const auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = six;
        text.replace(text.find(from), from.size(), to);
        return text;
    };
    EXPECT_EQ(errorField(six.substr(0, six.size() / 2)), "<file>");  // truncated: lcms2's count
    EXPECT_EQ(errorField(replaced("NUMBER_OF_SETS 6", "NUMBER_OF_SETS 1000000000000")), "NUMBER_OF_SETS");
    EXPECT_EQ(errorField(replaced("NUMBER_OF_FIELDS 37", "NUMBER_OF_FIELDS 1e12")), "NUMBER_OF_FIELDS");
    EXPECT_EQ(errorField(replaced(" 77.99 ", " nan ")), "data set 1 (45as-15).SPECTRAL_NM400");
    EXPECT_EQ(errorField(replaced(" 77.99 ", " -7.99 ")), "data set 1 (45as-15).SPECTRAL_NM400");
    EXPECT_EQ(errorField(replaced("\"45as75\"", "\"45as-75\"")),
              "data set 5 (45as-75).geometry");  // below horizon
    EXPECT_EQ(errorField(replaced("\"45as75\"", "\"45as25az200\"")),
              "data set 5 (45as25az200).geometry");  // azimuth out of range
    EXPECT_EQ(errorField(replaced("\"45as75\"", "\"15as100az30\"")),
              "data set 5 (15as100az30).geometry");  // out of the plane and below the horizon
    EXPECT_EQ(errorField(replaced("\"45as75\"", "\"45as25aznan\"")), "data set 5.GEOMETRY");
    EXPECT_EQ(errorField(replaced("\"45as75\"", "\"45as15\"")), "data set 5 (45as15)");  // twice
    EXPECT_EQ(errorField(replaced("\"45as75\"", "\"sideways\"")), "data set 5.GEOMETRY");
    EXPECT_EQ(errorField(replaced("BEGIN_DATA_FORMAT", "BEGIN_DATA_FORMATX")), "<file>");
    EXPECT_EQ(errorField(replaced("Illumination=D65", "Illumination=F11")), "MEASUREMENT_SOURCE");
    EXPECT_EQ(errorField(cgats("SAMPLE_NAME LAB_L LAB_A LAB_B", {"plain 50 0 0"})), "data set 1.SAMPLE_NAME");
    EXPECT_EQ(errorField(cgats("GEOMETRY LAB_L LAB_A", {"\"45as15\" 50 0"})), "DATA_FORMAT");
    EXPECT_EQ(errorField(cgats("GEOMETRY SAMPLE_NAME", {"\"45as15\" x"})), "DATA_FORMAT");
    // The angle fields cannot carry the azimuth a sample name ends in.
    EXPECT_EQ(errorField(cgats("SAMPLE_NAME ILLUMINATION_ANGLE ASPECULAR_ANGLE LAB_L LAB_A LAB_B",
                               {"\"p 45as25az90\" 45 25 50 0 0"})),
              "data set 1.SAMPLE_NAME");
    std::mt19937 random(11);
    std::string noise(3000, '\0');
    for (char& c : noise) c = static_cast<char>(random());
    EXPECT_EQ(errorField(noise), "<file>");
}

// Physics: spectra simulated from the silver metallic demo recipe at all 12
// geometries (15° and 45° illumination, detector placed by the ASTM E2284
// definition of the aspecular angle: from the specular direction towards the
// light) and the two out-of-plane ones 45as25az+-90, written as CGATS, read
// and fitted from a wrong first guess: the orientation spread comes back. The
// same file with its 15° rows labelled 25° cannot be fitted as well: the
// illumination angle is used.
TEST(MultiAngleCgats, FittedBackAtBothIlluminationAngles) {
    Recipe truth = loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes/silver-metallic.json");
    const std::string path = "layers[1].components[0].orientation_spread_deg";
    constexpr double kTrueSpreadDeg = 12.0;
    fit::setParameterValue(truth, path, kTrueSpreadDeg);
    const LayeredBrdf brdf = computeLayeredBrdf(truth, presetSettings(Preset::Preview));
    const auto wavelengths = brdf.wavelengthsNm();
    std::string fields = "SAMPLE_NAME GEOMETRY";
    for (const double w : wavelengths) fields += " SPECTRAL_NM" + std::to_string(static_cast<int>(w));
    std::vector<std::string> rows;
    std::vector<std::string> rows_mislabelled;  // 15° written as 25°
    const std::vector<std::array<int, 3>> geometries{
        {45, -15, 0}, {45, 15, 0},  {45, 25, 0}, {45, 45, 0}, {45, 75, 0}, {45, 110, 0}, {15, -45, 0},
        {15, -30, 0}, {15, -15, 0}, {15, 15, 0}, {15, 45, 0}, {15, 80, 0}, {45, 25, 90}, {45, 25, -90}};
    for (const auto& [illumination, aspecular, azimuth] : geometries) {
        // Light at +illumination in the plane (phi 0), its mirror direction at -illumination;
        // the detector aspecular degrees from the mirror direction towards the light.
        const double detector = -illumination + aspecular;
        const Direction wi = directionFromAnglesDeg(illumination, 0.0);
        Direction wo = directionFromAnglesDeg(std::abs(detector), detector >= 0.0 ? 0.0 : 180.0);
        if (azimuth != 0) {
            // By hand: az +-90 turns the detector a quarter turn about the mirror direction
            // m = (-sin i, 0, cos i): wo = cos(as) m -+ sin(as) y (engine/multiangle.h).
            const double i = illumination * std::numbers::pi / 180.0;
            const double as = aspecular * std::numbers::pi / 180.0;
            wo = {-std::sin(i) * std::cos(as), azimuth > 0 ? -std::sin(as) : std::sin(as),
                  std::cos(i) * std::cos(as)};
        }
        const auto colour = reflectanceFactorColour(brdf, wi, wo);
        std::ostringstream values;
        values.precision(17);
        for (const double r : colour.reflectance) values << ' ' << r;
        const std::string name = std::to_string(illumination) + "as" + std::to_string(aspecular) +
                                 (azimuth != 0 ? "az" + std::to_string(azimuth) : "");
        rows.push_back("panel \"" + name + "\"" + values.str());
        rows_mislabelled.push_back(
            "panel \"" + std::to_string(illumination == 15 ? 25 : 45) + "as" + std::to_string(aspecular) +
            (azimuth != 0 ? "az" + std::to_string(azimuth) : "") + "\"" + values.str());
    }
    ReadOptions fractions;
    fractions.cgats.unit = "1";
    const auto fitted = [&](const std::vector<std::string>& data) {
        const db::Measurement m = multiangle::parse(cgats(fields, data), "simulated.cgats", fractions);
        fit::FitProblem problem;
        problem.recipe = truth;
        fit::setParameterValue(problem.recipe, path, 25.0);  // the wrong first guess
        problem.free.push_back({path, 3.0, 40.0});
        db::addFitObservation(problem.observations, m, fit::Side::Top);
        problem.settings.starts = 1;
        problem.settings.search_preset = Preset::Preview;
        problem.settings.polish_preset = Preset::Preview;
        return fit::fitRecipe(problem);
    };
    const fit::FitResult result = fitted(rows);
    // Noise-free data at the model's own preset: the optimiser's tolerance, not the data, limits this.
    EXPECT_NEAR(result.parameters.at(0).value, kTrueSpreadDeg, 0.05);
    double worst = 0.0;
    for (const auto& g : result.geometries) worst = std::max(worst, g.delta_e00);
    EXPECT_LT(worst, 0.05);
    const fit::FitResult mislabelled = fitted(rows_mislabelled);
    EXPECT_GT(mislabelled.cost, 100.0 * std::max(result.cost, 1e-6));
}

}  // namespace
}  // namespace paintlab::plugins
