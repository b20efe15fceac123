// `slab`: Prahl's totals UR1, UT1, URU, UTU of a single raw-medium slab in air
// (adding-doubling core of the fast model, issue 3). Option names are a public contract.

#include "commands.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/layered/slab_totals.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

namespace paintlab::cli {

namespace {

struct SlabOptions {
    double albedo = 0.0;
    std::string optical_thickness;
    double g = 0.0;
    double n = 1.0;
    double slide_n = 1.0;
    double slide_n_bottom = 1.0;
    bool slide_n_bottom_given = false;  // otherwise the bottom slide is --slide-n
    double theta_deg = 0.0;
    int quad_points = 32;
    bool quad_points_given = false;
    std::string preset;  // empty: 32 nodes and a start of 1/4096, as before presets existed
    bool json = false;
};

// "inf" (any case, also "infinity") or a plain number using all of the text.
double parseThickness(const std::string& text) {
    std::string lower;
    for (char ch : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (lower == "inf" || lower == "+inf" || lower == "infinity")
        return std::numeric_limits<double>::infinity();
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || std::isinf(value))
        throw InputError("<argument>", "--optical-thickness",
                         "'" + text + "' is not a number (use a value >= 0 or 'inf')");
    return value;
}

// Engine field names -> the option that set them.
std::string optionName(const std::string& field) {
    if (field == "albedo") return "--albedo";
    if (field == "optical_thickness") return "--optical-thickness";
    if (field == "g") return "--g";
    if (field == "n_slab") return "--n";
    if (field == "n_slide_top") return "--slide-n";
    if (field == "n_slide_bottom") return "--slide-n-bottom";
    if (field == "theta_deg") return "--theta";
    if (field == "quad_points") return "--quad-points";
    if (field == "preset") return "--preset";
    return field;
}

int runSlab(const SlabOptions& options) {
    layered::SlabParameters p;
    p.albedo = options.albedo;
    p.optical_thickness = parseThickness(options.optical_thickness);
    p.g = options.g;
    p.n_slab = options.n;
    p.n_slide_top = options.slide_n;
    p.n_slide_bottom = options.slide_n_bottom_given ? options.slide_n_bottom : options.slide_n;
    p.theta_deg = options.theta_deg;
    p.quad_points = options.quad_points;
    layered::SlabTotals t;
    try {
        if (!options.preset.empty()) {
            // The fast model's angular settings of the preset; --quad-points, if given, overrides its nodes.
            const FastModelSettings preset = presetSettings(presetFromName(options.preset));
            if (!options.quad_points_given) p.quad_points = preset.nodes;
            p.max_start_tau = preset.max_start_tau;
        }
        t = layered::slabTotals(p);
    } catch (const InputError& e) {
        throw InputError("<argument>", optionName(e.field()), e.detail());
    }

    if (options.json) {
        nlohmann::ordered_json out;
        out["UR1"] = t.UR1;
        out["UT1"] = t.UT1;
        out["URU"] = t.URU;
        out["UTU"] = t.UTU;
        nlohmann::ordered_json in;
        in["albedo"] = p.albedo;
        if (std::isinf(p.optical_thickness))
            in["optical_thickness"] = "inf";
        else
            in["optical_thickness"] = p.optical_thickness;
        in["g"] = p.g;
        in["n"] = p.n_slab;
        in["slide_n"] = p.n_slide_top;
        in["slide_n_bottom"] = p.n_slide_bottom;
        in["theta_deg"] = p.theta_deg;
        in["quad_points"] = p.quad_points;
        if (!options.preset.empty()) in["preset"] = options.preset;
        in["max_start_tau"] = p.max_start_tau;
        out["inputs"] = in;
        std::cout << out.dump(2) << '\n';
    } else {
        std::cout << std::setprecision(6) << std::fixed << "UR1 " << t.UR1 << "  (collimated, reflected)\n"
                  << "UT1 " << t.UT1 << "  (collimated, transmitted)\n"
                  << "URU " << t.URU << "  (diffuse, reflected)\n"
                  << "UTU " << t.UTU << "  (diffuse, transmitted)\n";
    }
    return 0;
}

}  // namespace

void addSlabCommand(CLI::App& app, CommandAction& action) {
    auto options = std::make_shared<SlabOptions>();
    CLI::App* slab = app.add_subcommand(
        "slab",
        "Totals UR1, UT1, URU, UTU of a raw-medium slab in air (Prahl's adding-doubling definitions)");
    slab->add_option("--albedo", options->albedo, "Single-scattering albedo a, in [0, 1]")->required();
    slab->add_option("--optical-thickness", options->optical_thickness, "Optical thickness b >= 0, or 'inf'")
        ->required();
    slab->add_option("--g", options->g, "Henyey-Greenstein anisotropy g, in (-1, 1)")->required();
    slab->add_option("--n", options->n, "Refractive index of the slab, >= 1")->required();
    slab->add_option("--slide-n", options->slide_n,
                     "Index of non-absorbing glass slides on both faces (default 1: no slides)");
    CLI::Option* bottom =
        slab->add_option("--slide-n-bottom", options->slide_n_bottom,
                         "Index of the bottom slide if it differs from --slide-n (1: none)");
    slab->add_option("--theta", options->theta_deg,
                     "Incidence angle in air, degrees, in [0, 90) (default 0)");
    CLI::Option* quad_points = slab->add_option("--quad-points", options->quad_points,
                                                "Quadrature nodes per hemisphere, 4..512 (default 32, or the "
                                                "preset's; overrides the preset's if both are given)");
    slab->add_option(
        "--preset", options->preset,
        "Accuracy preset: preview, standard or reference (the fast model's nodes and starting layer)");
    slab->add_flag("--json", options->json, "Print the totals and inputs as JSON");
    slab->callback([options, bottom, quad_points, &action] {
        options->slide_n_bottom_given = bottom->count() > 0;
        options->quad_points_given = quad_points->count() > 0;
        action = [options] { return runSlab(*options); };
    });
}

}  // namespace paintlab::cli
