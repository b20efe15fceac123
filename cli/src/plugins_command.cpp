// `plugins [--json]`: the formats the registry offers (plugins/registry.h):
// each plugin with its version and API version, what it imports and exports,
// the folders searched, and every refused file with the reason.

#include "commands.h"

#include "paintlab/plugins/registry.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace paintlab::cli {

namespace {

using nlohmann::ordered_json;

template <typename Offer> ordered_json offersJson(const std::vector<const Offer*>& offers) {
    ordered_json out = ordered_json::array();
    for (const Offer* offer : offers) {
        const plugins::FormatInfo info = offer->format();
        out.push_back({{"id", info.id}, {"description", info.description}, {"extensions", info.extensions}});
    }
    return out;
}

template <typename Offer> void printOffers(const char* what, const std::vector<const Offer*>& offers) {
    for (const Offer* offer : offers) {
        const plugins::FormatInfo info = offer->format();
        std::cout << "    " << what << ' ' << info.id << " (";
        for (std::size_t i = 0; i < info.extensions.size(); ++i)
            std::cout << (i > 0 ? " " : "") << info.extensions[i];
        std::cout << "): " << info.description << '\n';
    }
}

int runPlugins(bool json) {
    const plugins::Registry& registry = plugins::Registry::global();
    const auto search_path = plugins::Registry::defaultSearchPath();
    if (json) {
        ordered_json out;
        out["api_version"] = plugins::kApiVersion;
        out["search_path"] = ordered_json::array();
        for (const auto& folder : search_path) out["search_path"].push_back(folder.string());
        out["plugins"] = ordered_json::array();
        for (const auto& loaded : registry.plugins())
            out["plugins"].push_back(
                {{"name", loaded.name},
                 {"version", loaded.version},
                 {"api_version", loaded.api_version},
                 {"built_in", loaded.builtIn()},
                 {"file", loaded.file.string()},
                 {"measurement_importers", offersJson(loaded.plugin->measurementImporters())},
                 {"spectra_importers", offersJson(loaded.plugin->spectraImporters())},
                 {"ingredient_importers", offersJson(loaded.plugin->ingredientImporters())},
                 {"exporters", offersJson(loaded.plugin->exporters())},
                 {"measurement_exporters", offersJson(loaded.plugin->measurementExporters())},
                 {"spectra_exporters", offersJson(loaded.plugin->spectraExporters())},
                 {"ingredient_exporters", offersJson(loaded.plugin->ingredientExporters())}});
        out["refused"] = ordered_json::array();
        for (const auto& refusal : registry.refusals()) {
            ordered_json entry{{"file", refusal.file.string()}, {"reason", refusal.reason}};
            // What the plugin claims, from its metadata sidecar (read without loading it).
            if (refusal.metadata)
                entry["metadata"] = ordered_json::parse(plugins::pluginMetadataJson(*refusal.metadata));
            out["refused"].push_back(std::move(entry));
        }
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::cout << "Plugin API version " << plugins::kApiVersion << "; searched:";
    for (const auto& folder : search_path) std::cout << ' ' << folder.string();
    std::cout << "\nPlugins (" << registry.plugins().size() << "):\n";
    for (const auto& loaded : registry.plugins()) {
        std::cout << "  " << loaded.name << ' ' << loaded.version << " ("
                  << (loaded.builtIn() ? std::string("built in") : loaded.file.string()) << ")\n";
        printOffers("import measurement", loaded.plugin->measurementImporters());
        printOffers("import spectra", loaded.plugin->spectraImporters());
        printOffers("import ingredients", loaded.plugin->ingredientImporters());
        printOffers("export", loaded.plugin->exporters());
        printOffers("export measurement", loaded.plugin->measurementExporters());
        printOffers("export spectra", loaded.plugin->spectraExporters());
        printOffers("export ingredients", loaded.plugin->ingredientExporters());
    }
    std::cout << "Refused (" << registry.refusals().size() << "):\n";
    for (const auto& refusal : registry.refusals()) {
        std::cout << "  " << refusal.file.string() << ": " << refusal.reason << '\n';
        if (!refusal.metadata) continue;
        std::cout << "    claims (metadata): " << refusal.metadata->name << ' ' << refusal.metadata->version;
        for (const auto& claim : refusal.metadata->formats)
            std::cout << "; " << claim.kind << ' ' << claim.id;
        std::cout << '\n';
    }
    return 0;
}

}  // namespace

void addPluginsCommand(CLI::App& app, CommandAction& action) {
    auto json = std::make_shared<bool>(false);
    CLI::App* command = app.add_subcommand(
        "plugins", "List the file-format plugins: versions, what each imports and exports, what was refused");
    command->add_flag("--json", *json, "Print the list as JSON");
    command->callback([json, &action] { action = [json] { return runPlugins(*json); }; });
}

}  // namespace paintlab::cli
