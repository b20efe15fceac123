// Import and export (exchange.h): parse the whole file first, then store
// everything inside one write transaction, so a bad record or a taken name
// leaves the database as it was.

#include "paintlab/database/exchange.h"

#include "paintlab/database/ingredient_csv.h"
#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/measurement_files.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"

#include "json_reader.h"
#include "sqlite.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>

namespace paintlab::db {

namespace {

// Far above any ingredient library or instrument export; refused before reading.
constexpr std::size_t kMaxImportBytes = std::size_t{64} << 20;

std::string lowerAscii(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// What a file holds, when --kind does not say: JSON by its "format" member,
// CSV by its header, CGATS is always spectra.
ContentKind detectKind(const std::string& text, FileFormat format, const std::string& source) {
    if (format == FileFormat::Cgats) return ContentKind::Spectra;
    if (format == FileFormat::Json) {
        const nlohmann::json document = jsonio::parseUntrustedJson(text, source);
        if (document.is_object() && document.contains("format") && document["format"].is_string()) {
            const std::string f = document["format"].get<std::string>();
            if (f == "paintlab-ingredients") return ContentKind::Ingredients;
            if (f == "paintlab-spectra") return ContentKind::Spectra;
            if (f == "paintlab-measurement") return ContentKind::Measurement;
        }
        if (document.is_object() && document.contains("schema_version") && document.contains("layers"))
            return ContentKind::Recipe;
        throw InputError(
            source, "format",
            "not a PaintLab file: expected \"format\": \"paintlab-ingredients\", \"paintlab-spectra\" "
            "or \"paintlab-measurement\", or a recipe (give --kind to say which)");
    }
    // The header's column names, unquoted.
    std::vector<std::string> columns(1);
    for (const char c : std::string_view(text).substr(0, text.find('\n'))) {
        if (c == ',')
            columns.emplace_back();
        else if (c != '"' && c != '\r')
            columns.back().push_back(c);
    }
    const auto has = [&](std::string_view column) {
        return std::find(columns.begin(), columns.end(), column) != columns.end();
    };
    if (has("kind") && has("spectrum")) return ContentKind::Ingredients;
    if (has("quantity") && has("wavelength_nm")) return ContentKind::Spectra;
    if (has("theta_i_deg") || has("aspecular_deg") || has("geometry")) return ContentKind::Measurement;
    throw InputError(
        source, "line 1",
        "cannot tell what this CSV holds from its header (ingredients: kind, name, spectrum, ...; "
        "spectra: name, quantity, ...; measurement: aspecular_deg or theta_i_deg, ...); give --kind");
}

// Re-raises an error of a repository function (which names the database) as
// one naming the import file and its record; the database is in the message too.
[[noreturn]] void rethrowForRecord(const InputError& e, const std::string& source,
                                   const std::string& record) {
    std::string detail = e.detail();
    if (!e.source().empty() && e.source() != source) detail += " (database " + e.source() + ")";
    throw InputError(source, record + (e.field().empty() ? "" : " (" + e.field() + ")"), detail);
}

ImportResult importIngredients(Database& db, const std::string& text, FileFormat format,
                               const std::string& source) {
    if (format != FileFormat::Json && format != FileFormat::Csv)
        throw InputError(source, "",
                         "ingredients are imported from JSON or CSV, not " +
                             std::string(fileFormatName(format)));
    const auto ingredients =
        format == FileFormat::Json ? parseIngredientsJson(text, source) : parseIngredientsCsv(text, source);
    return storeIngredients(db, ingredients, source, format == FileFormat::Json);
}

ImportResult importSpectra(Database& db, const std::string& text, FileFormat format,
                           const std::string& source, const ImportOptions& options) {
    std::vector<NamedSpectrum> spectra;
    if (format == FileFormat::Json)
        spectra = parseSpectraJson(text, source);
    else if (format == FileFormat::Csv)
        spectra = parseSpectraCsv(text, source);
    else if (format == FileFormat::Cgats)
        spectra = parseSpectraCgats(text, source, options.cgats);
    else
        throw InputError(source, "",
                         "spectra are imported from JSON, CSV or CGATS, not " +
                             std::string(fileFormatName(format)));
    return storeSpectra(db, spectra, source);
}

Measurement parseMeasurementFile(const std::filesystem::path& file, const std::string& text,
                                 FileFormat format, const ImportOptions& options) {
    const std::string source = file.string();
    Measurement m;
    if (format == FileFormat::Json) {
        m = parseMeasurementJson(text, source);
    } else if (format == FileFormat::Csv) {
        Measurement description = options.measurement;
        if (description.name.empty()) description.name = file.stem().string();
        if (description.source.empty()) description.source = file.filename().string();
        m = parseMeasurementCsv(text, source, description);
    } else {
        throw InputError(source, "",
                         "measurements are imported from JSON or CSV, not " +
                             std::string(fileFormatName(format)));
    }
    return m;
}

ImportResult importMeasurement(Database& db, const std::filesystem::path& file, const std::string& text,
                               FileFormat format, const ImportOptions& options) {
    const std::string source = file.string();
    const Measurement m = parseMeasurementFile(file, text, format, options);
    try {
        createMeasurement(db, m);
    } catch (const InputError& e) {
        rethrowForRecord(e, source, "measurement '" + m.name + "'");
    }
    ImportResult result;
    result.kind = ContentKind::Measurement;
    result.names.push_back(m.name);
    return result;
}

ImportResult importRecipe(Database& db, const std::filesystem::path& file, FileFormat format,
                          const ImportOptions& options) {
    if (format != FileFormat::Json)
        throw InputError(file.string(), "", "recipes are imported from JSON recipe files");
    const Recipe recipe = loadRecipeFile(file);
    SaveOptions save;
    save.author = options.author.empty() ? "unknown" : options.author;
    save.note = options.note;
    save.source = file.string();
    const auto saved = saveRecipeVersion(db, recipe, save);
    ImportResult result;
    result.kind = ContentKind::Recipe;
    result.names.push_back(saved.recipe_name);
    result.recipe_version = saved.version;
    result.recipe_created = saved.created;
    result.unlinked = saved.unlinked;
    return result;
}

}  // namespace

std::string_view fileFormatName(FileFormat format) {
    switch (format) {
    case FileFormat::Csv:
        return "csv";
    case FileFormat::Json:
        return "json";
    case FileFormat::Cgats:
        return "cgats";
    case FileFormat::Html:
        return "html";
    }
    return "json";
}

FileFormat parseFileFormat(std::string_view name) {
    const std::string lower = lowerAscii(name);
    if (lower == "csv") return FileFormat::Csv;
    if (lower == "json") return FileFormat::Json;
    if (lower == "cgats" || lower == "it8") return FileFormat::Cgats;
    if (lower == "html") return FileFormat::Html;
    throw InputError("<argument>", "--format",
                     "unknown format '" + std::string(name) + "' (csv, json, cgats or html)");
}

FileFormat formatOfFile(const std::filesystem::path& file) {
    const std::string extension = lowerAscii(file.extension().string());
    if (extension == ".csv") return FileFormat::Csv;
    if (extension == ".json") return FileFormat::Json;
    if (extension == ".cgats" || extension == ".it8" || extension == ".txt" || extension == ".ti3")
        return FileFormat::Cgats;
    if (extension == ".html" || extension == ".htm") return FileFormat::Html;
    throw InputError(file.string(), "",
                     "cannot tell the format from the extension '" + extension +
                         "' (.csv, .json, .cgats/.it8/.txt, .html); give --format");
}

std::string_view contentKindName(ContentKind kind) {
    switch (kind) {
    case ContentKind::Ingredients:
        return "ingredients";
    case ContentKind::Spectra:
        return "spectra";
    case ContentKind::Measurement:
        return "measurement";
    case ContentKind::Recipe:
        return "recipe";
    }
    return "ingredients";
}

ContentKind parseContentKind(std::string_view name) {
    for (const auto kind :
         {ContentKind::Ingredients, ContentKind::Spectra, ContentKind::Measurement, ContentKind::Recipe})
        if (contentKindName(kind) == name) return kind;
    throw InputError("<argument>", "--kind",
                     "unknown kind '" + std::string(name) +
                         "' (ingredients, spectra, measurement or recipe)");
}

ImportResult storeIngredients(Database& db, const std::vector<Ingredient>& ingredients,
                              const std::string& source, bool indexed) {
    if (ingredients.empty()) throw InputError(source, "ingredients", "the file holds no ingredient");
    ImportResult result;
    result.kind = ContentKind::Ingredients;
    detail::Transaction transaction(db.impl().connection, detail::Transaction::Mode::Write);
    for (std::size_t i = 0; i < ingredients.size(); ++i) {
        const Ingredient& ingredient = ingredients[i];
        const std::string record = (indexed ? "ingredients[" + std::to_string(i) + "] " : "") +
                                   std::string(ingredientKindName(ingredient.kind())) + " '" +
                                   ingredient.name + "'";
        for (std::size_t j = 0; j < i; ++j)
            if (ingredients[j].name == ingredient.name && ingredients[j].kind() == ingredient.kind())
                throw InputError(source, record, "this kind and name appear twice in the file");
        try {
            createIngredient(db, ingredient);
        } catch (const InputError& e) {
            rethrowForRecord(e, source, record);
        }
        result.names.push_back(ingredient.name);
    }
    transaction.commit();
    return result;
}

ImportResult storeSpectra(Database& db, const std::vector<NamedSpectrum>& spectra,
                          const std::string& source) {
    if (spectra.empty()) throw InputError(source, "spectra", "the file holds no spectrum");
    ImportResult result;
    result.kind = ContentKind::Spectra;
    detail::Transaction transaction(db.impl().connection, detail::Transaction::Mode::Write);
    for (const auto& s : spectra) {
        try {
            addNamedSpectrum(db, s.name, s.quantity, s.spectrum, s.info);
        } catch (const InputError& e) {
            rethrowForRecord(e, source, "spectrum '" + s.name + "'");
        }
        result.names.push_back(s.name);
    }
    transaction.commit();
    return result;
}

Measurement readMeasurementFile(const std::filesystem::path& file, const ImportOptions& options) {
    const FileFormat format = options.format ? *options.format : formatOfFile(file);
    const std::string text = jsonio::readBoundedTextFile(file, kMaxImportBytes);
    return parseMeasurementFile(file, text, format, options);
}

ImportResult importFile(Database& db, const std::filesystem::path& file, const ImportOptions& options) {
    const std::string source = file.string();
    const FileFormat format = options.format ? *options.format : formatOfFile(file);
    const std::string text = jsonio::readBoundedTextFile(file, kMaxImportBytes);
    const ContentKind kind = options.kind ? *options.kind : detectKind(text, format, source);
    switch (kind) {
    case ContentKind::Ingredients:
        return importIngredients(db, text, format, source);
    case ContentKind::Spectra:
        return importSpectra(db, text, format, source, options);
    case ContentKind::Measurement:
        return importMeasurement(db, file, text, format, options);
    case ContentKind::Recipe:
        return importRecipe(db, file, format, options);
    }
    return {};
}

std::vector<Ingredient> ingredientsByName(Database& db, const std::vector<std::string>& names) {
    const std::string file = db.file().string();
    std::vector<Ingredient> ingredients;
    const auto all = searchIngredients(db);
    if (names.empty()) {
        for (const auto& summary : all) ingredients.push_back(readIngredient(db, summary.id));
        return ingredients;
    }
    for (const auto& name : names) {
        bool found = false;
        for (const auto& summary : all)
            if (summary.name == name) {
                ingredients.push_back(readIngredient(db, summary.id));
                found = true;
            }
        if (!found) throw InputError(file, "ingredient '" + name + "'", "no such ingredient");
    }
    return ingredients;
}

std::vector<NamedSpectrum> spectraByName(Database& db, const std::vector<std::string>& names) {
    const std::string file = db.file().string();
    std::vector<NamedSpectrum> spectra;
    const auto add = [&](const StoredSpectrum& s) {
        spectra.push_back({s.name, s.quantity, s.info, s.spectrum});
    };
    if (names.empty()) {
        for (const auto& s : namedSpectra(db)) add(s);
        return spectra;
    }
    for (const auto& name : names) {
        const auto s = findNamedSpectrum(db, name);
        if (!s) throw InputError(file, "spectrum '" + name + "'", "no such spectrum");
        add(*s);
    }
    return spectra;
}

Measurement measurementByName(Database& db, std::string_view name) {
    auto m = findMeasurement(db, name);
    if (!m)
        throw InputError(db.file().string(), "measurement '" + std::string(name) + "'",
                         "no such measurement");
    return std::move(*m);
}

std::string exportIngredients(Database& db, const std::vector<std::string>& names, FileFormat format) {
    if (format != FileFormat::Json && format != FileFormat::Csv)
        throw InputError("<argument>", "--format", "ingredients are exported as JSON or CSV");
    const auto ingredients = ingredientsByName(db, names);
    return format == FileFormat::Json ? ingredientsToJson(ingredients) : ingredientsToCsv(ingredients);
}

std::string exportSpectra(Database& db, const std::vector<std::string>& names, FileFormat format) {
    const auto spectra = spectraByName(db, names);
    if (format == FileFormat::Json) return spectraToJson(spectra);
    if (format == FileFormat::Csv) return spectraToCsv(spectra);
    if (format == FileFormat::Cgats) return spectraToCgats(spectra);
    throw InputError("<argument>", "--format", "spectra are exported as JSON, CSV or CGATS");
}

std::string exportMeasurement(Database& db, std::string_view name, FileFormat format) {
    const Measurement m = measurementByName(db, name);
    if (format == FileFormat::Json) return measurementToJson(m);
    if (format == FileFormat::Csv) return measurementToCsv(m);
    throw InputError("<argument>", "--format", "measurements are exported as JSON or CSV");
}

}  // namespace paintlab::db
