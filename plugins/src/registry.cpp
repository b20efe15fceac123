// The plugin registry (registry.h): dlopen, the API-version check, refusals.

#include "paintlab/plugins/registry.h"

#include "paintlab/engine/error.h"

#include "json_reader.h"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <system_error>

namespace paintlab::plugins {

namespace {

using ApiVersionFn = int (*)();
using CreateFn = Plugin* (*)();

std::string lowerAscii(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool claimsExtension(const FormatInfo& info, const std::filesystem::path& file) {
    const std::string extension = lowerAscii(file.extension().string());
    return std::find(info.extensions.begin(), info.extensions.end(), extension) != info.extensions.end();
}

// Every format id a plugin offers, with the kind of offer in front (a
// measurement and a spectra importer may share an id such as "json").
std::vector<std::string> claimedIds(const Plugin& plugin) {
    std::vector<std::string> ids;
    for (const auto* offer : plugin.measurementImporters())
        ids.push_back("measurement " + offer->format().id);
    for (const auto* offer : plugin.spectraImporters()) ids.push_back("spectra " + offer->format().id);
    for (const auto* offer : plugin.ingredientImporters()) ids.push_back("ingredients " + offer->format().id);
    for (const auto* offer : plugin.exporters()) ids.push_back("export " + offer->format().id);
    for (const auto* offer : plugin.measurementExporters())
        ids.push_back("measurement export " + offer->format().id);
    for (const auto* offer : plugin.spectraExporters()) ids.push_back("spectra export " + offer->format().id);
    for (const auto* offer : plugin.ingredientExporters())
        ids.push_back("ingredients export " + offer->format().id);
    return ids;
}

// The content exporter for a file and --format (registry.h).
template <typename Exporter, typename Offers>
const Exporter* chooseContentExporter(const std::vector<LoadedPlugin>& plugins, Offers offers,
                                      const std::filesystem::path& file,
                                      const std::optional<std::string>& format) {
    std::vector<const Exporter*> all;
    for (const auto& loaded : plugins)
        for (const Exporter* offer : offers(*loaded.plugin)) all.push_back(offer);
    if (format) {
        for (const Exporter* offer : all)
            if (offer->format().id == *format) return offer;
        const std::string extension = "." + lowerAscii(*format);
        for (const Exporter* offer : all) {
            const auto& extensions = offer->format().extensions;
            if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) return offer;
        }
        return nullptr;
    }
    for (const Exporter* offer : all)
        if (claimsExtension(offer->format(), file)) return offer;
    return nullptr;
}

struct Head {
    std::string bytes;
    std::uintmax_t size = 0;
};

Head readHead(const std::filesystem::path& file) {
    std::error_code error;
    Head head;
    head.size = std::filesystem::file_size(file, error);
    std::ifstream in(file, std::ios::binary);
    if (error || !in)
        throw InputError(file.string(), "", "cannot read the file (missing or not a regular file)");
    head.bytes.resize(kProbeBytes);
    in.read(head.bytes.data(), static_cast<std::streamsize>(kProbeBytes));
    head.bytes.resize(static_cast<std::size_t>(in.gcount()));
    return head;
}

// An importer of either kind with what the choice needs.
struct Offer {
    const void* offer = nullptr;
    FormatInfo info;
    std::function<double(std::string_view, std::uintmax_t)> probe;
};

template <typename Importer>
void addOffers(std::vector<Offer>& all, const std::vector<const Importer*>& offers) {
    for (const Importer* offer : offers)
        all.push_back({offer, offer->format(), [offer](std::string_view head, std::uintmax_t size) {
                           return offer->probe(head, size);
                       }});
}

// The offer chosen by id, extension and probe (registry.h), nullptr if none.
const void* chooseOffer(const std::vector<Offer>& all, const std::filesystem::path& file,
                        const std::optional<std::string>& format_id) {
    if (format_id) {
        for (const Offer& offer : all)
            if (offer.info.id == *format_id) return offer.offer;
        return nullptr;
    }
    const Head head = readHead(file);
    const void* best = nullptr;
    double best_confidence = -1.0;  // a claimed extension wins even when no probe recognises the content:
                                    // the importer then says what is wrong with the file
    for (const Offer& offer : all) {
        if (!claimsExtension(offer.info, file)) continue;
        const double confidence = offer.probe(head.bytes, head.size);
        if (confidence > best_confidence) {
            best = offer.offer;
            best_confidence = confidence;
        }
    }
    if (best != nullptr) return best;
    best_confidence = 0.5;  // without the extension, only a confident probe
    for (const Offer& offer : all) {
        const double confidence = offer.probe(head.bytes, head.size);
        if (confidence > best_confidence) {
            best = offer.offer;
            best_confidence = confidence;
        }
    }
    return best;
}

}  // namespace

std::filesystem::path metadataFileOf(const std::filesystem::path& library) {
    std::filesystem::path file = library;
    return file.replace_extension(".json");
}

std::optional<PluginMetadata> readPluginMetadata(const std::filesystem::path& library) {
    const std::filesystem::path file = metadataFileOf(library);
    std::error_code error;
    if (!std::filesystem::exists(file, error)) return std::nullopt;
    const std::string source = file.string();
    const nlohmann::json document =
        jsonio::parseUntrustedJson(jsonio::readBoundedTextFile(file, std::size_t{1} << 20), source);
    if (!document.is_object()) throw InputError(source, "", "plugin metadata is a JSON object");
    jsonio::ObjectReader fields(document, "", source);
    PluginMetadata m;
    m.name = fields.string("name", true);
    m.version = fields.string("version", true);
    m.api_version = fields.integerIn("api_version", 0, 1000000);
    const nlohmann::json& formats = fields.require("formats", "an array");
    if (!formats.is_array()) fields.fail("formats", "must be an array");
    for (std::size_t i = 0; i < formats.size(); ++i) {
        const std::string at = fields.elementPath("formats", i);
        if (!formats[i].is_object()) throw InputError(source, at, "must be an object");
        jsonio::ObjectReader claim(formats[i], at, source);
        FormatClaim c;
        c.kind = claim.string("kind", true);
        c.id = claim.string("id", true);
        const nlohmann::json& extensions = claim.require("extensions", "an array");
        if (!extensions.is_array()) claim.fail("extensions", "must be an array of strings");
        for (const auto& extension : extensions) {
            if (!extension.is_string()) claim.fail("extensions", "must be an array of strings");
            c.extensions.push_back(extension.get<std::string>());
        }
        claim.finish();
        m.formats.push_back(std::move(c));
    }
    fields.finish();
    return m;
}

PluginMetadata metadataOf(const Plugin& plugin, int api_version) {
    PluginMetadata m{plugin.name(), plugin.version(), api_version, {}};
    const auto add = [&](const char* kind, const auto& offers) {
        for (const auto* offer : offers) {
            const FormatInfo info = offer->format();
            m.formats.push_back({kind, info.id, info.extensions});
        }
    };
    add("measurement import", plugin.measurementImporters());
    add("spectra import", plugin.spectraImporters());
    add("ingredients import", plugin.ingredientImporters());
    add("appearance export", plugin.exporters());
    add("measurement export", plugin.measurementExporters());
    add("spectra export", plugin.spectraExporters());
    add("ingredients export", plugin.ingredientExporters());
    return m;
}

std::string pluginMetadataJson(const PluginMetadata& metadata) {
    nlohmann::ordered_json formats = nlohmann::ordered_json::array();
    for (const auto& c : metadata.formats)
        formats.push_back({{"kind", c.kind}, {"id", c.id}, {"extensions", c.extensions}});
    const nlohmann::ordered_json out{{"name", metadata.name},
                                     {"version", metadata.version},
                                     {"api_version", metadata.api_version},
                                     {"formats", formats}};
    return out.dump(2) + "\n";
}

Registry::Registry() { add(makeBuiltInPlugin(), {}, kApiVersion); }

Registry::~Registry() = default;  // handles stay open: see registry.h

const Registry& Registry::global() {
    static const Registry* registry = [] {
        auto* r = new Registry();  // never destroyed: plugin code must outlive every user
        for (const auto& folder : defaultSearchPath()) r->loadFolder(folder);
        return r;
    }();
    return *registry;
}

std::vector<std::filesystem::path> Registry::defaultSearchPath() {
    std::vector<std::filesystem::path> folders;
    std::error_code error;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", error);
    // The build tree's folder only for a program inside that build tree, so
    // an installed copy never picks up (or clashes with) a build's plugins.
    const std::string build_root = PAINTLAB_BUILD_ROOT;
    if (!error && exe.string().starts_with(build_root + "/")) folders.emplace_back(PAINTLAB_PLUGIN_BUILD_DIR);
    if (!error) folders.push_back(exe.parent_path().parent_path() / "lib" / "paintlab" / "plugins");
    // NOLINTNEXTLINE(concurrency-mt-unsafe): read once, before any plugin thread
    if (const char* path = std::getenv("PAINTLAB_PLUGIN_PATH")) {
        std::string list = path;
        std::size_t start = 0;
        while (start <= list.size()) {
            const std::size_t end = std::min(list.find(':', start), list.size());
            if (end > start) folders.emplace_back(list.substr(start, end - start));
            start = end + 1;
        }
    }
    // The same folder twice (the build tree is also beside the program) is loaded once.
    std::vector<std::filesystem::path> unique;
    std::set<std::filesystem::path> seen;
    for (const auto& folder : folders) {
        const auto canonical = std::filesystem::weakly_canonical(folder, error);
        if (seen.insert(error ? folder : canonical).second) unique.push_back(folder);
    }
    return unique;
}

void Registry::loadFolder(const std::filesystem::path& folder) {
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) return;
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("libpaintlab-plugin-") && name.ends_with(".so")) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) loadFile(file);
}

