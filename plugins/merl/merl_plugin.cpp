// The MERL plugin (libpaintlab-plugin-merl.so): MERL BRDF binaries in, as a
// BRDF measurement a recipe fit can use, and out, as the fast model's BRDF
// tabulated in linear sRGB for any renderer that reads MERL files. The format
// is merl_format.h; how a plugin is built is plugins/README.md.

#include "merl_format.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/plugin.h"

#include <array>
#include <cstdint>
#include <cstring>

namespace paintlab::plugins::merl {

namespace {

constexpr const char* kFormatId = "merl-binary";

class MerlImporter final : public MeasurementImporter {
public:
    FormatInfo format() const override {
        return {kFormatId,
                "MERL BRDF binary (isotropic RGB; subsampled, " + std::to_string(kDefaultSamples) +
                    " samples unless told)",
                {".binary"}};
    }
    double probe(std::string_view head, std::uintmax_t size) const override {
        if (head.size() < kHeaderBytes) return 0.0;
        std::array<std::int32_t, 3> dims{};
        std::memcpy(dims.data(), head.data(), kHeaderBytes);
        if (dims[0] != kThetaHalfBins || dims[1] != kThetaDiffBins || dims[2] != kPhiDiffBins) return 0.0;
        return size == kFileBytes ? 1.0 : 0.6;  // the right header on a wrong size: ours, to refuse clearly
    }
    db::Measurement read(const std::filesystem::path& file, const ReadOptions& options) const override {
        const Table table = readFile(file);
        db::Measurement description = options.description;
        if (description.name.empty()) description.name = file.stem().string();
        if (description.source.empty()) description.source = file.filename().string();
        if (description.instrument.empty()) description.instrument = "MERL BRDF binary";
        if (description.geometry.empty())
            description.geometry = "isotropic, 90 x 90 x 180 half/difference-angle bins (MERL)";
        db::Measurement m = toMeasurement(table, options.max_samples, std::move(description));
        if (m.samples.empty()) throw InputError(file.string(), "", "no measured entry above the horizon");
        db::validateMeasurement(m, file.string());
        return m;
    }
};

class MerlExporter final : public AppearanceExporter {
public:
    FormatInfo format() const override {
        return {kFormatId,
                "MERL BRDF binary: the fast model's BRDF in linear sRGB (mirror term excluded)",
                {".binary"}};
    }
    std::string write(const Recipe& /*recipe*/, const LayeredBrdf& brdf, const std::filesystem::path& file,
                      const ExportOptions& options) const override {
        const std::string bytes = encode(tabulate(brdf, options.progress));
        writeExportFile(file, bytes);
        return {};
    }
};

class MerlPlugin final : public Plugin {
public:
    std::string name() const override { return "merl"; }
    std::string version() const override { return "1.0.0"; }
    std::vector<const MeasurementImporter*> measurementImporters() const override { return {&m_importer}; }
    std::vector<const AppearanceExporter*> exporters() const override { return {&m_exporter}; }

private:
    MerlImporter m_importer;
    MerlExporter m_exporter;
};

}  // namespace

}  // namespace paintlab::plugins::merl

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() {
    return new paintlab::plugins::merl::MerlPlugin();
}
