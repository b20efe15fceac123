// `db import|export|recipe-export|production|measurement-import|measurements|spectra`:
// files in and out of the database (exchange.h, production.h). An import is
// all or nothing; every output file is written atomically.

#include "db_cli.h"

#include "paintlab/database/exchange.h"
#include "paintlab/database/ingredients.h"
#include "paintlab/database/measurements.h"
#include "paintlab/database/production.h"
#include "paintlab/database/recipes.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/plugins/exchange.h"
#include "paintlab/plugins/registry.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace paintlab::cli {

namespace {

using nlohmann::ordered_json;

struct ExchangeOptions {
    std::string db_file;
    bool json = false;
    std::string file;  // import: the file read; export, production: --out
    std::string format;
    std::string kind;
    std::vector<std::string> names;
    bool all = false;
    int version = 0;
    // import: spectra
    std::string quantity = "reflectance";
    std::string unit;
    std::string source;
    // import: measurement description
    std::string name;
    std::string instrument;
    std::string geometry;
    std::string sample;
    std::string measured_at;
    std::string illuminant = "D65";
    std::string observer = "10deg";
    std::optional<std::size_t> samples;  // tabulated BRDF formats: at most this many
    // import: recipes
    std::string author;
    std::string note;
    // production
    std::optional<double> batch_kg;
    std::optional<double> area_m2;
    double transfer_efficiency = 1.0;
};

std::string defaultAuthor(const std::string& author) {
    if (!author.empty()) return author;
    const char* user = std::getenv("USER");  // NOLINT(concurrency-mt-unsafe): single-threaded here
    return user != nullptr && *user != '\0' ? user : "unknown";
}

db::FileFormat outputFormat(const ExchangeOptions& options) {
    return options.format.empty() ? db::formatOfFile(options.file) : db::parseFileFormat(options.format);
}

bool isDatabaseFormatName(const std::string& name) {
    try {
        (void)db::parseFileFormat(name);
        return true;
    } catch (const InputError&) {
        return false;
    }
}

int runImport(const ExchangeOptions& options) {
    // The registry chooses the importer (plugins/exchange.h): --format is a
    // database format name (csv, json, cgats) or an importer's id.
    plugins::ImportRequest request;
    db::ImportOptions& import = request.options;
    if (!options.format.empty()) {
        if (isDatabaseFormatName(options.format))
            import.format = db::parseFileFormat(options.format);
        else
            request.format_id = options.format;
    }
    if (!options.kind.empty()) import.kind = db::parseContentKind(options.kind);
    if (options.samples && *options.samples == 0)
        throw InputError("<argument>", "--samples", "must be at least 1");
    request.max_samples = options.samples.value_or(0);
    import.cgats.quantity = options.quantity;
    import.cgats.unit = options.unit;
    import.cgats.source = options.source;
    import.measurement.name = options.name;
    import.measurement.instrument = options.instrument;
    import.measurement.geometry = options.geometry;
    import.measurement.sample = options.sample;
    import.measurement.measured_at = options.measured_at;
    import.measurement.source = options.source;
    import.measurement.illuminant = options.illuminant;
    import.measurement.observer = options.observer;
    import.author = defaultAuthor(options.author);
    import.note = options.note;
    db::Database database = openCliDatabase(options.db_file, false);
    const auto result = plugins::importFile(database, options.file, request);
    for (const auto& missing : result.unlinked)
        std::cerr << "warning: " << options.file << ": " << missing
                  << ": not in the database; saved with the recipe's own data, unlinked\n";
    if (options.json) {
        ordered_json out{{"database", database.file().string()},
                         {"file", options.file},
                         {"kind", db::contentKindName(result.kind)},
                         {"added", result.names}};
        if (result.kind == db::ContentKind::Recipe) {
            out["version"] = result.recipe_version;
            out["created"] = result.recipe_created;
        }
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    if (result.kind == db::ContentKind::Recipe) {
        std::cout << (result.recipe_created ? "saved '" : "unchanged: '") << result.names.front()
                  << "' version " << result.recipe_version << '\n';
        return 0;
    }
    std::cout << "imported " << result.names.size() << ' ' << db::contentKindName(result.kind) << " from "
              << options.file << " into " << database.file().string() << ":\n";
    for (const auto& name : result.names) std::cout << "  " << name << '\n';
    return 0;
}

// The error when no exporter of the kind takes --format or the --out extension: what the registry offers.
InputError noExporter(const ExchangeOptions& options, const std::string& kind, plugins::OfferKind offers) {
    const std::string list =
        plugins::describeFormats(plugins::offeredFormats(plugins::Registry::global(), offers));
    if (!options.format.empty())
        return {"<argument>", "--format",
                "no format '" + options.format + "' for " + kind + "; " + kind + " are exported as " + list};
    return {options.file, "",
            "cannot tell the format from the extension '" +
                std::filesystem::path(options.file).extension().string() + "': " + kind +
                " are exported as " + list + "; give --format"};
}

int runExport(const ExchangeOptions& options) {
    if (options.names.empty() == !options.all)
        throw InputError("<argument>", "NAME/--all", "give the names to export or --all, not both");
    std::string kind = options.kind.empty() ? "ingredients" : options.kind;
    db::Database database = openCliDatabase(options.db_file, false);
    std::vector<std::string> names = options.names;
    // --kind pigment (an ingredient kind, as in `db list`): those ingredients.
    if (const auto ingredient_kind = db::parseIngredientKind(kind)) {
        db::IngredientFilter filter;
        filter.kind = ingredient_kind;
        if (options.all)
            for (const auto& summary : db::searchIngredients(database, filter)) names.push_back(summary.name);
        if (names.empty())
            throw InputError(database.file().string(), "--kind " + kind, "no ingredient of this kind");
        kind = "ingredients";
    }
    const plugins::Registry& registry = plugins::Registry::global();
    const std::optional<std::string> format =
        options.format.empty() ? std::nullopt : std::optional<std::string>(options.format);
    std::string text;
    switch (db::parseContentKind(kind)) {
    case db::ContentKind::Ingredients: {
        const auto* exporter = registry.ingredientExporterFor(options.file, format);
        if (exporter == nullptr) throw noExporter(options, kind, plugins::OfferKind::IngredientExport);
        text = exporter->text(db::ingredientsByName(database, names));
        break;
    }
    case db::ContentKind::Spectra: {
        const auto* exporter = registry.spectraExporterFor(options.file, format);
        if (exporter == nullptr) throw noExporter(options, kind, plugins::OfferKind::SpectraExport);
        text = exporter->text(db::spectraByName(database, names));
        break;
    }
    case db::ContentKind::Measurement: {
        if (options.names.size() != 1)
            throw InputError("<argument>", "NAME", "export one measurement at a time");
        const db::Measurement m = db::measurementByName(database, options.names.front());
        const auto* exporter = registry.measurementExporterFor(options.file, format);
        if (exporter == nullptr)
            throw noExporter(options, "measurements", plugins::OfferKind::MeasurementExport);
        text = exporter->text(m);
        break;
    }
    case db::ContentKind::Recipe:
        throw InputError("<argument>", "--kind",
                         "recipes are exported with `db recipe-export NAME --out FILE.json`");
    }
    io::writeFileAtomically(options.file, text);
    std::cout << "exported "
              << (options.all ? "all " + kind : kind + " " + std::to_string(options.names.size())) << " to "
              << options.file << '\n';
    return 0;
}

int runRecipeExport(const ExchangeOptions& options) {
    db::Database database = openCliDatabase(options.db_file, false);
    const auto stored = db::loadRecipeVersion(
        database, options.name, options.version > 0 ? std::optional(options.version) : std::nullopt);
    // The canonical JSON is what the checksum is of: the file hashes to the version's SHA-256.
    io::writeFileAtomically(options.file, recipeToJson(stored.recipe));
    if (options.json)
        std::cout << ordered_json{{"recipe", stored.info.recipe_name},
                                  {"version", stored.info.version},
                                  {"checksum_sha256", stored.info.checksum_sha256},
                                  {"file", options.file}}
                         .dump(2)
                  << '\n';
    else
        std::cout << "wrote '" << stored.info.recipe_name << "' version " << stored.info.version
                  << " (SHA-256 " << stored.info.checksum_sha256 << ") to " << options.file << '\n';
    return 0;
}

int runProduction(const ExchangeOptions& options) {
    db::ProductionOptions production;
    production.batch_kg = options.batch_kg;
    production.area_m2 = options.area_m2;
    production.transfer_efficiency = options.transfer_efficiency;
    db::validateProductionOptions(production);
    const db::FileFormat format = outputFormat(options);
    if (format == db::FileFormat::Cgats)
        throw InputError("<argument>", "--format", "a production sheet is written as csv, json or html");
    db::Database database = openCliDatabase(options.db_file, false);
    const auto sheet =
        db::productionSheet(database, options.name,
                            options.version > 0 ? std::optional(options.version) : std::nullopt, production);
    const std::string text = format == db::FileFormat::Csv    ? db::productionCsv(sheet)
                             : format == db::FileFormat::Json ? db::productionJson(sheet)
                                                              : db::productionHtml(sheet);
    io::writeFileAtomically(options.file, text);
    for (const auto& layer : sheet.layers)
        for (const auto& warning : layer.warnings) std::cerr << "warning: " << warning << '\n';
    if (options.json) {
        std::cout << db::productionJson(sheet);
        return 0;
    }
    std::cout << "production sheet of '" << sheet.version.recipe_name << "' version " << sheet.version.version
              << " (SHA-256 " << sheet.version.checksum_sha256 << ") written to " << options.file << '\n';
    for (const auto& layer : sheet.layers) {
        std::cout << "  " << layer.name << ": " << layer.batch_mass_kg << " kg";
        for (const auto& line : layer.lines) std::cout << ", " << line.name << " " << line.mass_kg << " kg";
        std::cout << '\n';
    }
    return 0;
}

int runMeasurementImport(const ExchangeOptions& options) {
    ExchangeOptions with_kind = options;
    with_kind.kind = "measurement";
    return runImport(with_kind);
}

int runMeasurements(const ExchangeOptions& options) {
    db::Database database = openCliDatabase(options.db_file, false);
    const auto measurements = db::listMeasurements(database);
    if (options.json) {
        ordered_json out = ordered_json::array();
        for (const auto& m : measurements)
            out.push_back({{"name", m.name},
                           {"kind", db::measurementKindName(m.kind)},
                           {"instrument", m.instrument},
                           {"sample", m.sample},
                           {"measured_at", m.measured_at},
                           {"points", m.points},
                           {"fits", m.fits}});
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::cout << "Measurements (" << measurements.size() << "):\n";
    for (const auto& m : measurements)
        std::cout << "  " << m.name << "  " << db::measurementKindName(m.kind) << "  " << m.points
                  << " points  " << m.fits << " fits" << (m.instrument.empty() ? "" : "  " + m.instrument)
                  << '\n';
    return 0;
}

int runSpectra(const ExchangeOptions& options) {
    db::Database database = openCliDatabase(options.db_file, false);
    const auto spectra = db::namedSpectra(database);
    if (options.json) {
        ordered_json out = ordered_json::array();
        for (const auto& s : spectra)
            out.push_back({{"name", s.name},
                           {"quantity", s.quantity},
                           {"unit", s.info.unit},
                           {"source", s.info.source},
                           {"date", s.info.date},
                           {"samples", s.spectrum.values().size()}});
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::cout << "Spectra (" << spectra.size() << "):\n";
    for (const auto& s : spectra)
        std::cout << "  " << s.name << "  " << s.quantity << " [" << s.info.unit << "]  "
                  << s.spectrum.values().size() << " samples\n";
    return 0;
}

CLI::App* addSubcommand(CLI::App& group, const std::string& name, const std::string& help,
                        const std::shared_ptr<ExchangeOptions>& options, CommandAction& action,
                        int (*run)(const ExchangeOptions&)) {
    CLI::App* command = group.add_subcommand(name, help);
    command->add_option("--db", options->db_file,
                        "Database file (default: the user's, created from the demo)");
    command->callback([options, &action, run] { action = [options, run] { return run(*options); }; });
    return command;
}

void addImportOptions(CLI::App& command, ExchangeOptions& o) {
    command.add_option("file", o.file, "File to import")->required();
    command.add_option("--format", o.format,
                       "csv, json, cgats or a plugin's format id such as merl-binary (default: from the "
                       "extension and content; paintlab-cli plugins lists them)");
    command.add_option("--quantity", o.quantity, "CGATS spectra: what the values are (default reflectance)");
    command.add_option("--unit", o.unit,
                       "CGATS spectra and multi-angle CGATS: unit of the spectral values (1 or %)");
    command.add_option("--source", o.source, "Source of the data (instrument, reference)");
    command.add_option("--name", o.name, "Measurement CSV: its name (default: the file stem)");
    command.add_option("--instrument", o.instrument, "Measurement CSV: the instrument");
    command.add_option("--geometry", o.geometry, "Measurement CSV: the geometry description");
    command.add_option(
        "--sample", o.sample,
        "Measurement CSV: the panel measured (a multi-angle CGATS file of several panels: the one to read)");
    command.add_option("--measured-at", o.measured_at, "Measurement CSV: date (ISO 8601)");
    command.add_option("--illuminant", o.illuminant, "Measurement CSV: D65, D50 or A (default D65)");
    command.add_option("--observer", o.observer, "Measurement CSV: 2deg or 10deg (default 10deg)");
    command.add_option("--samples", o.samples,
                       "Tabulated BRDF formats (MERL): keep at most this many samples (default 4096)");
    command.add_flag("--json", o.json, "Print the result as JSON");
}

}  // namespace

void addDbExchangeCommands(CLI::App& group, CommandAction& action) {
    auto o = std::make_shared<ExchangeOptions>();

    CLI::App* import = addSubcommand(group, "import",
                                     "Import ingredients, spectra, a measurement or a recipe from a file "
                                     "(all or nothing)",
                                     o, action, runImport);
    addImportOptions(*import, *o);
    import->add_option("--kind", o->kind,
                       "ingredients, spectra, measurement or recipe (default: from the file's content)");
    import->add_option("--author", o->author, "Recipes: who saves the version (default: $USER)");
    import->add_option("--note", o->note, "Recipes: what changed and why");

    CLI::App* exporter = addSubcommand(
        group, "export", "Export ingredients, spectra or a measurement to a file", o, action, runExport);
    exporter->add_option("names", o->names, "Names to export (or --all)");
    exporter->add_flag("--all", o->all, "Export every one of the kind");
    exporter->add_option("--out", o->file, "File to write")->required();
    exporter->add_option("--format", o->format, "csv, json or cgats (default: from the extension)");
    exporter->add_option(
        "--kind", o->kind,
        "ingredients (default), spectra or measurement; or an ingredient kind (pigment, ...)");

    CLI::App* recipe_export =
        addSubcommand(group, "recipe-export", "Write a saved recipe version to a JSON recipe file", o, action,
                      runRecipeExport);
    recipe_export->add_option("name", o->name, "Recipe name")->required();
    recipe_export->add_option("--version", o->version, "Recipe version (default: the latest)")
        ->check(CLI::PositiveNumber);
    recipe_export->add_option("--out", o->file, "Recipe file to write (.json)")->required();
    recipe_export->add_flag("--json", o->json, "Print the result as JSON");

    CLI::App* production = addSubcommand(
        group, "production", "Production sheet of a recipe version: the mass of every ingredient per layer",
        o, action, runProduction);
    production->add_option("name", o->name, "Recipe name")->required();
    production->add_option("--version", o->version, "Recipe version (default: the latest)")
        ->check(CLI::PositiveNumber);
    auto* batch = production->add_option("--batch-kg", o->batch_kg, "Wet paint per layer, kg");
    auto* area = production->add_option("--area-m2", o->area_m2,
                                        "Painted area, m2 (each layer at its dry film thickness)");
    batch->excludes(area);
    production->add_option(
        "--transfer-efficiency", o->transfer_efficiency,
        "With --area-m2: fraction of the sprayed paint that lands on the part (default 1)");
    production->add_option("--out", o->file, "Sheet to write: .csv, .json or .html")->required();
    production->add_option("--format", o->format, "csv, json or html (default: from the extension)");
    production->add_flag("--json", o->json, "Print the sheet as JSON");

    CLI::App* measurement_import = addSubcommand(group, "measurement-import",
                                                 "Import a measurement (multi-angle CIELAB or BRDF samples)",
                                                 o, action, runMeasurementImport);
    addImportOptions(*measurement_import, *o);

    CLI::App* measurements =
        addSubcommand(group, "measurements", "List the measurements", o, action, runMeasurements);
    measurements->add_flag("--json", o->json, "Print as JSON");

    CLI::App* spectra =
        addSubcommand(group, "spectra", "List the spectra stored on their own", o, action, runSpectra);
    spectra->add_flag("--json", o->json, "Print as JSON");
}

}  // namespace paintlab::cli
