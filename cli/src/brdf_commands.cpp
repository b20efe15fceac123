// `brdf`, `eval` and `multiangle`: the fast model from the command line.
// Options and JSON fields are a public contract (issue 3): extend, never rename.

#include "brdf_table_io.h"
#include "commands.h"

#include "paintlab/database/measurements.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/plugins/exchange.h"
#include "paintlab/plugins/registry.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

namespace paintlab::cli {

namespace {

using nlohmann::ordered_json;

struct BrdfOptions {
    std::string recipe;
    std::string preset = "standard";
    std::string out;
    std::string wi;
    std::string wo;
    double step_deg = 5.0;
    std::string object = "sphere";
    std::vector<std::string> geometries;  // multiangle --geometry
    bool json = false;
};

// Progress on stderr when a person is watching (a terminal); scripts get clean output.
ProgressCallback terminalProgress() {
    if (isatty(STDERR_FILENO) == 0) return {};
    return [](double fraction) {
        std::fprintf(stderr, "\rfast model: %3.0f%%", 100.0 * fraction);
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        return true;
    };
}

LayeredBrdf runFastModel(const BrdfOptions& o) {
    const Recipe recipe = loadRecipeFile(o.recipe);
    return computeLayeredBrdf(recipe, presetSettings(presetFromName(o.preset)), terminalProgress());
}

// "THETA,PHI" in degrees; theta in [0, 90).
Direction parseDirection(const std::string& text, const std::string& option) {
    std::istringstream in(text);
    double theta = std::numeric_limits<double>::quiet_NaN();
    double phi = std::numeric_limits<double>::quiet_NaN();
    char comma = 0;
    if (!(in >> theta >> comma >> phi) || comma != ',' || !(in >> std::ws).eof())
        throw InputError("<argument>", option, "'" + text + "' is not THETA,PHI in degrees (e.g. 45,0)");
    if (!std::isfinite(theta) || !std::isfinite(phi) || theta < 0.0 || theta >= 90.0)
        throw InputError("<argument>", option,
                         "theta " + std::to_string(theta) + " must be in [0, 90) degrees");
    return directionFromAnglesDeg(theta, phi);
}

// The fast model's settings as every output records them (plugins/exchange.h).
ordered_json settingsJson(const LayeredBrdf& brdf, const std::string& preset) {
    return ordered_json::parse(plugins::fastModelSettingsJson(brdf, preset));
}

// A plugin's exporter (not the built-in BRDF table, written below as before)
// that claims the --out file's extension, or nullptr.
const plugins::AppearanceExporter* pluginExporter(const std::string& out) {
    if (out.empty()) return nullptr;
    const plugins::Registry& registry = plugins::Registry::global();
    const plugins::AppearanceExporter* exporter = registry.exporterFor(out);
    const plugins::LoadedPlugin* owner = exporter != nullptr ? registry.ownerOf(exporter) : nullptr;
    return owner != nullptr && !owner->builtIn() ? exporter : nullptr;
}

int runBrdf(const BrdfOptions& o) {
    if (std::find(plugins::kExportObjects.begin(), plugins::kExportObjects.end(), o.object) ==
        plugins::kExportObjects.end()) {
        std::string message = "'" + o.object + "' is not an object; one of";
        for (std::string_view name : plugins::kExportObjects) message.append(" ").append(name);
        throw InputError("<argument>", "--object", message);
    }
    if (const plugins::AppearanceExporter* exporter = pluginExporter(o.out)) {
        const Recipe recipe = loadRecipeFile(o.recipe);
        const LayeredBrdf brdf =
            computeLayeredBrdf(recipe, presetSettings(presetFromName(o.preset)), terminalProgress());
        plugins::ExportOptions options;
        options.recipe_path = o.recipe;
        options.settings_json = plugins::fastModelSettingsJson(brdf, o.preset);
        options.step_deg = o.step_deg;
        options.object = o.object;
        const std::string report = exporter->write(recipe, brdf, o.out, options);
        if (!report.empty()) std::cerr << report << (report.back() == '\n' ? "" : "\n");
        std::cerr << "wrote " << o.out << " (" << exporter->format().id << ", " << brdf.wavelengthsNm().size()
                  << " bands, " << brdf.computeSeconds() << " s)\n";
        return 0;
    }
    const LayeredBrdf brdf = runFastModel(o);
    const bool csv = isCsvPath(o.out);
    // The same writer as `mc --table`, so the two files have one format.
    const std::string text = brdfTableText(brdf, o.recipe, settingsJson(brdf, o.preset), o.step_deg, csv);
    if (o.out.empty()) {
        std::cout << text;
        return 0;
    }
    writeTextFile(o.out, text, "--out");
    std::cerr << "wrote " << o.out << " (" << (csv ? "CSV" : "JSON") << ", " << brdf.wavelengthsNm().size()
              << " bands, " << brdf.computeSeconds() << " s)\n";
    return 0;
}

int runEval(const BrdfOptions& o) {
    const Direction wi = parseDirection(o.wi, "--wi");
    const Direction wo = parseDirection(o.wo, "--wo");
    const LayeredBrdf brdf = runFastModel(o);
    const auto f = brdf.eval(wi, wo);
    const auto specular = brdf.specularReflectance(wi.z);
    const auto wavelengths = brdf.wavelengthsNm();
    if (o.json) {
        ordered_json out;
        out["recipe"] = o.recipe;
        out["wi"] = o.wi;
        out["wo"] = o.wo;
        out["settings"] = settingsJson(brdf, o.preset);
        out["wavelengths_nm"] = std::vector<double>(wavelengths.begin(), wavelengths.end());
        out["brdf_per_sr"] = f;
        out["specular_reflectance"] = specular;
        std::cout << out.dump(2) << '\n';
    } else {
        std::printf("%10s %14s %14s\n", "lambda_nm", "f (1/sr)", "specular R");
        for (std::size_t b = 0; b < f.size(); ++b)
            std::printf("%10.1f %14.6g %14.6g\n", wavelengths[b], f[b], specular[b]);
    }
    return 0;
}

// The --geometry names as directions, each checked as a measurement's reading is.
std::vector<MultiAngleGeometry> requestedGeometries(const std::vector<std::string>& names) {
    std::vector<MultiAngleGeometry> out;
    for (const std::string& name : names) {
        const auto g = db::parseMultiAngleGeometry(name);
        if (!g)
            throw InputError("<argument>", "--geometry",
                             "'" + name + "' is not a geometry like 45as15, 15as-45 or 45as25az90");
        db::Measurement check;
        check.name = name;
        check.readings.push_back({g->illumination_deg, g->aspecular_deg, 0.0, 0.0, 0.0, {}, g->azimuth_deg});
        try {
            db::validateMeasurement(check, "<argument>");
        } catch (const InputError& e) {
            // "readings[0].azimuth_deg" -> "'45as25az200': azimuth_deg 200 deg is outside -180 to 180"
            std::string message = "'" + name + "': ";
            message.append(e.field().substr(e.field().rfind('.') + 1)).append(" ").append(e.detail());
            throw InputError("<argument>", "--geometry", message);
        }
        out.push_back(multiAngleDirections(g->illumination_deg, g->aspecular_deg, g->azimuth_deg));
    }
    return out;
}

int runMultiangle(const BrdfOptions& o) {
    const std::vector<MultiAngleGeometry> requested = requestedGeometries(o.geometries);
    const LayeredBrdf brdf = runFastModel(o);
    MultiAngleReport report = multiAngleColours(brdf);
    // --geometry: those geometries instead of the six; the flop index where its three are among them.
    double flop = report.flop_index;
    bool has_flop = true;
    if (!requested.empty()) {
        report.colours.clear();
        const ColourConditions conditions{.illuminant = report.illuminant, .observer = report.observer};
        for (const MultiAngleGeometry& g : requested)
            report.colours.push_back(multiAngleColour(brdf, g, conditions));
        const auto lightness = [&](double aspecular) -> std::optional<double> {
            for (const auto& c : report.colours)
                if (c.illumination_deg == kMultiAngleIlluminationDeg && c.aspecular_deg == aspecular &&
                    isInPlane(c.azimuth_deg))
                    return c.lab.L;
            return std::nullopt;
        };
        const auto L15 = lightness(15.0);
        const auto L45 = lightness(45.0);
        const auto L110 = lightness(110.0);
        has_flop = L15 && L45 && L110;
        flop = has_flop ? flopIndex(*L15, *L45, *L110) : 0.0;
    }
    const bool one_illumination =
        std::all_of(report.colours.begin(), report.colours.end(), [](const MultiAngleColour& c) {
            return c.illumination_deg == kMultiAngleIlluminationDeg;
        });
    if (o.json) {
        ordered_json out;
        out["recipe"] = o.recipe;
        out["illuminant"] = std::string(toString(report.illuminant));
        out["observer"] = std::string(toString(report.observer));
        if (one_illumination) out["illumination_deg"] = kMultiAngleIlluminationDeg;
        out["settings"] = settingsJson(brdf, o.preset);
        ordered_json geometries = ordered_json::array();
        for (const auto& c : report.colours) {
            ordered_json entry;
            if (!requested.empty()) {
                // Named geometries: each says where it is (the six standard ones are as before).
                entry["geometry"] =
                    db::multiAngleGeometryName(c.illumination_deg, c.aspecular_deg, c.azimuth_deg);
                entry["illumination_deg"] = c.illumination_deg;
            }
            entry["aspecular_deg"] = c.aspecular_deg;
            if (!isInPlane(c.azimuth_deg)) entry["azimuth_deg"] = c.azimuth_deg;
            entry["L"] = c.lab.L;
            entry["a"] = c.lab.a;
            entry["b"] = c.lab.b;
            entry["X"] = c.xyz.X;
            entry["Y"] = c.xyz.Y;
            entry["Z"] = c.xyz.Z;
            entry["reflectance_factor"] = c.reflectance_factor;
            geometries.push_back(std::move(entry));
        }
        out["geometries"] = std::move(geometries);
        if (has_flop) out["flop_index"] = flop;
        std::cout << out.dump(2) << '\n';
    } else {
        std::printf("CIELAB (%s, %s)%s, preset %s\n", std::string(toString(report.illuminant)).c_str(),
                    std::string(toString(report.observer)).c_str(),
                    one_illumination ? ", illumination 45 deg" : "", o.preset.c_str());
        std::printf("%10s %8s %8s %8s\n", "geometry", "L*", "a*", "b*");
        for (const auto& c : report.colours) {
            const std::string name =
                db::multiAngleGeometryName(c.illumination_deg, c.aspecular_deg, c.azimuth_deg);
            // The six standard ones as before; named geometries with room for "45as25az-90".
            std::printf("  %-*s %8.2f %8.2f %8.2f\n", requested.empty() ? 8 : 12, name.c_str(), c.lab.L,
                        c.lab.a, c.lab.b);
        }
        if (has_flop) std::printf("flop index %.2f\n", flop);
    }
    return 0;
}

void addCommon(CLI::App* command, BrdfOptions& o) {
    command->add_option("recipe", o.recipe, "Recipe JSON file")->required();
    command->add_option("--preset", o.preset, "Accuracy preset: preview, standard or reference")
        ->capture_default_str();
}

}  // namespace

void addBrdfCommands(CLI::App& app, CommandAction& action) {
    auto o = std::make_shared<BrdfOptions>();

    CLI::App* brdf = app.add_subcommand("brdf", "Tabulate the paint's spectral BRDF (fast model)");
    addCommon(brdf, *o);
    brdf->add_option("--out", o->out,
                     "Output file, .json or .csv, or a plugin's format such as .binary (MERL) or .gltf/.glb "
                     "(a painted object with a fitted glTF material; paintlab-cli plugins lists them) "
                     "(default: JSON on stdout)");
    brdf->add_option("--step", o->step_deg, "Angular step of the table in degrees")->capture_default_str();
    brdf->add_option("--object", o->object,
                     "The painted object of a scene format (.gltf, .glb): sphere, panel or car (the demo "
                     "scenes' car body)")
        ->capture_default_str();
    brdf->callback([o, &action] { action = [o] { return runBrdf(*o); }; });

    CLI::App* eval = app.add_subcommand("eval", "Spectral BRDF value (1/sr) for one pair of directions");
    addCommon(eval, *o);
    eval->add_option("--wi", o->wi, "Direction to the light: THETA,PHI in degrees")->required();
    eval->add_option("--wo", o->wo, "Direction to the viewer: THETA,PHI in degrees")->required();
    eval->add_flag("--json", o->json, "Print JSON");
    eval->callback([o, &action] { action = [o] { return runEval(*o); }; });

    CLI::App* multiangle = app.add_subcommand(
        "multiangle", "CIELAB at the multi-angle geometries 45as-15..110 and the flop index");
    addCommon(multiangle, *o);
    multiangle->add_option(
        "--geometry", o->geometries,
        "A geometry to report instead of the six standard ones, by its instrument name: "
        "45as15, 15as-45, or out of the plane of incidence 45as25az90 (the detector turned "
        "90 deg about the specular direction); repeatable");
    multiangle->add_flag("--json", o->json, "Print JSON");
    multiangle->callback([o, &action] { action = [o] { return runMultiangle(*o); }; });
}

}  // namespace paintlab::cli
