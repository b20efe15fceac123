#pragma once
// The plugin interface (issue 29; how to write a plugin: plugins/README.md).
//
// A plugin is a shared library libpaintlab-plugin-NAME.so exporting two plain
// C functions (after OpenImageIO's version integer and plain entry points):
//
//   extern "C" int paintlab_plugin_api_version();       // kApiVersion it was built with
//   extern "C" paintlab::plugins::Plugin* paintlab_plugin_create();  // new; the host owns it
//
// The host calls the first before anything else and refuses the file unless
// it returns kApiVersion: the classes below are C++ and only the same
// interface version may cross the boundary. kApiVersion changes whenever a
// class, a struct or a database/engine type below changes layout.
//
// A plugin offers measurement importers, spectra importers, exporters of
// a recipe's appearance and exporters of database content. Each names its format with an id unique among the
// loaded plugins ("merl-binary"); a second plugin claiming an id is refused.
// Errors in a user's file throw InputError naming the file and the field.
// No Qt type: the CLI and the GUI use the same plugins.

#include "paintlab/database/measurements.h"
#include "paintlab/database/spectra_files.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/recipe.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::plugins {

// 2: exporters of database content (measurements, spectra, ingredients), ingredient importers.
// 3: ExportOptions::object and ::progress, ExportCancelled; AppearanceExporter::write returns its report.
inline constexpr int kApiVersion = 3;

// How many leading bytes of a file a probe sees.
inline constexpr std::size_t kProbeBytes = 4096;

struct FormatInfo {
    std::string id;                       // unique among loaded plugins: "merl-binary", "measurement-csv"
    std::string description;              // one line for listings and file dialogs
    std::vector<std::string> extensions;  // lower case with the dot: ".binary"
    // An appearance exporter that writes a painted object (ExportOptions::object
    // applies; the GUI asks which): glTF. False for tabulated BRDFs.
    bool paints_object = false;
};

struct ReadOptions {
    // The measurement's description where the file has none (name, instrument,
    // sample, ...); an empty name means the file's stem.
    db::Measurement description;
    // BRDF formats with more points than a fit needs: at most this many
    // samples (0: the format's default, stated in its description).
    std::size_t max_samples = 0;
    db::CgatsOptions cgats;  // CGATS spectra: quantity, unit, source
};

// Reads one kind of measurement file into the database's Measurement (not stored).
class MeasurementImporter {
public:
    virtual ~MeasurementImporter() = default;
    virtual FormatInfo format() const = 0;
    // How sure the importer is that a file is its format, from its first bytes
    // (at most kProbeBytes) and its size: 0 no, 1 certain. Never throws.
    virtual double probe(std::string_view head, std::uintmax_t size) const = 0;
    // Throws InputError naming the file (and the field or record) for any problem.
    virtual db::Measurement read(const std::filesystem::path& file, const ReadOptions& options) const = 0;
};

// Reads named spectra (ingredient data) from a file.
class SpectraImporter {
public:
    virtual ~SpectraImporter() = default;
    virtual FormatInfo format() const = 0;
    virtual double probe(std::string_view head, std::uintmax_t size) const = 0;
    virtual std::vector<db::NamedSpectrum> read(const std::filesystem::path& file,
                                                const ReadOptions& options) const = 0;
};

// Reads ingredients (binders, pigments, flakes, substrates with their data) from a file.
class IngredientImporter {
public:
    virtual ~IngredientImporter() = default;
    virtual FormatInfo format() const = 0;
    virtual double probe(std::string_view head, std::uintmax_t size) const = 0;
    virtual std::vector<db::Ingredient> read(const std::filesystem::path& file,
                                             const ReadOptions& options) const = 0;
};

// The painted objects an exporter of a scene format can write (ExportOptions::object):
// a sphere, a flat panel, the demo scenes' car body (raymaps/scene_geometry.h).
inline constexpr std::array<std::string_view, 3> kExportObjects{"sphere", "panel", "car"};

struct ExportOptions {
    std::string recipe_path;        // where the recipe came from, for the file's provenance
    std::string settings_json;      // the fast model's settings as a JSON object ("{}" if none)
    double step_deg = 5.0;          // tabulated formats with a free grid: the angular step
    std::string object = "sphere";  // formats holding a painted object (glTF): one of kExportObjects
    // An exporter whose own work takes long (MERL's 1.46 million bins) reports
    // the fraction done; when this returns false it stops and throws
    // ExportCancelled, writing nothing. Empty: no progress. Called from any thread.
    ProgressCallback progress;
};

// Thrown by an exporter whose ExportOptions::progress asked it to stop.
class ExportCancelled : public Error {
public:
    ExportCancelled() : Error("export cancelled: nothing written") {}
};

// Writes a recipe's appearance, from its fast-model BRDF, to a file.
class AppearanceExporter {
public:
    virtual ~AppearanceExporter() = default;
    virtual FormatInfo format() const = 0;
    // Writes atomically (io/atomic_file.h) and returns what the user should
    // read about the file, one line each ("" for nothing; an approximation
    // says how far it is from the paint). Throws InputError naming the file
    // if it cannot be written or an option (the field) is not allowed, Error
    // for anything else.
    virtual std::string write(const Recipe& recipe, const LayeredBrdf& brdf,
                              const std::filesystem::path& file, const ExportOptions& options) const = 0;
};

// What an AppearanceExporter writes its file with: atomically
// (io/atomic_file.h), any failure an InputError naming the file.
inline void writeExportFile(const std::filesystem::path& file, std::string_view bytes) {
    try {
        io::writeFileAtomically(file, bytes);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(file.string(), "", e.what());
    }
}

// Writers of database content, what `db export` writes: the text (or bytes)
// of a file holding one measurement, named spectra or ingredients. Each
// throws InputError(<format id>, field, ...) for content its format cannot
// hold (two spectra on different grids in one CGATS table, a quote in a name).
class MeasurementExporter {
public:
    virtual ~MeasurementExporter() = default;
    virtual FormatInfo format() const = 0;
    virtual std::string text(const db::Measurement& measurement) const = 0;
};

class SpectraExporter {
public:
    virtual ~SpectraExporter() = default;
    virtual FormatInfo format() const = 0;
    virtual std::string text(const std::vector<db::NamedSpectrum>& spectra) const = 0;
};

class IngredientExporter {
public:
    virtual ~IngredientExporter() = default;
    virtual FormatInfo format() const = 0;
    virtual std::string text(const std::vector<db::Ingredient>& ingredients) const = 0;
};

// What a plugin's library hands over; the pointers it returns live as long as it.
class Plugin {
public:
    virtual ~Plugin() = default;
    virtual std::string name() const = 0;     // "merl"
    virtual std::string version() const = 0;  // the plugin's own version, "1.0.0"
    virtual std::vector<const MeasurementImporter*> measurementImporters() const { return {}; }
    virtual std::vector<const SpectraImporter*> spectraImporters() const { return {}; }
    virtual std::vector<const IngredientImporter*> ingredientImporters() const { return {}; }
    virtual std::vector<const AppearanceExporter*> exporters() const { return {}; }
    virtual std::vector<const MeasurementExporter*> measurementExporters() const { return {}; }
    virtual std::vector<const SpectraExporter*> spectraExporters() const { return {}; }
    virtual std::vector<const IngredientExporter*> ingredientExporters() const { return {}; }
};

}  // namespace paintlab::plugins

// For a plugin's two entry points: C linkage, visible although the rest of
// the library is hidden (see plugins/CMakeLists.txt, paintlab_add_plugin).
#define PAINTLAB_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
