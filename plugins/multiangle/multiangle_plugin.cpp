// The multi-angle plugin (libpaintlab-plugin-multiangle.so): CGATS exports of
// multi-angle spectrophotometers (X-Rite MA-T6/MA-T12/MA98, BYK-mac i) as
// multi-angle measurements with a spectrum and/or CIELAB per geometry. The
// format is multiangle_cgats.h; how a plugin is built is plugins/README.md.

#include "multiangle_cgats.h"

#include "paintlab/plugins/plugin.h"

namespace paintlab::plugins::multiangle {

namespace {

class CgatsImporter final : public MeasurementImporter {
public:
    FormatInfo format() const override {
        return {
            kFormatId,
            "multi-angle spectrophotometer CGATS (MA-T6/MA-T12/MA98, BYK-mac i): a spectrum and/or CIELAB "
            "per geometry (45as-15 ... 45as110, 15as-45 ... 15as80)",
            {".cgats", ".txt", ".it8"}};
    }
    double probe(std::string_view head, std::uintmax_t /*size*/) const override {
        return multiangle::probe(head);
    }
    db::Measurement read(const std::filesystem::path& file, const ReadOptions& options) const override {
        return readFile(file, options);
    }
};

class MultiAnglePlugin final : public Plugin {
public:
    std::string name() const override { return "multiangle"; }
    std::string version() const override { return "1.0.0"; }
    std::vector<const MeasurementImporter*> measurementImporters() const override { return {&m_importer}; }

private:
    CgatsImporter m_importer;
};

}  // namespace

}  // namespace paintlab::plugins::multiangle

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() {
    return new paintlab::plugins::multiangle::MultiAnglePlugin();
}
