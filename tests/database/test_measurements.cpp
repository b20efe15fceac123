// Measurements and fits: multi-angle CIELAB and BRDF samples imported from
// instrument-style CSV and from JSON, round trips through the database and
// back out, fits linking a recipe version to a measurement, and bad files
// refused naming the file, the record and the field with nothing stored.

#include "db_test_support.h"

#include "paintlab/database/demo.h"
#include "paintlab/database/exchange.h"
#include "paintlab/database/measurement_files.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/recipes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <tuple>

namespace paintlab::db {
namespace {

using test::TempDir;

// As a BYK-mac exports a silver metallic panel (values made up for the test).
const std::string kMultiAngleCsv = "geometry,L*,a*,b*\n"
                                   "45as-15,131.2,-0.8,2.1\n"
                                   "45as15,112.5,-0.7,1.9\n"
                                   "45as25,88.4,-0.5,1.2\n"
                                   "45as45,52.0,-0.2,0.1\n"
                                   "45as75,34.6,0.1,-0.9\n"
                                   "45as110,30.2,0.2,-1.4\n";

const std::string kBrdfCsv = "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,450nm,550nm,650nm\n"
                             "30,0,30,180,2.5,2.75,3.0\n"
                             "30,0,0,0,0.05,0.06,0.07\n"
                             "60,0,45,90,0.01,0.0125,0.015\n";

Measurement description(const std::string& name) {
    Measurement m;
    m.name = name;
    m.instrument = "BYK-mac i";
    m.sample = "panel 7; \"silver\"";
    m.measured_at = "2024-06-01";
    return m;
}

// Stored in a database and read back, written as JSON and CSV and read back: the same measurement.
void expectStoredAndWrittenUnchanged(const Measurement& m) {
    TempDir dir;
    Database db = Database::open(dir / "m.db");
    createMeasurement(db, m);
    auto stored = findMeasurement(db, m.name);
    ASSERT_TRUE(stored.has_value());
    stored->id = 0;
    EXPECT_EQ(*stored, m);
    EXPECT_EQ(parseMeasurementJson(measurementToJson(*stored), "m.json"), m);
    EXPECT_EQ(parseMeasurementCsv(measurementToCsv(*stored), "m.csv", description(m.name)), m);
}

TEST(Measurements, MultiAngleCsvIsReadAndRoundTrips) {
    const Measurement m = parseMeasurementCsv(kMultiAngleCsv, "panel.csv", description("silver panel"));
    EXPECT_EQ(m.kind, MeasurementKind::MultiAngle);
    ASSERT_EQ(m.readings.size(), 6U);
    EXPECT_EQ(m.readings[0], (MultiAngleReading{45.0, -15.0, 131.2, -0.8, 2.1, {}}));
    EXPECT_EQ(m.readings[5].aspecular_deg, 110.0);
    TempDir dir;
    Database db = Database::open(dir / "m.db");
    const auto id = createMeasurement(db, m);
    auto stored = findMeasurement(db, "silver panel");
    ASSERT_TRUE(stored.has_value());
    EXPECT_EQ(stored->id, id);
    stored->id = 0;
    EXPECT_TRUE(*stored == m);
    // Out as JSON and CSV, and back in: the same measurement.
    EXPECT_TRUE(parseMeasurementJson(measurementToJson(*stored), "m.json") == m);
    EXPECT_TRUE(parseMeasurementCsv(measurementToCsv(*stored), "m.csv", description("silver panel")) == m);
}

TEST(Measurements, SpectralBrdfCsvIsReadAndRoundTripsThroughTheDatabase) {
    TempDir dir;
    const auto file = dir / "gonio.csv";
    test::writeBytes(file, kBrdfCsv);
    Database db = Database::open(dir / "m.db");
    ImportOptions options;
    options.measurement.instrument = "gonio";
    const auto result = importFile(db, file, options);
    EXPECT_EQ(result.kind, ContentKind::Measurement);
    ASSERT_EQ(result.names, std::vector<std::string>{"gonio"});  // named after the file
    const auto m = findMeasurement(db, "gonio");
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->kind, MeasurementKind::Brdf);
    EXPECT_EQ(m->wavelengths_nm, (std::vector<double>{450, 550, 650}));
    ASSERT_EQ(m->samples.size(), 3U);
    EXPECT_EQ(m->samples[2], (BrdfSample{60, 0, 45, 90, {0.01, 0.0125, 0.015}}));
    EXPECT_EQ(m->instrument, "gonio");
    const auto json_file = dir / "gonio-copy.json";
    Measurement renamed = *m;
    renamed.name = "gonio copy";
    test::writeBytes(json_file, measurementToJson(renamed));
    importFile(db, json_file);
    auto copy = findMeasurement(db, "gonio copy");
    ASSERT_TRUE(copy.has_value());
    copy->id = renamed.id;
    EXPECT_TRUE(*copy == renamed);
    const auto list = listMeasurements(db);
    ASSERT_EQ(list.size(), 2U);
    EXPECT_EQ(list[0].points, 3U);
}

TEST(Measurements, RgbBrdfJsonIsRead) {
    const auto m = parseMeasurementJson(R"({"format": "paintlab-measurement", "format_version": 1,
        "name": "rgb gonio", "kind": "brdf", "channels": ["R", "G", "B"],
        "samples": [{"theta_i_deg": 45, "phi_i_deg": 0, "theta_o_deg": 45, "phi_o_deg": 180, "values": [1, 2, 3]}]})",
                                        "rgb.json");
    EXPECT_EQ(m.channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(m.samples.at(0).values, (std::vector<double>{1, 2, 3}));
}

