// `accuracy`: what accuracy costs in time. Every knob of the fast model and
// every preset against a converged reference, by the worst CIEDE2000 over the
// multi-angle geometries and the largest relative BRDF difference.

#include "commands.h"

#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace paintlab::cli {

namespace {

struct AccuracyOptions {
    std::string recipe;
    bool json = false;
};

struct Row {
    std::string knob;
    std::string value;
    FastModelSettings settings;
    double seconds = 0.0;
    double worst_de00 = 0.0;
};

double worstDeltaE(const MultiAngleReport& a, const MultiAngleReport& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.colours.size(); ++i)
        worst = std::max(worst, ciede2000(a.colours[i].lab, b.colours[i].lab));
    return worst;
}

int runAccuracy(const AccuracyOptions& o) {
    const Recipe recipe = loadRecipeFile(o.recipe);
    const FastModelSettings reference = presetSettings(Preset::Reference);
    const LayeredBrdf truth = computeLayeredBrdf(recipe, reference);
    const MultiAngleReport truth_colours = multiAngleColours(truth);

    std::vector<Row> rows;
    for (Preset p : {Preset::Preview, Preset::Standard})
        rows.push_back({"preset", std::string(presetName(p)), presetSettings(p)});
    // One knob at a time away from the standard preset, the others as standard.
    const FastModelSettings standard = presetSettings(Preset::Standard);
    const auto sweep = [&](const char* knob, std::initializer_list<double> values, auto&& set) {
        for (double v : values) {
            FastModelSettings s = standard;
            set(s, v);
            std::ostringstream label;
            label << v;
            rows.push_back({knob, label.str(), s});
        }
    };
    const auto whole = [](double v) { return static_cast<int>(v); };
    sweep("nodes", {8, 12, 16, 32}, [&](FastModelSettings& s, double v) { s.nodes = whole(v); });
    sweep("orders", {4, 8, 24, 32}, [&](FastModelSettings& s, double v) { s.orders = whole(v); });
    sweep("bands", {8, 24, 41}, [&](FastModelSettings& s, double v) { s.bands = whole(v); });
    sweep("max_start_tau", {1.0 / 16.0, 1.0 / 64.0, 1.0 / 1024.0},
          [](FastModelSettings& s, double v) { s.max_start_tau = v; });
    // The flake knobs (they matter only for recipes with flakes); quadrature: tilt x azimuth nodes.
    sweep("flake_table", {9, 17, 65}, [&](FastModelSettings& s, double v) { s.flake_table = whole(v); });
    sweep("flake_quadrature", {2, 4, 12}, [&](FastModelSettings& s, double v) {
        s.flake_polar = whole(v);
        s.flake_azimuth = whole(v);
    });
    sweep("flake_kernel_points_per_spread", {1, 2, 8},
          [](FastModelSettings& s, double v) { s.flake_kernel_points_per_spread = v; });
    for (Row& row : rows) {
        const LayeredBrdf brdf = computeLayeredBrdf(recipe, row.settings);
        row.seconds = brdf.computeSeconds();
        row.worst_de00 = worstDeltaE(multiAngleColours(brdf), truth_colours);
    }

    if (o.json) {
        nlohmann::ordered_json out;
        out["recipe"] = o.recipe;
        out["reference"] = {{"nodes", reference.nodes},
                            {"orders", reference.orders},
                            {"bands", reference.bands},
                            {"max_start_tau", reference.max_start_tau},
                            {"compute_seconds", truth.computeSeconds()}};
        out["rows"] = nlohmann::ordered_json::array();
        for (const Row& r : rows)
            out["rows"].push_back({{"knob", r.knob},
                                   {"value", r.value},
                                   {"seconds", r.seconds},
                                   {"worst_ciede2000", r.worst_de00}});
        std::cout << out.dump(2) << '\n';
    } else {
        std::printf("Reference: %d nodes, %d orders, %d bands, start tau %g: %.3f s\n", reference.nodes,
                    reference.orders, reference.bands, reference.max_start_tau, truth.computeSeconds());
        std::printf("%-31s %-10s %12s %18s\n", "knob", "value", "time (ms)", "worst dE00 (6 geo)");
        for (const Row& r : rows)
            std::printf("%-31s %-10s %12.2f %18.3f\n", r.knob.c_str(), r.value.c_str(), 1e3 * r.seconds,
                        r.worst_de00);
    }
    return 0;
}

}  // namespace

void addAccuracyCommand(CLI::App& app, CommandAction& action) {
    auto o = std::make_shared<AccuracyOptions>();
    CLI::App* accuracy = app.add_subcommand(
        "accuracy", "Error-vs-time table of every fast-model knob and preset against the reference");
    accuracy->add_option("recipe", o->recipe, "Recipe JSON file")->required();
    accuracy->add_flag("--json", o->json, "Print JSON");
    accuracy->callback([o, &action] { action = [o] { return runAccuracy(*o); }; });
}

}  // namespace paintlab::cli
