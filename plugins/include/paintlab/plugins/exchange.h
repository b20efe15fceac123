#pragma once
// What the CLI and the GUI share when files go in and out through the
// registry (registry.h), so that neither knows a format: the formats of one
// kind of offer (for a listing, an error message or a file chooser's
// filters), importing a file into the database, and the fast model's
// settings as an exported appearance records them.

#include "paintlab/database/exchange.h"
#include "paintlab/plugins/registry.h"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::plugins {

enum class OfferKind {
    MeasurementImport,
    SpectraImport,
    IngredientImport,
    AppearanceExport,
    MeasurementExport,
    SpectraExport,
    IngredientExport,
};

// The formats of every offer of a kind, in the registry's order (the built-in plugin first).
std::vector<FormatInfo> offeredFormats(const Registry& registry, OfferKind kind);
// "id (.ext .ext), id (.ext)": the formats for a message.
std::string describeFormats(const std::vector<FormatInfo>& formats);

struct ImportRequest {
    // The database importer's options: the kind (measurement, spectra and
    // ingredients limit the importers that compete; recipe: the database
    // reads it), a database format name given (`--format csv`: the database
    // reads the file as before), CGATS options, the measurement's description.
    db::ImportOptions options;
    // An importer's id ("merl-binary", "measurement-csv"): that importer reads
    // the file. None: the importer claiming the extension with the most
    // confident probe (registry.h), else a confident probe.
    std::optional<std::string> format_id;
    // Tabulated BRDF formats: at most this many samples (0: the format's default).
    std::size_t max_samples = 0;
};

// Imports a file into the database, whole or nothing (`db import`, the
// GUI's import dialogs). A plugin's importer (or any importer named by
// format_id) reads the whole file, then it is stored in one transaction
// (db::storeSpectra, storeIngredients, createMeasurement); the built-in
// formats chosen by extension and content go to db::importFile, which reads
// them as it always has (a recipe, told from ingredients by content,
// included). Throws InputError naming the file and the record for a bad
// file (nothing stored), InputError("<argument>", "--format", ...) for an
// unknown format id.
db::ImportResult importFile(db::Database& db, const std::filesystem::path& file,
                            const ImportRequest& request);

// The fast model's settings as a JSON object (preset, nodes, orders, bands,
// slices, max_start_tau, compute_seconds): what the BRDF table and the
// exporters record (ExportOptions::settings_json) and `brdf`, `eval` and
// `multiangle --json` print.
std::string fastModelSettingsJson(const LayeredBrdf& brdf, std::string_view preset);

}  // namespace paintlab::plugins