// A multi-angle spectrophotometer's export: reflectance factors per geometry
// and no CIELAB. A flat spectrum R has, for any illuminant and observer,
// Y = R and x, y of the white, so L* = 116 R^(1/3) - 16 and a* = b* = 0
// (CIE 15:2004): an independent check of the computed CIELAB.
TEST(Measurements, SpectralMultiAngleCsvGivesLabAndRoundTrips) {
    const std::string csv = "geometry,400nm,550nm,700nm\n"
                            "45as15,0.5,0.5,0.5\n"
                            "45as45,0.2,0.2,0.2\n"
                            "45as110,0.01,0.01,0.01\n";
    const Measurement m = parseMeasurementCsv(csv, "byk.csv", description("spectral panel"));
    EXPECT_EQ(m.kind, MeasurementKind::MultiAngle);
    EXPECT_EQ(m.wavelengths_nm, (std::vector<double>{400, 550, 700}));
    ASSERT_EQ(m.readings.size(), 3U);
    EXPECT_EQ(m.readings[1].reflectance, (std::vector<double>{0.2, 0.2, 0.2}));
    const auto lstar = [](double y) {
        return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : 24389.0 / 27.0 * y;
    };
    // 1e-3 in L*: the CIE tables' white is normalised to Y = 1 to double precision;
    // the tolerance only absorbs the summation's rounding.
    for (std::size_t i = 0; i < m.readings.size(); ++i) {
        const auto& r = m.readings[i];
        EXPECT_NEAR(r.L, lstar(r.reflectance[0]), 1e-3) << i;
        EXPECT_NEAR(r.a, 0.0, 1e-3) << i;
        EXPECT_NEAR(r.b, 0.0, 1e-3) << i;
    }
    expectStoredAndWrittenUnchanged(m);
}

