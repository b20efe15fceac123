// A test plugin (never in a folder the programs search) with formats the CLI
// has never heard of, so the tests can show `db export` and `db import`
// choosing them from the registry: a measurement exporter (.tsv: geometry
// and CIELAB per line), an ingredient exporter (.names: one name per line)
// a spectra importer (.tsv: "name<TAB>wavelength:value ..." per line) and an
// ingredient importer (.ingr: PaintLab's ingredient JSON under another name).
#include "paintlab/database/ingredient_json.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/plugins/plugin.h"

#include <fstream>
#include <sstream>

namespace {

using namespace paintlab;  // NOLINT(google-build-using-namespace): a small test plugin

class MeasurementTsv final : public plugins::MeasurementExporter {
public:
    plugins::FormatInfo format() const override {
        return {"measurement-tsv", "geometry and CIELAB, tab-separated (test)", {".tsv"}};
    }
    std::string text(const db::Measurement& m) const override {
        std::string out = "geometry\tL\ta\tb\n";
        for (const auto& r : m.readings)
            out += db::multiAngleGeometryName(r.illumination_deg, r.aspecular_deg) + "\t" +
                   io::formatNumber(r.L) + "\t" + io::formatNumber(r.a) + "\t" + io::formatNumber(r.b) + "\n";
        return out;
    }
};

class IngredientNames final : public plugins::IngredientExporter {
public:
    plugins::FormatInfo format() const override {
        return {"ingredient-names", "names only (test)", {".names"}};
    }
    std::string text(const std::vector<db::Ingredient>& ingredients) const override {
        std::string out;
        for (const auto& i : ingredients) out += i.name + "\n";
        return out;
    }
};

class SpectraTsv final : public plugins::SpectraImporter {
public:
    plugins::FormatInfo format() const override {
        return {"spectra-tsv", "name, then wavelength:value pairs, tab-separated (test)", {".tsv"}};
    }
    double probe(std::string_view /*head*/, std::uintmax_t /*size*/) const override { return 0.5; }
    std::vector<db::NamedSpectrum> read(const std::filesystem::path& file,
                                        const plugins::ReadOptions& /*options*/) const override {
        std::ifstream in(file);
        std::vector<db::NamedSpectrum> out;
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream fields(line);
            db::NamedSpectrum s;
            std::getline(fields, s.name, '\t');
            std::vector<double> wavelengths;
            std::vector<double> values;
            std::string pair;
            while (fields >> pair) {
                const auto colon = pair.find(':');
                const auto w = io::parseFiniteNumber(pair.substr(0, colon));
                const auto v =
                    colon == std::string::npos ? std::nullopt : io::parseFiniteNumber(pair.substr(colon + 1));
                if (!w || !v)
                    throw InputError(file.string(), s.name, "'" + pair + "' is not wavelength:value");
                wavelengths.push_back(*w);
                values.push_back(*v);
            }
            s.quantity = "reflectance";
            s.info = {"1", "test plugin", ""};
            s.spectrum = Spectrum(std::move(wavelengths), std::move(values));
            out.push_back(std::move(s));
        }
        return out;
    }
};

class IngredientsIngr final : public plugins::IngredientImporter {
public:
    plugins::FormatInfo format() const override {
        return {"ingredients-ingr", "ingredient JSON named .ingr (test)", {".ingr"}};
    }
    double probe(std::string_view /*head*/, std::uintmax_t /*size*/) const override { return 0.0; }
    std::vector<db::Ingredient> read(const std::filesystem::path& file,
                                     const plugins::ReadOptions& /*options*/) const override {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        return db::parseIngredientsJson(text.str(), file.string());
    }
};

class TsvPlugin final : public plugins::Plugin {
public:
    std::string name() const override { return "tsv-test"; }
    std::string version() const override { return "0.1"; }
    std::vector<const plugins::SpectraImporter*> spectraImporters() const override { return {&m_spectra}; }
    std::vector<const plugins::IngredientImporter*> ingredientImporters() const override {
        return {&m_ingredients};
    }
    std::vector<const plugins::MeasurementExporter*> measurementExporters() const override {
        return {&m_measurement};
    }
    std::vector<const plugins::IngredientExporter*> ingredientExporters() const override {
        return {&m_names};
    }

private:
    SpectraTsv m_spectra;
    MeasurementTsv m_measurement;
    IngredientNames m_names;
    IngredientsIngr m_ingredients;
};

}  // namespace

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() { return new TsvPlugin(); }
