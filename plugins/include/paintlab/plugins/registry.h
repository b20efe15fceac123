#pragma once
// The plugins PaintLab knows: the built-in formats (measurement JSON/CSV,
// spectra JSON/CSV/CGATS, the BRDF table JSON/CSV) and the shared libraries
// libpaintlab-plugin-*.so found in
//   1. the build tree's plugin folder (only for a program inside that build tree),
//   2. ../lib/paintlab/plugins beside the running program (installed),
//   3. the folders of PAINTLAB_PLUGIN_PATH (colon-separated),
// in that order. A file is refused, with its path and the reason, when it
// cannot be opened, lacks an entry point, was built for another API version
// or claims a format id another plugin has; the others keep working.
// Libraries are never unloaded (their code backs the objects handed out).

#include "paintlab/database/exchange.h"
#include "paintlab/plugins/plugin.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace paintlab::plugins {

struct LoadedPlugin {
    std::string name;
    std::string version;
    int api_version = kApiVersion;
    std::filesystem::path file;  // empty for the built-in plugin
    std::unique_ptr<Plugin> plugin;
    bool builtIn() const { return file.empty(); }
};

// What a plugin says about itself in the sidecar libpaintlab-plugin-NAME.json
// beside its library (after Qt's plugin metadata), readable without loading
// the library: a plugin built for another API version is refused without
// running its code, and a refused plugin's claims can still be listed. The
// build writes each sidecar from the loaded plugin (paintlab-plugin-metadata).
struct FormatClaim {
    std::string kind;  // "measurement import", "spectra export", "appearance export", ...
    std::string id;
    std::vector<std::string> extensions;
    friend bool operator==(const FormatClaim&, const FormatClaim&) = default;
};

struct PluginMetadata {
    std::string name;
    std::string version;
    int api_version = 0;
    std::vector<FormatClaim> formats;
    friend bool operator==(const PluginMetadata&, const PluginMetadata&) = default;
};

// The sidecar's path: the library's with ".json" for ".so".
std::filesystem::path metadataFileOf(const std::filesystem::path& library);
// The sidecar of a library; nullopt when there is none. Throws InputError
// naming the sidecar and the field when it is not valid metadata.
std::optional<PluginMetadata> readPluginMetadata(const std::filesystem::path& library);
// What a loaded plugin's sidecar says (every offer, in the plugin's order).
PluginMetadata metadataOf(const Plugin& plugin, int api_version);
// As the sidecar holds it: { "name", "version", "api_version", "formats": [ { "kind", "id", "extensions" } ]
// }.
std::string pluginMetadataJson(const PluginMetadata& metadata);

struct Refusal {
    std::filesystem::path file;
    std::string reason;
    std::optional<PluginMetadata> metadata;  // the sidecar's claims, when it has one
};

// An importer of any kind: at most one of the three is set.
struct ImporterChoice {
    const MeasurementImporter* measurement = nullptr;
    const SpectraImporter* spectra = nullptr;
    const IngredientImporter* ingredients = nullptr;
    const LoadedPlugin* plugin = nullptr;  // the plugin offering it
    bool found() const { return measurement != nullptr || spectra != nullptr || ingredients != nullptr; }
};

class Registry {
public:
    // The built-in plugin only.
    Registry();
    Registry(const Registry&) = delete;
    Registry& operator=(const Registry&) = delete;
    ~Registry();

    // The built-ins plus every plugin in defaultSearchPath(), loaded on the first call.
    static const Registry& global();
    static std::vector<std::filesystem::path> defaultSearchPath();

    // Loads every libpaintlab-plugin-*.so of a folder (in name order); a
    // missing folder is skipped. Never throws for a bad plugin: it is refused.
    void loadFolder(const std::filesystem::path& folder);
    // Loads one library; false (and a refusal) if it is refused.
    bool loadFile(const std::filesystem::path& file);
    // Adds a plugin object (the built-in one; tests). False (and a refusal
    // naming `file`) if it claims a format id already taken.
    bool add(std::unique_ptr<Plugin> plugin, const std::filesystem::path& file, int api_version);

    const std::vector<LoadedPlugin>& plugins() const { return m_plugins; }
    const std::vector<Refusal>& refusals() const { return m_refusals; }

    // The importer for a file: the one whose id is `format_id` if given
    // (nullptr if none), else the most confident probe among the importers
    // claiming the file's extension, else the most confident probe above 0.5
    // among all. nullptr when none fits. Throws InputError naming the file if
    // it cannot be read for probing.
    const MeasurementImporter* measurementImporterFor(const std::filesystem::path& file,
                                                      const std::optional<std::string>& format_id = {}) const;
    const SpectraImporter* spectraImporterFor(const std::filesystem::path& file,
                                              const std::optional<std::string>& format_id = {}) const;
    const IngredientImporter* ingredientImporterFor(const std::filesystem::path& file,
                                                    const std::optional<std::string>& format_id = {}) const;
    // For a file of unknown kind (`db import FILE`): the measurement, spectra or
    // ingredient importer chosen as above among the importers of all kinds, so that a
    // content both kinds claim by extension (CGATS: spectra, or a multi-angle
    // measurement) goes to the most confident probe.
    ImporterChoice importerFor(const std::filesystem::path& file,
                               const std::optional<std::string>& format_id = {}) const;
    // The exporter whose id is format_id, else the first claiming the file's extension.
    const AppearanceExporter* exporterFor(const std::filesystem::path& file,
                                          const std::optional<std::string>& format_id = {}) const;
    // The exporter of database content for `db export`: the one whose id is
    // `format`, else the one claiming ".<format>" (`--format csv`), else (no
    // format) the first claiming the file's extension; nullptr when none does.
    const MeasurementExporter* measurementExporterFor(const std::filesystem::path& file,
                                                      const std::optional<std::string>& format = {}) const;
    const SpectraExporter* spectraExporterFor(const std::filesystem::path& file,
                                              const std::optional<std::string>& format = {}) const;
    const IngredientExporter* ingredientExporterFor(const std::filesystem::path& file,
                                                    const std::optional<std::string>& format = {}) const;
    // The plugin that offers an object (for "built in or not").
    const LoadedPlugin* ownerOf(const void* offer) const;

private:
    std::vector<LoadedPlugin> m_plugins;
    std::vector<Refusal> m_refusals;
    std::vector<void*> m_handles;
};

// A measurement file through the registry: a plugin format's importer when
// one claims the file (by --format id, extension and probe), else the
// database's JSON/CSV reader (db::readMeasurementFile, unchanged). For
// `paintlab-cli fit --measurement` and `db import`. Throws InputError naming the file.
db::Measurement readMeasurementFile(const std::filesystem::path& file, const db::ImportOptions& options = {},
                                    std::size_t max_samples = 0,
                                    const std::optional<std::string>& format_id = {});

// The built-in plugin (registry_builtin.cpp).
std::unique_ptr<Plugin> makeBuiltInPlugin();

}  // namespace paintlab::plugins