// A 12-geometry instrument's rows out of the plane of incidence (issue 29):
// the azimuth is read from the geometry name or its own column, kept through
// the database, JSON and CSV, and written only where a reading has one.
TEST(Measurements, OutOfPlaneReadingsRoundTripAndInPlaneFilesStayAsBefore) {
    const Measurement m = parseMeasurementCsv("geometry,L,a,b\n45as25,50,1,2\n45as25az90,48,1,2\n"
                                              "45as25azMinus90,47,1,2\n15as-15,90,1,2\n",
                                              "ma-t12.csv", description("pearl"));
    ASSERT_EQ(m.readings.size(), 4U);
    EXPECT_EQ(m.readings[0].azimuth_deg, 0.0);
    EXPECT_EQ(m.readings[1].azimuth_deg, 90.0);
    EXPECT_EQ(m.readings[2].azimuth_deg, -90.0);
    EXPECT_EQ(m.readings[3].illumination_deg, 15.0);
    expectStoredAndWrittenUnchanged(m);
    const std::string json = measurementToJson(m);
    const std::string csv = measurementToCsv(m);
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "illumination_deg,aspecular_deg,azimuth_deg,L,a,b");
    // The azimuth column of a table without names.
    const Measurement columns = parseMeasurementCsv("aspecular_deg,azimuth_deg,L,a,b\n25,-90,47,1,2\n",
                                                    "columns.csv", description("pearl"));
    EXPECT_EQ(columns.readings[0].azimuth_deg, -90.0);
    // JSON only names the azimuth of out-of-plane readings: one key for two of the four.
    std::size_t keys = 0;
    for (auto at = json.find("azimuth_deg"); at != std::string::npos; at = json.find("azimuth_deg", at + 1))
        ++keys;
    EXPECT_EQ(keys, 2U);
    // In-plane measurements are written exactly as before azimuths existed.
    const Measurement plane = parseMeasurementCsv(kMultiAngleCsv, "panel.csv", description("silver panel"));
    EXPECT_EQ(measurementToJson(plane).find("azimuth"), std::string::npos);
    EXPECT_EQ(measurementToCsv(plane).substr(0, 39), "illumination_deg,aspecular_deg,L,a,b\n45");
}

// A database written before azimuths: its readings' JSON has no azimuth_deg
// (the readings live in measurement.data_json, so no column was added and the
// schema version is unchanged); it opens and reads them as in-plane.
TEST(Measurements, DatabaseFromBeforeAzimuthsReadsInPlane) {
    TempDir dir;
    const auto file = dir / "old.db";
    { Database created = Database::open(file); }
    ASSERT_EQ(test::rawExec(file, R"(INSERT INTO measurement (name, kind, instrument, geometry, sample,
        measured_at, data_json, source) VALUES ('old panel', 'multiangle', 'BYK-mac i', '45as15,110', '', '',
        '{"illuminant":"D65","observer":"10deg","readings":[{"illumination_deg":45.0,"aspecular_deg":15.0,
        "L":80.0,"a":1.0,"b":2.0},{"illumination_deg":45.0,"aspecular_deg":110.0,"L":30.0,"a":1.0,
        "b":2.0}]}', ''))"),
              SQLITE_OK);
    Database db = Database::open(file);
    const auto m = findMeasurement(db, "old panel");
    ASSERT_TRUE(m.has_value());
    ASSERT_EQ(m->readings.size(), 2U);
    EXPECT_EQ(m->readings[1], (MultiAngleReading{45.0, 110.0, 30.0, 1.0, 2.0, {}, 0.0}));
    EXPECT_TRUE(db.integrityCheck().empty());
}

TEST(Measurements, GeometryNamesRoundTrip) {
    for (const auto& [illumination, aspecular, azimuth, name] :
         std::vector<std::tuple<double, double, double, std::string>>{
             {45, -15, 0, "45as-15"},
             {15, 80, 0, "15as80"},
             {45, 25, 90, "45as25az90"},
             {45, 25, -90, "45as25az-90"},
             {15, 46.9, -104.5, "15as46.9az-104.5"}}) {
        EXPECT_EQ(multiAngleGeometryName(illumination, aspecular, azimuth), name);
        const auto parsed = parseMultiAngleGeometry(name);
        ASSERT_TRUE(parsed.has_value()) << name;
        EXPECT_EQ(parsed->illumination_deg, illumination) << name;
        EXPECT_EQ(parsed->aspecular_deg, aspecular) << name;
        EXPECT_EQ(parsed->azimuth_deg, azimuth) << name;
    }
    // X-Rite's spelling of a negative azimuth, and "az0" is in the plane.
    EXPECT_EQ(parseMultiAngleGeometry("r45as25azMinus90")->azimuth_deg, -90.0);
    EXPECT_EQ(multiAngleGeometryName(45, 25, 0.0), "45as25");
}