bool Registry::loadFile(const std::filesystem::path& file) {
    std::optional<PluginMetadata> metadata;
    const auto refuse = [&](const std::string& reason) {
        m_refusals.push_back({file, reason, metadata});
        return false;
    };
    for (const auto& loaded : m_plugins)
        if (loaded.file == file) return true;
    // The sidecar first: a plugin for another API version is refused without running its code.
    try {
        metadata = readPluginMetadata(file);
    } catch (const InputError& e) {
        return refuse(std::string("unreadable metadata: ") + e.what());
    }
    if (metadata && metadata->api_version != kApiVersion)
        return refuse("built for plugin API version " + std::to_string(metadata->api_version) + " (" +
                      metadataFileOf(file).filename().string() + "), this PaintLab has " +
                      std::to_string(kApiVersion) + "; not loaded");
    // RTLD_LOCAL: each plugin keeps its own copy of the engine and database code to itself.
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
        const char* message = dlerror();
        return refuse(std::string("cannot be loaded: ") + (message != nullptr ? message : "dlopen failed"));
    }
    m_handles.push_back(handle);
    // POSIX: a dlsym result converts to a function pointer.
    const auto api = reinterpret_cast<ApiVersionFn>(dlsym(handle, "paintlab_plugin_api_version"));
    const auto create = reinterpret_cast<CreateFn>(dlsym(handle, "paintlab_plugin_create"));
    if (api == nullptr) return refuse("no entry point paintlab_plugin_api_version (not a PaintLab plugin?)");
    if (create == nullptr) return refuse("no entry point paintlab_plugin_create");
    const int version = api();
    if (version != kApiVersion)
        return refuse("built for plugin API version " + std::to_string(version) + ", this PaintLab has " +
                      std::to_string(kApiVersion));
    std::unique_ptr<Plugin> plugin;
    try {
        plugin.reset(create());
    } catch (const std::exception& e) {
        return refuse(std::string("paintlab_plugin_create failed: ") + e.what());
    }
    if (!plugin) return refuse("paintlab_plugin_create returned no plugin");
    return add(std::move(plugin), file, version);
}

