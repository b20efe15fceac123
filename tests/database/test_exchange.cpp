// Import and export of ingredients and spectra: JSON, CSV and CGATS round
// trips (export then import gives equal rows and spectra), a hostile name
// through every format, and every kind of bad file refused with a message
// naming the file, the record and the field while the database stays as it
// was (all or nothing).

#include "db_test_support.h"

#include "paintlab/database/demo.h"
#include "paintlab/database/exchange.h"
#include "paintlab/database/ingredient_csv.h"
#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/spectra_files.h"

#include <gtest/gtest.h>

#include <cctype>
#include <string>

namespace paintlab::db {
namespace {

using test::TempDir;

const std::string kHostile =
    "Robert'); DROP TABLE ingredient;-- \"quoted\", a;b; SELECT * FROM spectrum; 50% é";

// Every row of every table, as text: equal before and after a refused import.
std::string contents(const std::filesystem::path& file) {
    std::string out;
    for (const char* table :
         {"ingredient", "spectrum", "binder", "pigment", "mirror_flake", "interference_flake", "substrate",
          "tag", "ingredient_tag", "technological_limit", "recipe", "recipe_version", "measurement", "fit"})
        out += std::string(table) + ":" +
               test::rawQuery(file, std::string("SELECT count(*) || '/' || coalesce(max(rowid), 0) FROM ") +
                                        table) +
               " ";
    return out;
}

std::vector<Ingredient> allIngredients(Database& db) {
    std::vector<Ingredient> out;
    for (const auto& summary : searchIngredients(db)) {
        out.push_back(readIngredient(db, summary.id));
        out.back().id = 0;
    }
    return out;
}

std::filesystem::path write(const TempDir& dir, const std::string& name, const std::string& text) {
    auto path = dir / name;
    test::writeBytes(path, text);
    return path;
}

TEST(IngredientExchange, DemoLibraryRoundTripsThroughJsonAndCsv) {
    TempDir dir;
    Database demo = Database::open(dir / "demo.db");
    initDemoDatabase(demo);
    const auto original = allIngredients(demo);
    ASSERT_EQ(original.size(), 16U);
    for (const auto format : {FileFormat::Json, FileFormat::Csv}) {
        const std::string name = std::string("lib.") + std::string(fileFormatName(format));
        const std::string text = exportIngredients(demo, {}, format);
        const auto file = write(dir, name, text);
        Database copy = Database::open(dir / (name + ".db"));
        const auto result = importFile(copy, file);
        EXPECT_EQ(result.kind, ContentKind::Ingredients);
        EXPECT_EQ(result.names.size(), 16U);
        EXPECT_TRUE(allIngredients(copy) == original) << name << " did not round-trip";
        EXPECT_EQ(exportIngredients(copy, {}, format), text) << name << ": a second export differs";
    }
}

TEST(IngredientExchange, HostileNameAndTextRoundTripThroughEveryFormat) {
    TempDir dir;
    Ingredient ing;
    ing.name = kHostile;
    ing.description = "line one\nline two, with \"quotes\"";
    ing.source = kHostile;
    ing.density_g_cm3 = 1.05;
    ing.tags = {"a;b", "DROP TABLE tag;"};
    ing.solids_mass_fraction = 0.45;
    ing.volatile_density_g_cm3 = 0.87;
    ing.data = Binder{kHostile, Spectrum({380, 780}, {1.5, 1.48}), Spectrum(0.001)};
    ing.spectrum_info["refractive_index"] = {"1", kHostile, "2024-05-01"};
    Database db = Database::open(dir / "hostile.db");
    createIngredient(db, ing);
    const auto original = allIngredients(db);
    for (const auto format : {FileFormat::Json, FileFormat::Csv}) {
        const std::string name = std::string("h.") + std::string(fileFormatName(format));
        const auto file = write(dir, name, exportIngredients(db, {kHostile}, format));
        Database copy = Database::open(dir / (name + ".db"));
        importFile(copy, file);
        EXPECT_TRUE(allIngredients(copy) == original) << name;
        EXPECT_EQ(test::rawQuery(dir / (name + ".db"), "SELECT count(*) FROM ingredient"), "1");
    }
}

// Kinds the demo library lacks: substrates without spectra (black,
// transparent) or with two (metal), a mirror flake given by n and k.
TEST(IngredientExchange, EveryKindRoundTripsThroughCsvAndJson) {
    std::vector<Ingredient> ingredients;
    for (const Substrate& s : {Substrate{BlackSubstrate{}}, Substrate{TransparentSubstrate{1.52}},
                               Substrate{MetalSubstrate{Spectrum({400, 700}, {1.2, 0.3}), Spectrum(7.0)}}}) {
        Ingredient substrate;
        substrate.name = "substrate " + std::string(substrateKind(s));
        substrate.data = s;
        ingredients.push_back(substrate);
    }
    Ingredient mirror;
    mirror.name = "Al, n and k";
    mirror.diameter_sd_um = 6.0;
    mirror.limits = {0.2, 12.0, 25.0};
    MirrorFlake m;
    m.name = mirror.name;
    m.diameter_um = 18;
    m.thickness_um = 0.3;
    m.orientation_spread_deg = 12;
    m.metal_n = Spectrum({400, 600}, {0.49, 1.2});
    m.metal_k = Spectrum({400, 600}, {4.8, 7.2});
    mirror.data = m;
    ingredients.push_back(mirror);
    Ingredient pearl;
    pearl.name = "pearl";
    InterferenceFlake p;
    p.name = "pearl";
    p.diameter_um = 18;
    p.mica_thickness_nm = 350;
    p.tio2_thickness_nm = 120;
    pearl.data = p;
    ingredients.push_back(pearl);
    // Reading fills in the defaults of the provenance: compare text after one pass.
    const auto once = parseIngredientsCsv(ingredientsToCsv(ingredients), "a.csv");
    ASSERT_EQ(once.size(), ingredients.size());
    EXPECT_TRUE(parseIngredientsCsv(ingredientsToCsv(once), "b.csv") == once);
    EXPECT_TRUE(parseIngredientsJson(ingredientsToJson(once), "c.json") == once);
    for (std::size_t i = 0; i < once.size(); ++i) {
        EXPECT_TRUE(once[i].data == ingredients[i].data) << ingredients[i].name;
        EXPECT_EQ(once[i].limits, ingredients[i].limits) << ingredients[i].name;
    }
}

TEST(IngredientExchange, UnitsAreConvertedToTheDeclaredOnes) {
    const std::string csv =
        "kind,name,hg_g,particle_diameter_um,spectrum,unit,spectrum_source,wavelength_nm,value\n"
        "pigment,p,0.5,0.2,sigma_a_per_um,1/cm,lab,400,1000\n"
        "pigment,p,0.5,0.2,sigma_a_per_um,1/cm,lab,700,2000\n"
        "pigment,p,0.5,0.2,sigma_s_per_um,1/mm,lab,,30\n";
    const auto ingredients = parseIngredientsCsv(csv, "u.csv");
    ASSERT_EQ(ingredients.size(), 1U);
    const auto& p = std::get<Pigment>(ingredients[0].data);
    // 1000 /cm = 0.1 /µm; 30 /mm = 0.03 /µm.
    EXPECT_DOUBLE_EQ(p.sigma_a_per_um.values()[0], 0.1);
    EXPECT_DOUBLE_EQ(p.sigma_a_per_um.values()[1], 0.2);
    EXPECT_DOUBLE_EQ(p.sigma_s_per_um.values()[0], 0.03);
    EXPECT_EQ(ingredients[0].spectrum_info.at("sigma_a_per_um").unit, "1/µm");
}

struct BadFile {
    std::string label;
    std::string file_name;
    std::string text;
    std::vector<std::string> expected;  // fragments of the message (the file name is checked too)
};

// A good pigment in CSV, for the bad files to spoil.
const std::string kCsvHeader =
    "kind,name,hg_g,particle_diameter_um,spectrum,unit,spectrum_source,wavelength_nm,value\n";
std::string goodPigmentCsv(const std::string& name) {
    return "pigment," + name + ",0.5,0.2,sigma_a_per_um,1/µm,lab,400,0.1\n" + "pigment," + name +
           ",0.5,0.2,sigma_a_per_um,1/µm,lab,700,0.2\n" + "pigment," + name +
           ",0.5,0.2,sigma_s_per_um,1/µm,lab,,20\n";
}

std::string goodIngredientsJson(const std::string& extra_spectrum_fields, const std::string& name = "j") {
    return R"({"format": "paintlab-ingredients", "format_version": 1, "ingredients": [
      {"kind": "pigment", "name": "good", "hg_g": 0.5, "particle_diameter_um": 0.2,
       "spectra": {"sigma_a_per_um": {"unit": "1/µm", "source": "s", "value": 0.1},
                   "sigma_s_per_um": {"unit": "1/µm", "source": "s", "value": 20}}},
      {"kind": "pigment", "name": ")" +
           name + R"(", "hg_g": 0.5, "particle_diameter_um": 0.2,
       "spectra": {"sigma_a_per_um": {"source": "s", )" +
           extra_spectrum_fields + R"(},
                   "sigma_s_per_um": {"unit": "1/µm", "source": "s", "value": 20}}}]})";
}