TEST(Measurements, SpectralMultiAngleJsonWithoutLabIsRead) {
    const auto m = parseMeasurementJson(R"({"format": "paintlab-measurement", "format_version": 1,
        "name": "spectral", "kind": "multiangle", "observer": "2deg", "wavelengths_nm": [400, 700],
        "readings": [{"aspecular_deg": 15, "reflectance": [0.5, 0.5]}]})",
                                        "s.json");
    ASSERT_EQ(m.readings.size(), 1U);
    EXPECT_NEAR(m.readings[0].L, 116.0 * std::cbrt(0.5) - 16.0, 1e-3);  // as above
}

TEST(Measurements, FitsLinkARecipeVersionAndAMeasurement) {
    TempDir dir;
    Database db = Database::open(dir / "f.db");
    initDemoDatabase(db);
    createMeasurement(db, parseMeasurementCsv(kMultiAngleCsv, "panel.csv", description("silver panel")));
    const std::string recipe = listRecipes(db).front().name;
    Fit fit;
    fit.recipe_name = recipe;
    fit.recipe_version = 1;
    fit.measurement_name = "silver panel";
    fit.method = "dE2000 per angle";
    fit.residual_rms = 1.25;
    fit.residuals = {0.5, -1.0, 2.0, 0.25, -0.75, 1.5};
    fit.parameters = {{"layers[0].thickness_um", 18.5}};
    fit.note = "first try";
    const auto id = recordFit(db, fit);
    const auto fits = fitsOfMeasurement(db, "silver panel");
    ASSERT_EQ(fits.size(), 1U);
    EXPECT_EQ(fits[0].id, id);
    EXPECT_EQ(fits[0].recipe_name, recipe);
    EXPECT_EQ(fits[0].residuals, fit.residuals);
    EXPECT_EQ(fits[0].parameters, fit.parameters);
    EXPECT_EQ(fits[0].residual_rms, 1.25);
    EXPECT_FALSE(fits[0].created_at.empty());
    EXPECT_EQ(fitsOfRecipe(db, recipe).size(), 1U);
    // The demo database's made-up panel is listed too (by name): find ours.
    const auto listed = listMeasurements(db);
    const auto silver = std::find_if(listed.begin(), listed.end(),
                                     [](const MeasurementSummary& m) { return m.name == "silver panel"; });
    ASSERT_NE(silver, listed.end());
    EXPECT_EQ(silver->fits, 1U);

    Fit unknown = fit;
    unknown.recipe_version = 99;
    EXPECT_THROW(recordFit(db, unknown), InputError);
    unknown = fit;
    unknown.measurement_name = "nope";
    EXPECT_THROW(recordFit(db, unknown), InputError);
    unknown = fit;
    unknown.residual_rms = -1.0;
    EXPECT_THROW(recordFit(db, unknown), InputError);
    EXPECT_EQ(fitsOfMeasurement(db, "silver panel").size(), 1U);
}

struct BadMeasurement {
    std::string label;
    std::string file_name;
    std::string text;
    std::string expected;
};

class BadMeasurementImport : public ::testing::TestWithParam<BadMeasurement> {};

