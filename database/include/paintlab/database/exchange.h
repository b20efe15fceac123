#pragma once
// Importing files into the database and exporting from it, whole or not at
// all. An import runs in one write transaction: the first bad record (or an
// ingredient, spectrum or measurement name already taken) throws InputError
// naming the file, the record and the field, and nothing of the file is
// stored. Formats per kind of content:
//
//   ingredients  JSON (ingredient_json.h), CSV (ingredient_csv.h)
//   spectra      JSON, CSV, CGATS/IT8 (spectra_files.h)
//   measurement  JSON, CSV (measurement_files.h)
//   recipe       JSON recipe files (recipe_json.h; saved as a new version)

#include "paintlab/database/database.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/spectra_files.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db {

enum class FileFormat { Csv, Json, Cgats, Html };
enum class ContentKind { Ingredients, Spectra, Measurement, Recipe };

std::string_view fileFormatName(FileFormat format);  // "csv", "json", "cgats", "html"
// Throws InputError("<argument>", "--format", ...) for an unknown name.
FileFormat parseFileFormat(std::string_view name);
// From the extension: .csv, .json, .cgats / .it8 / .txt / .ti3, .html / .htm.
// Throws InputError naming the file if the extension says nothing.
FileFormat formatOfFile(const std::filesystem::path& file);
std::string_view contentKindName(ContentKind kind);   // "ingredients", "spectra", "measurement", "recipe"
ContentKind parseContentKind(std::string_view name);  // InputError("<argument>", "--kind", ...)

struct ImportOptions {
    std::optional<FileFormat> format;  // default: from the extension
    std::optional<ContentKind>
        kind;            // default: from the content (JSON "format", CSV header; CGATS = spectra)
    CgatsOptions cgats;  // CGATS spectra: quantity, unit, source
    // Measurement CSV: the description (name defaults to the file stem).
    Measurement measurement;
    // Recipes: who saves the version and why.
    std::string author;
    std::string note;
};

struct ImportResult {
    ContentKind kind = ContentKind::Ingredients;
    std::vector<std::string> names;  // what was added
    int recipe_version = 0;          // recipes: the version saved (or the identical one)
    bool recipe_created = false;
    std::vector<std::string>
        unlinked;  // recipes: ingredients not in the database (saved with the recipe's data)
};

// Reads the file (at most 64 MiB) and stores its content in one transaction.
// Throws InputError naming the file (missing, empty, too large, unknown
// format, bad record), DatabaseError naming the database when SQLite fails.
ImportResult importFile(Database& db, const std::filesystem::path& file, const ImportOptions& options = {});

// Stores ingredients read elsewhere (a plugin's importer) in one transaction,
// as importFile does; records are named "ingredients[i] kind 'name'" when
// `indexed`, else "kind 'name'". InputError naming source and the record
// (an empty list, a kind and name twice, a taken name); nothing stored then.
ImportResult storeIngredients(Database& db, const std::vector<Ingredient>& ingredients,
                              const std::string& source, bool indexed = true);
// Stores spectra read elsewhere (a plugin's importer) in one transaction, as
// importFile does: InputError naming source and the spectrum (an empty list,
// a taken name), and nothing stored.
ImportResult storeSpectra(Database& db, const std::vector<NamedSpectrum>& spectra, const std::string& source);

// A measurement file (JSON or CSV, as importFile reads it) without storing
// it: for a fit to a file. Throws InputError naming the file.
Measurement readMeasurementFile(const std::filesystem::path& file, const ImportOptions& options = {});

// Ingredients by exact name (any kind; empty names = every ingredient).
// Throws InputError naming the database for a name it does not hold.
std::vector<Ingredient> ingredientsByName(Database& db, const std::vector<std::string>& names);
// Named spectra by name (empty names = all); InputError as above.
std::vector<NamedSpectrum> spectraByName(Database& db, const std::vector<std::string>& names);
// One measurement by name; InputError naming the database if there is none.
Measurement measurementByName(Database& db, std::string_view name);

// ingredientsByName as JSON or CSV text.
std::string exportIngredients(Database& db, const std::vector<std::string>& names, FileFormat format);
// spectraByName as JSON, CSV or CGATS.
std::string exportSpectra(Database& db, const std::vector<std::string>& names, FileFormat format);
// One measurement, as JSON or CSV.
std::string exportMeasurement(Database& db, std::string_view name, FileFormat format);

}  // namespace paintlab::db