std::vector<BadFile> badFiles() {
    return {
        {"csv malformed row",
         "bad.csv",
         kCsvHeader + goodPigmentCsv("a") + "pigment,\"b,0.5,0.2,sigma_a_per_um,1/µm,lab,400,0.1\n",
         {"line 5", "never closed"}},
        {"csv missing column",
         "bad.csv",
         "kind,name,spectrum,wavelength_nm\npigment,a,sigma_a_per_um,400\n",
         {"line 1", "missing column 'value'"}},
        {"csv NaN",
         "bad.csv",
         kCsvHeader + goodPigmentCsv("a") + "pigment,b,0.5,0.2,sigma_a_per_um,1/µm,lab,400,nan\n",
         {"line 5, column value", "'nan' is not a finite number"}},
        {"csv negative wavelength",
         "bad.csv",
         kCsvHeader + goodPigmentCsv("a") + "pigment,b,0.5,0.2,sigma_a_per_um,1/µm,lab,-400,0.1\n",
         {"line 5, column wavelength_nm", "must be positive"}},
        {"csv non-monotonic wavelengths",
         "bad.csv",
         kCsvHeader + "pigment,b,0.5,0.2,sigma_a_per_um,1/µm,lab,500,0.1\npigment,b,0.5,0.2,sigma_a_per_um,1/"
                      "µm,lab,450,0.2\n",
         {"line 3, column wavelength_nm", "does not increase"}},
        {"csv unknown unit",
         "bad.csv",
         kCsvHeader + goodPigmentCsv("a") +
             "pigment,b,0.5,0.2,sigma_a_per_um,furlongs,lab,400,0.1\n"
             "pigment,b,0.5,0.2,sigma_s_per_um,1/µm,lab,,20\n",
         {"pigment 'b'", "sigma_a_per_um.unit", "unknown unit 'furlongs'"}},
        {"csv unit of another dimension",
         "bad.csv",
         kCsvHeader + "pigment,b,0.5,0.2,sigma_a_per_um,%,lab,400,0.1\npigment,b,0.5,0.2,sigma_s_per_um,1/"
                      "µm,lab,,20\n",
         {"sigma_a_per_um.unit", "does not fit"}},
        {"csv duplicate of a stored name",
         "bad.csv",
         kCsvHeader + goodPigmentCsv("a") + goodPigmentCsv("taken"),
         {"pigment 'taken'", "already exists"}},
        {"csv truncated",
         "bad.csv",
         kCsvHeader + goodPigmentCsv("a") + "pigment,b,0.5,0.2,sigma_a",
         {"line 5", "truncated"}},
        {"csv disagreeing fields",
         "bad.csv",
         kCsvHeader + "pigment,b,0.5,0.2,sigma_a_per_um,1/µm,lab,400,0.1\npigment,b,0.7,0.2,sigma_s_per_um,1/"
                      "µm,lab,,20\n",
         {"line 3, column hg_g", "differs"}},
        {"csv unknown column",
         "bad.csv",
         "kind,name,colour,spectrum,wavelength_nm,value\n",
         {"unknown column 'colour'"}},
        {"json truncated",
         "bad.json",
         goodIngredientsJson(R"("unit": "1/µm", "value": 0.1)").substr(0, 200),
         {"the file ends early (truncated JSON)"}},
        {"json negative wavelength",
         "bad.json",
         goodIngredientsJson(R"("unit": "1/µm", "wavelengths_nm": [-400, 700], "values": [0.1, 0.2])"),
         {"ingredients[1].spectra.sigma_a_per_um.wavelengths_nm[0]", "must be positive"}},
        {"json non-monotonic wavelengths",
         "bad.json",
         goodIngredientsJson(R"("unit": "1/µm", "wavelengths_nm": [700, 400], "values": [0.1, 0.2])"),
         {"ingredients[1].spectra.sigma_a_per_um"}},
        {"json unknown unit",
         "bad.json",
         goodIngredientsJson(R"("unit": "parsec", "value": 0.1)"),
         {"ingredients[1].spectra.sigma_a_per_um.unit", "unknown unit 'parsec'"}},
        {"json missing field",
         "bad.json",
         goodIngredientsJson(R"("value": 0.1)"),
         {"ingredients[1].spectra.sigma_a_per_um.unit", "missing"}},
        {"json duplicate name in the file",
         "bad.json",
         goodIngredientsJson(R"("unit": "1/µm", "value": 0.1)", "good"),
         {"ingredients[1] pigment 'good'", "twice"}},
        {"json duplicate of a stored name",
         "bad.json",
         goodIngredientsJson(R"("unit": "1/µm", "value": 0.1)", "taken"),
         {"ingredients[1] pigment 'taken'", "already exists"}},
        {"json out of range",
         "bad.json",
         goodIngredientsJson(R"("unit": "1/µm", "value": -5)"),
         {"ingredients[1] pigment 'j'", "sigma_a_per_um", "is below the minimum 0"}},
        {"spectra csv duplicate name",
         "bad.csv",
         "name,quantity,unit,wavelength_nm,value\ns,reflectance,1,400,0.1\nt,reflectance,1,400,0.1\n"
         "s,reflectance,%,500,10\n",
         {"line 4, column unit", "differs"}},
        {"spectra json NaN-like string",
         "bad.json",
         R"({"format": "paintlab-spectra", "format_version": 1, "spectra": [{"name": "s", "quantity": "reflectance",
            "unit": "1", "wavelengths_nm": [400, 500], "values": [0.1, "NaN"]}]})",
         {"spectra[0].values[1]", "expected a number"}},
        {"spectra json duplicate of a stored name",
         "bad.json",
         R"({"format": "paintlab-spectra", "format_version": 1, "spectra": [{"name": "fresh", "quantity": "reflectance",
            "unit": "1", "wavelengths_nm": [400], "values": [0.1]}, {"name": "stored spectrum", "quantity": "reflectance",
            "unit": "1", "wavelengths_nm": [400], "values": [0.1]}]})",
         {"spectrum 'stored spectrum'", "already exists"}},
        {"cgats not a number",
         "bad.cgats",
         "CGATS.17\nNUMBER_OF_FIELDS 4\nBEGIN_DATA_FORMAT\nSAMPLE_ID SAMPLE_NAME SPECTRAL_NM400 "
         "SPECTRAL_NM500\n"
         "END_DATA_FORMAT\nNUMBER_OF_SETS 2\nBEGIN_DATA\n1 \"a\" 0.1 0.2\n2 \"b\" 0.1 nan\nEND_DATA\n",
         {"data set 2 'b'.SPECTRAL_NM500", "not a finite number"}},
        {"cgats truncated",
         "bad.cgats",
         "CGATS.17\nNUMBER_OF_FIELDS 4\nBEGIN_DATA_FORMAT\nSAMPLE_ID SAMPLE_NAME SPECTRAL_NM400 "
         "SPECTRAL_NM500\n"
         "END_DATA_FORMAT\nNUMBER_OF_SETS 3\nBEGIN_DATA\n1 \"a\" 0.1 0.2\n2 \"b\" 0.1",
         {"bad.cgats"}},
        {"cgats percent without a unit",
         "bad.cgats",
         "CGATS.17\nNUMBER_OF_FIELDS 3\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPECTRAL_NM400 SPECTRAL_NM500\n"
         "END_DATA_FORMAT\nNUMBER_OF_SETS 1\nBEGIN_DATA\n1 10.5 45.2\nEND_DATA\n",
         {"SPECTRAL_NM500", "percent"}},
        {"cgats without spectra",
         "bad.cgats",
         "CGATS.17\nNUMBER_OF_FIELDS 4\nBEGIN_DATA_FORMAT\nSAMPLE_ID LAB_L LAB_A LAB_B\nEND_DATA_FORMAT\n"
         "NUMBER_OF_SETS 1\nBEGIN_DATA\n1 50 0 0\nEND_DATA\n",
         {"DATA_FORMAT", "no spectral column"}},
        {"empty file", "bad.csv", "", {"empty"}},
    };
}

