// paintlab-plugin-metadata LIBRARY: writes the library's metadata sidecar
// (registry.h, PluginMetadata) from the loaded plugin itself, so that the
// sidecar says exactly what the plugin offers. The build runs it after each
// plugin links (paintlab_add_plugin); it is not installed.

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/registry.h"

#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
    using namespace paintlab::plugins;  // NOLINT(google-build-using-namespace): a small tool
    if (argc != 2) {
        std::cerr << "usage: paintlab-plugin-metadata LIBRARY\n";
        return 2;
    }
    try {
        const std::filesystem::path library =
            argv[1];  // NOLINT(cppcoreguidelines-pro-bounds-pointer-arithmetic)
        std::error_code ignored;
        std::filesystem::remove(metadataFileOf(library),
                                ignored);  // a stale sidecar must not refuse the new library
        Registry registry;
        if (!registry.loadFile(library)) {
            std::cerr << library.string() << ": " << registry.refusals().back().reason << '\n';
            return 1;
        }
        const LoadedPlugin& loaded = registry.plugins().back();
        paintlab::io::writeFileAtomically(metadataFileOf(library),
                                          pluginMetadataJson(metadataOf(*loaded.plugin, loaded.api_version)));
    } catch (const std::exception& e) {
        std::cerr << "paintlab-plugin-metadata: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
