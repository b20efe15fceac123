// The MaterialX plugin (libpaintlab-plugin-materialx.so): a recipe's
// appearance as a MaterialX document with an OpenPBR surface, the glTF
// material fitted to the fast model (engine approx/) mapped to OpenPBR's
// inputs. The write returns the ΔE00 left at the six multi-angle
// geometries; the document carries it. The format and the mapping:
// mtlx_format.h.

#include "mtlx_format.h"

#include "paintlab/engine/approx/material_fit.h"
#include "paintlab/plugins/plugin.h"

namespace paintlab::plugins::materialx {

namespace {

class MtlxExporter final : public AppearanceExporter {
public:
    FormatInfo format() const override {
        return {
            "mtlx", "MaterialX 1.39 with an OpenPBR surface fitted to the fast model (via glTF)", {".mtlx"}};
    }
    std::string write(const Recipe& recipe, const LayeredBrdf& brdf, const std::filesystem::path& file,
                      const ExportOptions& options) const override {
        const approx::MaterialFit fit = approx::fitGltfMaterial(recipe, brdf);
        writeExportFile(file,
                        mtlxText(openPbrFromGltf(fit.material), fit, {recipe.name, options.recipe_path}));
        return approx::deltaESummary(fit, kModelName);
    }
};

class MtlxPlugin final : public Plugin {
public:
    std::string name() const override { return "materialx"; }
    std::string version() const override { return "1.0.0"; }
    std::vector<const AppearanceExporter*> exporters() const override { return {&m_exporter}; }

private:
    MtlxExporter m_exporter;
};

}  // namespace

}  // namespace paintlab::plugins::materialx

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() {
    return new paintlab::plugins::materialx::MtlxPlugin();
}