class BadImport : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadImport, IsRefusedNamingFileAndFieldAndChangesNothing) {
    const BadFile& bad = GetParam();
    TempDir dir;
    const auto db_file = dir / "lab.db";
    {
        Database db = Database::open(db_file);
        initDemoDatabase(db);
        createIngredient(db, parseIngredientsCsv(kCsvHeader + goodPigmentCsv("taken"), "seed.csv").front());
        addNamedSpectrum(db, "stored spectrum", "reflectance", Spectrum(0.5), {"1", "seed", ""});
    }
    const std::string before = contents(db_file);
    const auto file = write(dir, bad.file_name, bad.text);
    Database db = Database::open(db_file);
    try {
        importFile(db, file);
        FAIL() << bad.label << ": imported";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(e.source(), file.string()) << bad.label << ": " << message;
        for (const auto& fragment : bad.expected)
            EXPECT_NE(message.find(fragment), std::string::npos)
                << bad.label << ": '" << fragment << "' not in: " << message;
    }
    EXPECT_EQ(contents(db_file), before) << bad.label << ": the database changed";
    EXPECT_TRUE(db.integrityCheck().empty());
}

// GoogleTest names may hold letters and digits only. (A plain loop, not
// std::regex: GCC 12 warns -Wmaybe-uninitialized inside <regex> in the
// sanitizer build, where warnings are errors.)
INSTANTIATE_TEST_SUITE_P(Files, BadImport, ::testing::ValuesIn(badFiles()), [](const auto& test_info) {
    std::string name = test_info.param.label;
    for (char& c : name)
        if (std::isalnum(static_cast<unsigned char>(c)) == 0) c = '_';
    return name;
});