bool Registry::add(std::unique_ptr<Plugin> plugin, const std::filesystem::path& file, int api_version) {
    const auto ids = claimedIds(*plugin);
    // A plugin refused here was loaded: its claims come from the object itself.
    const auto refuse = [&](const std::string& reason) {
        m_refusals.push_back({file, reason, metadataOf(*plugin, api_version)});
        return false;
    };
    for (std::size_t i = 0; i < ids.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (ids[i] == ids[j]) return refuse("offers the format " + ids[i] + " twice");
    for (const auto& loaded : m_plugins) {
        if (loaded.name == plugin->name())
            return refuse("a plugin named '" + loaded.name + "' is already loaded from " +
                          (loaded.builtIn() ? "PaintLab itself" : loaded.file.string()));
        for (const auto& id : claimedIds(*loaded.plugin))
            if (std::find(ids.begin(), ids.end(), id) != ids.end())
                return refuse("claims the format " + id + ", which plugin '" + loaded.name + "' (" +
                              (loaded.builtIn() ? "built in" : loaded.file.string()) + ") already offers");
    }
    LoadedPlugin loaded;
    loaded.name = plugin->name();
    loaded.version = plugin->version();
    loaded.api_version = api_version;
    loaded.file = file;
    loaded.plugin = std::move(plugin);
    m_plugins.push_back(std::move(loaded));
    return true;
}

const MeasurementImporter*
Registry::measurementImporterFor(const std::filesystem::path& file,
                                 const std::optional<std::string>& format_id) const {
    std::vector<Offer> all;
    for (const auto& loaded : m_plugins) addOffers(all, loaded.plugin->measurementImporters());
    return static_cast<const MeasurementImporter*>(chooseOffer(all, file, format_id));
}

const SpectraImporter* Registry::spectraImporterFor(const std::filesystem::path& file,
                                                    const std::optional<std::string>& format_id) const {
    std::vector<Offer> all;
    for (const auto& loaded : m_plugins) addOffers(all, loaded.plugin->spectraImporters());
    return static_cast<const SpectraImporter*>(chooseOffer(all, file, format_id));
}

const IngredientImporter* Registry::ingredientImporterFor(const std::filesystem::path& file,
                                                          const std::optional<std::string>& format_id) const {
    std::vector<Offer> all;
    for (const auto& loaded : m_plugins) addOffers(all, loaded.plugin->ingredientImporters());
    return static_cast<const IngredientImporter*>(chooseOffer(all, file, format_id));
}

ImporterChoice Registry::importerFor(const std::filesystem::path& file,
                                     const std::optional<std::string>& format_id) const {
    std::vector<Offer> all;
    for (const auto& loaded : m_plugins) addOffers(all, loaded.plugin->measurementImporters());
    const std::size_t measurement_offers = all.size();
    for (const auto& loaded : m_plugins) addOffers(all, loaded.plugin->spectraImporters());
    const std::size_t spectra_offers = all.size();
    for (const auto& loaded : m_plugins) addOffers(all, loaded.plugin->ingredientImporters());
    const void* chosen = chooseOffer(all, file, format_id);
    ImporterChoice choice;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].offer != chosen || chosen == nullptr) continue;
        if (i < measurement_offers)
            choice.measurement = static_cast<const MeasurementImporter*>(chosen);
        else if (i < spectra_offers)
            choice.spectra = static_cast<const SpectraImporter*>(chosen);
        else
            choice.ingredients = static_cast<const IngredientImporter*>(chosen);
        choice.plugin = ownerOf(chosen);
        break;
    }
    return choice;
}