TEST_P(BadMeasurementImport, IsRefusedNamingFileAndFieldAndStoresNothing) {
    const auto& bad = GetParam();
    TempDir dir;
    Database db = Database::open(dir / "m.db");
    createMeasurement(db, parseMeasurementCsv(kMultiAngleCsv, "panel.csv", description("taken")));
    const auto file = dir / bad.file_name;
    test::writeBytes(file, bad.text);
    ImportOptions options;
    options.kind = ContentKind::Measurement;
    try {
        importFile(db, file, options);
        FAIL() << bad.label;
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), file.string()) << e.what();
        EXPECT_NE(std::string(e.what()).find(bad.expected), std::string::npos)
            << bad.label << ": " << e.what();
    }
    EXPECT_EQ(listMeasurements(db).size(), 1U);
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadMeasurementImport,
    ::testing::Values(
        BadMeasurement{"NaN", "nan.csv", "aspecular_deg,L,a,b\n15,nan,0,0\n", "line 2, column L"},
        BadMeasurement{"missing", "missing.csv", "aspecular_deg,L,a\n15,50,0\n", "missing column 'b'"},
        BadMeasurement{"geometry", "geometry.csv", "geometry,L,a,b\n45x15,50,0,0\n",
                       "line 2, column geometry"},
        BadMeasurement{"horizon", "horizon.csv", "aspecular_deg,L,a,b\n140,50,0,0\n",
                       "readings[0].aspecular_deg"},
        BadMeasurement{"azimuth NaN", "aznan.csv", "aspecular_deg,azimuth_deg,L,a,b\n25,nan,50,0,0\n",
                       "line 2, column azimuth_deg"},
        BadMeasurement{"azimuth range", "azrange.csv", "geometry,L,a,b\n45as25az200,50,0,0\n",
                       "readings[0].azimuth_deg"},
        // One direction, one name: out of the plane the aspecular is positive and the
        // azimuth short of a half turn (multiangle.h, outOfPlaneFormProblem).
        BadMeasurement{"negative aspecular out of plane", "azneg.csv", "geometry,L,a,b\n45as-25az90,50,0,0\n",
                       "readings[0].aspecular_deg"},
        BadMeasurement{"angle column against the name", "azboth.csv",
                       "geometry,azimuth_deg,L,a,b\n45as25,,50,0,0\n45as25,90,50,0,0\n",
                       "line 3, column azimuth_deg"},
        BadMeasurement{"half turn", "azhalf.csv", "aspecular_deg,azimuth_deg,L,a,b\n25,180,50,0,0\n",
                       "readings[0].aspecular_deg"},
        BadMeasurement{"azimuth horizon", "azhorizon.csv",
                       "geometry,L,a,b\n45as25,50,0,0\n15as100az30,50,0,0\n", "readings[1].aspecular_deg"},
        BadMeasurement{
            "json azimuth", "az.json",
            R"({"format": "paintlab-measurement", "format_version": 1, "name": "x", "kind": "multiangle",
                           "readings": [{"aspecular_deg": 15, "azimuth_deg": "ninety", "L": 50, "a": 0, "b": 0}]})",
            "readings[0].azimuth_deg"},
        BadMeasurement{"theta", "theta.csv",
                       "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,R,G,B\n95,0,0,0,1,1,1\n",
                       "samples[0].theta_i_deg"},
        BadMeasurement{"negative brdf", "neg.csv",
                       "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,R,G,B\n45,0,0,0,1,-1,1\n",
                       "samples[0].values[1]"},
        BadMeasurement{"truncated", "cut.csv",
                       "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,R,G,B\n45,0,0,0,1,1,1\n45,0", "line 3"},
        BadMeasurement{"taken name", "taken.csv", "aspecular_deg,L,a,b\n15,50,0,0\n", "already exists"},
        BadMeasurement{
            "json unknown field", "u.json",
            R"({"format": "paintlab-measurement", "format_version": 1, "name": "x", "kind": "multiangle",
                           "readings": [{"aspecular_deg": 15, "L": 50, "a": 0, "b": 0, "c": 1}]})",
            "readings[0].c"},
        BadMeasurement{"negative reflectance", "negr.csv", "aspecular_deg,400,700\n15,0.5,-0.1\n",
                       "readings[0].reflectance[1]"},
        BadMeasurement{
            "reflectance without wavelengths", "nowl.json",
            R"({"format": "paintlab-measurement", "format_version": 1, "name": "x", "kind": "multiangle",
                           "readings": [{"aspecular_deg": 15, "L": 50, "a": 0, "b": 0, "reflectance": [1]}]})",
            "readings[0].reflectance"},
        BadMeasurement{
            "reflectance size", "size.json",
            R"({"format": "paintlab-measurement", "format_version": 1, "name": "x", "kind": "multiangle",
                "wavelengths_nm": [400, 500, 600],
                "readings": [{"aspecular_deg": 15, "reflectance": [1, 1]}]})",
            "readings[0].reflectance"}),
    [](const auto& test_info) {
        std::string name = test_info.param.label;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

}  // namespace
}  // namespace paintlab::db
