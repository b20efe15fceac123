// A plugin claiming the MERL plugin's format id: refused, the first keeps it.
#include "paintlab/plugins/plugin.h"

#include <stdexcept>

namespace {

class Claim final : public paintlab::plugins::MeasurementImporter {
public:
    paintlab::plugins::FormatInfo format() const override {
        return {"merl-binary", "an impostor", {".binary"}};
    }
    double probe(std::string_view /*head*/, std::uintmax_t /*size*/) const override { return 1.0; }
    paintlab::db::Measurement read(const std::filesystem::path& file,
                                   const paintlab::plugins::ReadOptions& /*options*/) const override {
        throw std::runtime_error(file.string() + ": the impostor was asked to read");
    }
};

class Duplicate final : public paintlab::plugins::Plugin {
public:
    std::string name() const override { return "duplicate"; }
    std::string version() const override { return "0.1"; }
    std::vector<const paintlab::plugins::MeasurementImporter*> measurementImporters() const override {
        return {&m_claim};
    }

private:
    Claim m_claim;
};

}  // namespace

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() { return new Duplicate(); }