TEST(IngredientExchange, ABadLastIngredientLeavesNoneOfTheFile) {
    TempDir dir;
    Database db = Database::open(dir / "lab.db");
    const auto file = write(dir, "three.csv",
                            kCsvHeader + goodPigmentCsv("first") + goodPigmentCsv("second") +
                                "pigment,third,0.5,7,sigma_a_per_um,1/µm,lab,400,-1\n"
                                "pigment,third,0.5,7,sigma_s_per_um,1/µm,lab,,20\n");
    EXPECT_THROW(importFile(db, file), InputError);
    EXPECT_TRUE(searchIngredients(db).empty());
    EXPECT_EQ(test::rawQuery(dir / "lab.db", "SELECT count(*) FROM spectrum"), "0");
}

// A spectrophotometer-style CGATS export (keywords, SAMPLE_ID/SAMPLE_NAME,
// SPECTRAL_NM columns, reflectance in percent) through liblcms2's parser.
const std::string kInstrumentCgats = R"(CGATS.17
ORIGINATOR "i1Profiler"
INSTRUMENTATION "i1Pro 2"
CREATED "2024-03-05"
# the white and the red panel
KEYWORD "MEASUREMENT_CONDITION"
MEASUREMENT_CONDITION "M1"
NUMBER_OF_FIELDS 6
BEGIN_DATA_FORMAT
SAMPLE_ID SAMPLE_NAME SPECTRAL_NM380 SPECTRAL_NM390 SPECTRAL_NM400 SPECTRAL_NM410
END_DATA_FORMAT
NUMBER_OF_SETS 2
BEGIN_DATA
1 "white panel" 85.1 86.0 87.25 88.0
2 "red; panel" 5.5 5.25 5.0 4.75
END_DATA
)";

