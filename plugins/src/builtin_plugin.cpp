// The built-in plugin: the formats PaintLab has always read and written
// (measurements, spectra and ingredients in and out of the database, the BRDF table),
// behind the plugin interface so that listings and file choosers see one
// registry. Each offer calls the one implementation of its format (database
// measurement_files.h, spectra_files.h; engine fast_model/brdf_table_io.h).

#include "paintlab/database/exchange.h"
#include "paintlab/database/ingredient_csv.h"
#include "paintlab/database/ingredient_json.h"
#include "paintlab/database/measurement_files.h"
#include "paintlab/engine/fast_model/brdf_table_io.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/registry.h"

#include "json_reader.h"

#include <memory>

namespace paintlab::plugins {

namespace {

// As the database's import (exchange.cpp): far above any real file, refused before reading.
constexpr std::size_t kMaxTextBytes = std::size_t{64} << 20;

std::string_view firstLine(std::string_view head) { return head.substr(0, head.find('\n')); }

// One description per format, for its importer and its exporter (they share the id).
FormatInfo measurementFormat(bool csv) {
    if (csv)
        return {
            "measurement-csv", "instrument CSV table (multi-angle CIELAB/spectra or BRDF samples)", {".csv"}};
    return {"measurement-json", "PaintLab measurement JSON (multi-angle or BRDF)", {".json"}};
}

FormatInfo ingredientFormat(bool csv) {
    if (csv) return {"ingredients-csv", "ingredients CSV (one record per spectrum sample)", {".csv"}};
    return {"ingredients-json", "PaintLab ingredients JSON", {".json"}};
}

FormatInfo spectraFormat(db::FileFormat format) {
    switch (format) {
    case db::FileFormat::Json:
        return {"spectra-json", "PaintLab spectra JSON", {".json"}};
    case db::FileFormat::Csv:
        return {"spectra-csv", "spectra CSV (one row per sample)", {".csv"}};
    default:
        return {"spectra-cgats",
                "CGATS/IT8 spectral data (lcms2; written as one CGATS.17 table)",
                {".cgats", ".it8", ".txt", ".ti3"}};
    }
}

class MeasurementFileImporter final : public MeasurementImporter {
public:
    explicit MeasurementFileImporter(db::FileFormat format) : m_format(format) {}
    FormatInfo format() const override { return measurementFormat(m_format == db::FileFormat::Csv); }
    double probe(std::string_view head, std::uintmax_t /*size*/) const override {
        if (m_format == db::FileFormat::Json)
            return head.find("\"paintlab-measurement\"") != std::string_view::npos ? 0.9 : 0.0;
        const std::string_view line = firstLine(head);
        for (const std::string_view column : {"theta_i_deg", "aspecular_deg", "geometry"})
            if (line.find(column) != std::string_view::npos) return 0.8;
        return 0.0;
    }
    db::Measurement read(const std::filesystem::path& file, const ReadOptions& options) const override {
        db::ImportOptions import;
        import.format = m_format;
        import.measurement = options.description;
        return db::readMeasurementFile(file, import);
    }

private:
    db::FileFormat m_format;
};

class SpectraFileImporter final : public SpectraImporter {
public:
    explicit SpectraFileImporter(db::FileFormat format) : m_format(format) {}
    FormatInfo format() const override { return spectraFormat(m_format); }
    double probe(std::string_view head, std::uintmax_t /*size*/) const override {
        switch (m_format) {
        case db::FileFormat::Json:
            return head.find("\"paintlab-spectra\"") != std::string_view::npos ? 0.9 : 0.0;
        case db::FileFormat::Csv: {
            const std::string_view line = firstLine(head);
            return line.find("quantity") != std::string_view::npos &&
                           line.find("wavelength_nm") != std::string_view::npos
                       ? 0.8
                       : 0.0;
        }
        default:
            return head.find("BEGIN_DATA_FORMAT") != std::string_view::npos ? 0.8 : 0.0;
        }
    }
    std::vector<db::NamedSpectrum> read(const std::filesystem::path& file,
                                        const ReadOptions& options) const override {
        const std::string source = file.string();
        const std::string text = jsonio::readBoundedTextFile(file, kMaxTextBytes);
        if (m_format == db::FileFormat::Json) return db::parseSpectraJson(text, source);
        if (m_format == db::FileFormat::Csv) return db::parseSpectraCsv(text, source);
        return db::parseSpectraCgats(text, source, options.cgats);
    }

private:
    db::FileFormat m_format;
};

class IngredientFileImporter final : public IngredientImporter {
public:
    explicit IngredientFileImporter(bool csv) : m_csv(csv) {}
    FormatInfo format() const override { return ingredientFormat(m_csv); }
    double probe(std::string_view head, std::uintmax_t /*size*/) const override {
        if (!m_csv) return head.find("\"paintlab-ingredients\"") != std::string_view::npos ? 0.9 : 0.0;
        const std::string_view line = firstLine(head);
        return line.find("kind") != std::string_view::npos && line.find("spectrum") != std::string_view::npos
                   ? 0.8
                   : 0.0;
    }
    std::vector<db::Ingredient> read(const std::filesystem::path& file,
                                     const ReadOptions& /*options*/) const override {
        const std::string text = jsonio::readBoundedTextFile(file, kMaxTextBytes);
        return m_csv ? db::parseIngredientsCsv(text, file.string())
                     : db::parseIngredientsJson(text, file.string());
    }

private:
    bool m_csv;
};

class BrdfTableExporter final : public AppearanceExporter {
public:
    explicit BrdfTableExporter(bool csv) : m_csv(csv) {}
    FormatInfo format() const override {
        if (m_csv) return {"brdf-table-csv", "tabulated spectral BRDF, one row per direction pair", {".csv"}};
        return {"brdf-table-json", "tabulated spectral BRDF with settings and mirror reflectance", {".json"}};
    }
    std::string write(const Recipe& /*recipe*/, const LayeredBrdf& brdf, const std::filesystem::path& file,
                      const ExportOptions& options) const override {
        io::writeFileAtomically(
            file, brdfTableText(brdf, options.recipe_path, options.settings_json, options.step_deg, m_csv));
        return {};
    }

private:
    bool m_csv;
};

// `db export`: the database's own writers, one offer per kind and format.
class MeasurementFileExporter final : public MeasurementExporter {
public:
    explicit MeasurementFileExporter(bool csv) : m_csv(csv) {}
    FormatInfo format() const override { return measurementFormat(m_csv); }
    std::string text(const db::Measurement& measurement) const override {
        return m_csv ? db::measurementToCsv(measurement) : db::measurementToJson(measurement);
    }

private:
    bool m_csv;
};

class SpectraFileExporter final : public SpectraExporter {
public:
    explicit SpectraFileExporter(db::FileFormat format) : m_format(format) {}
    FormatInfo format() const override { return spectraFormat(m_format); }
    std::string text(const std::vector<db::NamedSpectrum>& spectra) const override {
        if (m_format == db::FileFormat::Json) return db::spectraToJson(spectra);
        if (m_format == db::FileFormat::Csv) return db::spectraToCsv(spectra);
        return db::spectraToCgats(spectra);
    }

private:
    db::FileFormat m_format;
};

class IngredientFileExporter final : public IngredientExporter {
public:
    explicit IngredientFileExporter(bool csv) : m_csv(csv) {}
    FormatInfo format() const override { return ingredientFormat(m_csv); }
    std::string text(const std::vector<db::Ingredient>& ingredients) const override {
        return m_csv ? db::ingredientsToCsv(ingredients) : db::ingredientsToJson(ingredients);
    }

private:
    bool m_csv;
};

class BuiltInPlugin final : public Plugin {
public:
    std::string name() const override { return "builtin"; }
    std::string version() const override { return PAINTLAB_PLUGINS_VERSION; }
    std::vector<const MeasurementImporter*> measurementImporters() const override {
        return {&m_measurement_json, &m_measurement_csv};
    }
    std::vector<const SpectraImporter*> spectraImporters() const override {
        return {&m_spectra_json, &m_spectra_csv, &m_spectra_cgats};
    }
    std::vector<const IngredientImporter*> ingredientImporters() const override {
        return {&m_ingredients_json, &m_ingredients_csv};
    }
    std::vector<const AppearanceExporter*> exporters() const override {
        return {&m_table_json, &m_table_csv};
    }
    std::vector<const MeasurementExporter*> measurementExporters() const override {
        return {&m_measurement_out_json, &m_measurement_out_csv};
    }
    std::vector<const SpectraExporter*> spectraExporters() const override {
        return {&m_spectra_out_json, &m_spectra_out_csv, &m_spectra_out_cgats};
    }
    std::vector<const IngredientExporter*> ingredientExporters() const override {
        return {&m_ingredients_out_json, &m_ingredients_out_csv};
    }

private:
    MeasurementFileImporter m_measurement_json{db::FileFormat::Json};
    MeasurementFileImporter m_measurement_csv{db::FileFormat::Csv};
    SpectraFileImporter m_spectra_json{db::FileFormat::Json};
    SpectraFileImporter m_spectra_csv{db::FileFormat::Csv};
    SpectraFileImporter m_spectra_cgats{db::FileFormat::Cgats};
    IngredientFileImporter m_ingredients_json{false};
    IngredientFileImporter m_ingredients_csv{true};
    BrdfTableExporter m_table_json{false};
    BrdfTableExporter m_table_csv{true};
    MeasurementFileExporter m_measurement_out_json{false};
    MeasurementFileExporter m_measurement_out_csv{true};
    SpectraFileExporter m_spectra_out_json{db::FileFormat::Json};
    SpectraFileExporter m_spectra_out_csv{db::FileFormat::Csv};
    SpectraFileExporter m_spectra_out_cgats{db::FileFormat::Cgats};
    IngredientFileExporter m_ingredients_out_json{false};
    IngredientFileExporter m_ingredients_out_csv{true};
};

}  // namespace

std::unique_ptr<Plugin> makeBuiltInPlugin() { return std::make_unique<BuiltInPlugin>(); }

}  // namespace paintlab::plugins