const AppearanceExporter* Registry::exporterFor(const std::filesystem::path& file,
                                                const std::optional<std::string>& format_id) const {
    for (const auto& loaded : m_plugins)
        for (const auto* offer : loaded.plugin->exporters())
            if (format_id ? offer->format().id == *format_id : claimsExtension(offer->format(), file))
                return offer;
    return nullptr;
}

const MeasurementExporter* Registry::measurementExporterFor(const std::filesystem::path& file,
                                                            const std::optional<std::string>& format) const {
    return chooseContentExporter<MeasurementExporter>(
        m_plugins, [](const Plugin& p) { return p.measurementExporters(); }, file, format);
}

const SpectraExporter* Registry::spectraExporterFor(const std::filesystem::path& file,
                                                    const std::optional<std::string>& format) const {
    return chooseContentExporter<SpectraExporter>(
        m_plugins, [](const Plugin& p) { return p.spectraExporters(); }, file, format);
}

const IngredientExporter* Registry::ingredientExporterFor(const std::filesystem::path& file,
                                                          const std::optional<std::string>& format) const {
    return chooseContentExporter<IngredientExporter>(
        m_plugins, [](const Plugin& p) { return p.ingredientExporters(); }, file, format);
}

namespace {

template <typename Offer> bool offers(const std::vector<const Offer*>& list, const void* offer) {
    return std::find(list.begin(), list.end(), offer) != list.end();
}

}  // namespace

const LoadedPlugin* Registry::ownerOf(const void* offer) const {
    for (const auto& loaded : m_plugins) {
        const Plugin& p = *loaded.plugin;
        if (offers(p.measurementImporters(), offer) || offers(p.spectraImporters(), offer) ||
            offers(p.ingredientImporters(), offer) || offers(p.exporters(), offer) ||
            offers(p.measurementExporters(), offer) || offers(p.spectraExporters(), offer) ||
            offers(p.ingredientExporters(), offer))
            return &loaded;
    }
    return nullptr;
}

db::Measurement readMeasurementFile(const std::filesystem::path& file, const db::ImportOptions& options,
                                    std::size_t max_samples, const std::optional<std::string>& format_id) {
    const Registry& registry = Registry::global();
    const MeasurementImporter* importer =
        options.format ? nullptr : registry.measurementImporterFor(file, format_id);
    if (format_id && importer == nullptr)
        throw InputError("<argument>", "--format",
                         "no plugin reads measurements in format '" + *format_id + "'");
    const LoadedPlugin* owner = importer != nullptr ? registry.ownerOf(importer) : nullptr;
    if (owner == nullptr || owner->builtIn()) return db::readMeasurementFile(file, options);
    ReadOptions read;
    read.description = options.measurement;
    read.max_samples = max_samples;
    read.cgats = options.cgats;
    return importer->read(file, read);
}

}  // namespace paintlab::plugins