TEST(SpectraExchange, InstrumentCgatsIsReadWithItsKeywords) {
    CgatsOptions options;
    options.unit = "%";
    const auto spectra = parseSpectraCgats(kInstrumentCgats, "panels.cgats", options);
    ASSERT_EQ(spectra.size(), 2U);
    EXPECT_EQ(spectra[0].name, "white panel");
    EXPECT_EQ(spectra[1].name, "red; panel");
    EXPECT_EQ(spectra[0].quantity, "reflectance");
    EXPECT_EQ(spectra[0].info.unit, "1");
    EXPECT_EQ(spectra[0].info.date, "2024-03-05");
    EXPECT_NE(spectra[0].info.source.find("i1Pro 2"), std::string::npos) << spectra[0].info.source;
    EXPECT_EQ(spectra[0].spectrum.wavelengthsNm(), (std::vector<double>{380, 390, 400, 410}));
    EXPECT_DOUBLE_EQ(spectra[0].spectrum.values()[2], 0.8725);  // 87.25 % as a fraction
    EXPECT_DOUBLE_EQ(spectra[1].spectrum.values()[3], 0.0475);
}

TEST(SpectraExchange, NamedSpectraRoundTripThroughEveryFormat) {
    TempDir dir;
    Database db = Database::open(dir / "s.db");
    CgatsOptions options;
    options.unit = "%";
    options.source = "lab; i1Pro 2, 'M1' conditions";
    for (const auto& s : parseSpectraCgats(kInstrumentCgats, "panels.cgats", options))
        addNamedSpectrum(db, s.name, s.quantity, s.spectrum, s.info);
    addNamedSpectrum(db, kHostile, "k_over_s", Spectrum({400, 410.5}, {1.25, 0.1}), {"1", kHostile, "2020"});
    const std::string all_json = exportSpectra(db, {}, FileFormat::Json);
    for (const auto format : {FileFormat::Json, FileFormat::Csv, FileFormat::Cgats}) {
        // CGATS holds one grid and one quantity: the two panels only.
        const std::vector<std::string> names = format == FileFormat::Cgats
                                                   ? std::vector<std::string>{"red; panel", "white panel"}
                                                   : std::vector<std::string>{};
        const std::string name = std::string("s.") + std::string(fileFormatName(format));
        const auto file = write(dir, name, exportSpectra(db, names, format));
        Database copy = Database::open(dir / (name + ".db"));
        importFile(copy, file);
        for (const auto& original : namedSpectra(db)) {
            if (format == FileFormat::Cgats && original.name == kHostile) continue;
            const auto read = findNamedSpectrum(copy, original.name);
            ASSERT_TRUE(read.has_value()) << name << ": " << original.name;
            EXPECT_EQ(read->spectrum, original.spectrum) << name << ": " << original.name;
            EXPECT_EQ(read->quantity, original.quantity) << name;
            EXPECT_EQ(read->info, original.info) << name;
        }
        if (format != FileFormat::Cgats) {
            EXPECT_EQ(exportSpectra(copy, {}, FileFormat::Json), all_json) << name;
        }
    }
    // The hostile name cannot be a CGATS string: refused, not mangled.
    EXPECT_THROW(exportSpectra(db, {kHostile}, FileFormat::Cgats), InputError);
}

}  // namespace
}  // namespace paintlab::db
