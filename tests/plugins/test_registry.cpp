// The plugin registry: loading from a folder, the refusals (another API
// version, a missing entry point, a format claimed twice, a file that is no
// library), and that the rest keep working after a refusal.

#include "merl_format.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

namespace paintlab::plugins {
namespace {

const Refusal* refusalOf(const Registry& registry, const std::string& file_part) {
    for (const auto& refusal : registry.refusals())
        if (refusal.file.string().find(file_part) != std::string::npos) return &refusal;
    return nullptr;
}

TEST(Registry, BuiltInFormatsAreThereWithoutAnyLibrary) {
    const Registry registry;
    ASSERT_EQ(registry.plugins().size(), 1u);
    EXPECT_TRUE(registry.plugins()[0].builtIn());
    EXPECT_TRUE(registry.refusals().empty());
    EXPECT_NE(registry.exporterFor("table.csv"), nullptr);
    EXPECT_EQ(registry.exporterFor("table.csv")->format().id, "brdf-table-csv");
    EXPECT_EQ(registry.exporterFor("x.binary"), nullptr);
    EXPECT_EQ(registry.spectraImporterFor("any.it8", std::string("spectra-cgats"))->format().id,
              "spectra-cgats");
}

TEST(Registry, LoadsTheMerlPluginFromTheBuildTree) {
    Registry registry;
    registry.loadFolder(PAINTLAB_TEST_PLUGIN_DIR);
    EXPECT_TRUE(registry.refusals().empty());
    const auto merl = std::find_if(registry.plugins().begin(), registry.plugins().end(),
                                   [](const LoadedPlugin& p) { return p.name == "merl"; });
    ASSERT_NE(merl, registry.plugins().end());
    EXPECT_EQ(merl->api_version, kApiVersion);
    EXPECT_EQ(merl->file.filename(), "libpaintlab-plugin-merl.so");
    const auto* exporter = registry.exporterFor("paint.BINARY");  // extensions match in any case
    ASSERT_NE(exporter, nullptr);
    EXPECT_EQ(registry.ownerOf(exporter), &*merl);
}

TEST(Registry, RefusesBadPluginsByFileAndReasonAndKeepsTheOthers) {
    Registry registry;
    registry.loadFolder(PAINTLAB_TEST_PLUGIN_DIR);
    const std::size_t good = registry.plugins().size();  // the built-in and the build's plugins
    ASSERT_GE(good, 2u);
    registry.loadFolder(PAINTLAB_TEST_BAD_PLUGIN_DIR);
    const auto junk = std::filesystem::temp_directory_path() / "libpaintlab-plugin-junk.so";
    {
        std::ofstream out(junk, std::ios::binary);
        out << "not an ELF file";
    }
    EXPECT_FALSE(registry.loadFile(junk));
    std::filesystem::remove(junk);

    ASSERT_EQ(registry.refusals().size(), 4u);
    const Refusal* wrong_api = refusalOf(registry, "libpaintlab-plugin-bad-wrong_api.so");
    ASSERT_NE(wrong_api, nullptr);
    EXPECT_NE(wrong_api->reason.find("API version 999"), std::string::npos) << wrong_api->reason;
    const Refusal* no_create = refusalOf(registry, "libpaintlab-plugin-bad-no_create.so");
    ASSERT_NE(no_create, nullptr);
    EXPECT_NE(no_create->reason.find("paintlab_plugin_create"), std::string::npos) << no_create->reason;
    const Refusal* duplicate = refusalOf(registry, "libpaintlab-plugin-bad-duplicate.so");
    ASSERT_NE(duplicate, nullptr);
    EXPECT_NE(duplicate->reason.find("merl-binary"), std::string::npos) << duplicate->reason;
    EXPECT_NE(duplicate->reason.find("libpaintlab-plugin-merl.so"), std::string::npos) << duplicate->reason;
    const Refusal* not_elf = refusalOf(registry, "libpaintlab-plugin-junk.so");
    ASSERT_NE(not_elf, nullptr);
    EXPECT_NE(not_elf->reason.find("cannot be loaded"), std::string::npos) << not_elf->reason;

    // The same plugins, and the MERL format is the MERL plugin's, not the impostor's.
    EXPECT_EQ(registry.plugins().size(), good);
    const auto file = std::filesystem::temp_directory_path() / "paintlab_registry_probe.binary";
    io::writeFileAtomically(file, merl::encode(merl::Table{}));  // zeros: a valid MERL file
    const auto* importer = registry.measurementImporterFor(file);
    ASSERT_NE(importer, nullptr);
    EXPECT_EQ(registry.ownerOf(importer)->name, "merl");
    std::filesystem::remove(file);
}

// Every plugin of the build has a sidecar, and it says what the loaded plugin offers.
TEST(Registry, MetadataSidecarsSayWhatThePluginsOffer) {
    Registry registry;
    registry.loadFolder(PAINTLAB_TEST_PLUGIN_DIR);
    std::size_t libraries = 0;
    for (const auto& loaded : registry.plugins()) {
        if (loaded.builtIn()) continue;
        ++libraries;
        const auto metadata = readPluginMetadata(loaded.file);
        ASSERT_TRUE(metadata) << loaded.file << ": no sidecar " << metadataFileOf(loaded.file);
        EXPECT_EQ(*metadata, metadataOf(*loaded.plugin, loaded.api_version)) << loaded.file;
        EXPECT_FALSE(metadata->formats.empty());
    }
    EXPECT_GE(libraries, 2u);  // merl and multiangle at least
    // The wrong-API plugin is refused from its sidecar, which lists its claims.
    registry.loadFolder(PAINTLAB_TEST_BAD_PLUGIN_DIR);
    const auto refused =
        std::find_if(registry.refusals().begin(), registry.refusals().end(), [](const Refusal& r) {
            return r.file.filename() == "libpaintlab-plugin-bad-wrong_api.so";
        });
    ASSERT_NE(refused, registry.refusals().end());
    ASSERT_TRUE(refused->metadata);
    EXPECT_EQ(refused->metadata->formats.at(0).id, "wrong-api-format");
    EXPECT_NE(refused->reason.find("libpaintlab-plugin-bad-wrong_api.json"), std::string::npos)
        << refused->reason;
}

// A sidecar that is not valid metadata refuses its library, naming the sidecar and the field.
TEST(Registry, ABrokenSidecarRefusesItsLibrary) {
    const auto folder = std::filesystem::temp_directory_path() / "paintlab_broken_sidecar";
    std::filesystem::create_directories(folder);
    const auto library = folder / "libpaintlab-plugin-merl.so";
    std::filesystem::copy_file(std::filesystem::path(PAINTLAB_TEST_PLUGIN_DIR) / "libpaintlab-plugin-merl.so",
                               library, std::filesystem::copy_options::overwrite_existing);
    io::writeFileAtomically(metadataFileOf(library),
                            R"({"name": "merl", "version": "1", "api_version": "two", "formats": []})");
    Registry registry;
    EXPECT_FALSE(registry.loadFile(library));
    ASSERT_EQ(registry.refusals().size(), 1u);
    const std::string& reason = registry.refusals().front().reason;
    EXPECT_NE(reason.find("unreadable metadata"), std::string::npos) << reason;
    EXPECT_NE(reason.find("api_version"), std::string::npos) << reason;
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace paintlab::plugins
