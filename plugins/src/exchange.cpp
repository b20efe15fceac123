// Files in and out through the registry, shared by the CLI and the GUI (exchange.h).

#include "paintlab/plugins/exchange.h"

#include "paintlab/database/measurements.h"
#include "paintlab/engine/error.h"

#include <nlohmann/json.hpp>

#include <system_error>

namespace paintlab::plugins {

namespace {

template <typename Offer>
void addFormats(std::vector<FormatInfo>& formats, const std::vector<const Offer*>& offers) {
    for (const Offer* offer : offers) formats.push_back(offer->format());
}

// The importer for a file among those of the kind asked for (all kinds without one).
ImporterChoice chooseImporter(const Registry& registry, const std::filesystem::path& file,
                              const std::optional<db::ContentKind>& kind,
                              const std::optional<std::string>& format_id) {
    ImporterChoice choice;
    if (kind == db::ContentKind::Measurement)
        choice.measurement = registry.measurementImporterFor(file, format_id);
    else if (kind == db::ContentKind::Spectra)
        choice.spectra = registry.spectraImporterFor(file, format_id);
    else if (kind == db::ContentKind::Ingredients)
        choice.ingredients = registry.ingredientImporterFor(file, format_id);
    else
        choice = registry.importerFor(file, format_id);
    choice.plugin = choice.measurement != nullptr   ? registry.ownerOf(choice.measurement)
                    : choice.spectra != nullptr     ? registry.ownerOf(choice.spectra)
                    : choice.ingredients != nullptr ? registry.ownerOf(choice.ingredients)
                                                    : nullptr;
    return choice;
}

// Reads the whole file through the importer, then stores it in one transaction.
db::ImportResult readAndStore(db::Database& db, const ImporterChoice& choice,
                              const std::filesystem::path& file, const ImportRequest& request) {
    ReadOptions read;
    read.description = request.options.measurement;
    read.max_samples = request.max_samples;
    read.cgats = request.options.cgats;
    const std::string source = file.string();
    if (choice.spectra != nullptr) return db::storeSpectra(db, choice.spectra->read(file, read), source);
    if (choice.ingredients != nullptr)
        return db::storeIngredients(db, choice.ingredients->read(file, read), source);
    const db::Measurement m = choice.measurement->read(file, read);
    try {
        db::createMeasurement(db, m);
    } catch (const InputError& e) {
        throw InputError(source, "measurement '" + m.name + "'",
                         e.detail() + " (database " + e.source() + ")");
    }
    db::ImportResult result;
    result.kind = db::ContentKind::Measurement;
    result.names.push_back(m.name);
    return result;
}

}  // namespace

std::vector<FormatInfo> offeredFormats(const Registry& registry, OfferKind kind) {
    std::vector<FormatInfo> formats;
    for (const auto& loaded : registry.plugins()) {
        const Plugin& p = *loaded.plugin;
        switch (kind) {
        case OfferKind::MeasurementImport:
            addFormats(formats, p.measurementImporters());
            break;
        case OfferKind::SpectraImport:
            addFormats(formats, p.spectraImporters());
            break;
        case OfferKind::IngredientImport:
            addFormats(formats, p.ingredientImporters());
            break;
        case OfferKind::AppearanceExport:
            addFormats(formats, p.exporters());
            break;
        case OfferKind::MeasurementExport:
            addFormats(formats, p.measurementExporters());
            break;
        case OfferKind::SpectraExport:
            addFormats(formats, p.spectraExporters());
            break;
        case OfferKind::IngredientExport:
            addFormats(formats, p.ingredientExporters());
            break;
        }
    }
    return formats;
}

std::string describeFormats(const std::vector<FormatInfo>& formats) {
    std::string list;
    for (const FormatInfo& info : formats) {
        if (!list.empty()) list.append(", ");
        list.append(info.id).append(" (");
        for (std::size_t i = 0; i < info.extensions.size(); ++i)
            list.append(i > 0 ? " " : "").append(info.extensions[i]);
        list.append(")");
    }
    return list;
}

db::ImportResult importFile(db::Database& db, const std::filesystem::path& file,
                            const ImportRequest& request) {
    const db::ImportOptions& options = request.options;
    // A database format name or a recipe: the database's importer, as always.
    if (options.format || options.kind == db::ContentKind::Recipe) return db::importFile(db, file, options);
    // A file that cannot be probed: the database's importer says what is wrong with it.
    std::error_code error;
    if (!request.format_id && !std::filesystem::is_regular_file(file, error))
        return db::importFile(db, file, options);
    const ImporterChoice choice = chooseImporter(Registry::global(), file, options.kind, request.format_id);
    if (request.format_id && !choice.found())
        throw InputError("<argument>", "--format",
                         "unknown format '" + *request.format_id +
                             "' (csv, json, cgats, html, or a plugin's format: paintlab-cli plugins)");
    // The built-in formats chosen by extension and content are read as before.
    if (!choice.found() || (!request.format_id && (choice.plugin == nullptr || choice.plugin->builtIn())))
        return db::importFile(db, file, options);
    return readAndStore(db, choice, file, request);
}

std::string fastModelSettingsJson(const LayeredBrdf& brdf, std::string_view preset) {
    const auto& s = brdf.settings();
    return nlohmann::ordered_json{{"preset", std::string(preset)},
                                  {"nodes", s.nodes},
                                  {"orders", s.orders},
                                  {"bands", s.bands},
                                  {"slices", s.slices},
                                  {"max_start_tau", s.max_start_tau},
                                  {"compute_seconds", brdf.computeSeconds()}}
        .dump();
}

}  // namespace paintlab::plugins
