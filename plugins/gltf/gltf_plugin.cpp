// The glTF plugin (libpaintlab-plugin-gltf.so): a painted object (sphere,
// panel or the demo car body, ExportOptions::object) as a glTF 2.0 file,
// .gltf (JSON, buffer embedded) or .glb (binary), with a physically based
// material fitted to the recipe's fast-model BRDF (engine approx/). The
// write returns the ΔE00 left at the six multi-angle geometries; the file's
// material carries it in `extras`. The format: gltf_format.h.

#include "gltf_format.h"

#include "paintlab/engine/approx/material_fit.h"
#include "paintlab/engine/error.h"
#include "paintlab/plugins/plugin.h"

namespace paintlab::plugins::gltf {

namespace {

class GltfExporter final : public AppearanceExporter {
public:
    explicit GltfExporter(bool binary) : m_binary(binary) {}
    FormatInfo format() const override {
        if (m_binary)
            return {"glb",
                    "glTF 2.0 binary: a painted object (--object) with a fitted PBR material",
                    {".glb"},
                    true};
        return {"gltf",
                "glTF 2.0: a painted object (--object) with a fitted PBR material, buffer embedded",
                {".gltf"},
                true};
    }
    std::string write(const Recipe& recipe, const LayeredBrdf& brdf, const std::filesystem::path& file,
                      const ExportOptions& options) const override {
        const raymaps::TriangleMesh mesh = objectMesh(options.object);  // a bad name fails before the fit
        const approx::MaterialFit fit = approx::fitGltfMaterial(recipe, brdf);
        const GltfAsset asset =
            makeAsset(mesh, fit, {recipe.name, options.recipe_path, options.settings_json, options.object});
        const std::string bytes = m_binary ? glbBytes(asset) : gltfText(asset);
        writeExportFile(file, bytes);
        return approx::deltaESummary(fit, "glTF");
    }

private:
    bool m_binary;
};

class GltfPlugin final : public Plugin {
public:
    std::string name() const override { return "gltf"; }
    std::string version() const override { return "1.0.0"; }
    std::vector<const AppearanceExporter*> exporters() const override { return {&m_text, &m_binary}; }

private:
    GltfExporter m_text{false};
    GltfExporter m_binary{true};
};

}  // namespace

}  // namespace paintlab::plugins::gltf

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() {
    return new paintlab::plugins::gltf::GltfPlugin();
}
