// `plan SCENE.json RECIPE.json [--json]`: what the effect planner decides to
// simulate for this paint in this scene, and why (engine/plan.h, issue 7).
// Options and JSON fields are a public contract: extend, never rename.

#include "commands.h"
#include "helper_commands.h"

#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/scene.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

namespace paintlab::cli {

namespace {

using nlohmann::ordered_json;

struct PlanOptions {
    std::string scene;
    std::string recipe;
    std::string preset = "standard";
    double scene_unit_m = 1.0;
    bool json = false;
};

ordered_json sceneJson(const PlanScene& s) {
    ordered_json lights = ordered_json::array();
    for (const auto& l : s.lights)
        lights.push_back(
            {{"name", l.name}, {"irradiance_w_m2", l.irradiance_w_m2}, {"solid_angle_sr", l.solid_angle_sr}});
    return {{"lights", lights},
            {"environment_radiance", s.environment_radiance},
            {"environment_sharpness_deg", s.environment_sharpness_deg},
            {"footprint_min_um", s.footprint_min_um},
            {"footprint_max_um", s.footprint_max_um},
            {"viewing_distance_m", s.viewing_distance_m}};
}

int runPlan(const PlanOptions& o) {
    const Preset preset = presetFromName(o.preset);
    const raymaps::Scene scene = raymaps::loadSceneFile(o.scene);
    const Recipe recipe = loadRecipeFile(o.recipe);
    const PlanScene summary = raymaps::summariseScene(scene, {.scene_unit_m = o.scene_unit_m});
    const EffectPlan p = plan(recipe, summary, preset);
    if (o.json) {
        ordered_json decisions = ordered_json::array();
        for (const auto& d : p.decisions)
            decisions.push_back({{"effect", d.effect},
                                 {"simulate", d.simulate},
                                 {"setting", d.setting},
                                 {"accepted_error_de", d.accepted_error_de},
                                 {"skip_error_de", d.skip_error_de},
                                 {"reason", d.reason}});
        ordered_json out{{"scene_file", o.scene},
                         {"recipe_file", o.recipe},
                         {"preset", std::string(presetName(preset))},
                         {"tolerance_de", p.tolerance_de},
                         {"interference", p.interference},
                         {"sparkle", p.sparkle},
                         {"full_model", p.full_model},
                         {"fast_model",
                          {{"nodes", p.fast.nodes},
                           {"orders", p.fast.orders},
                           {"bands", p.fast.bands},
                           {"output_bands", p.fast.output_bands},
                           {"slices", p.fast.slices}}},
                         {"decisions", decisions},
                         {"scene", sceneJson(summary)}};
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::printf("plan for '%s' in %s (preset %s, tolerance dE00 %.2g per pixel, 99th percentile)\n",
                recipe.name.c_str(), o.scene.c_str(), std::string(presetName(preset)).c_str(),
                p.tolerance_de);
    std::printf("fast model: nodes %d, orders %d, bands %d (output %d), slices %d\n", p.fast.nodes,
                p.fast.orders, p.fast.bands, p.fast.output_bands, p.fast.slices);
    for (const auto& d : p.decisions)
        std::printf("  %-12s %-8s %-40s accepted dE00 %.3g\n               %s\n", d.effect.c_str(),
                    d.simulate ? "simulate" : "skip", d.setting.c_str(), d.accepted_error_de,
                    d.reason.c_str());
    return 0;
}

}  // namespace

void addPlanCommand(CLI::App& app, CommandAction& action) {
    auto o = std::make_shared<PlanOptions>();
    CLI::App* cmd = app.add_subcommand(kPlanCommand.name, kPlanCommand.description);
    cmd->add_option("scene", o->scene, "Scene JSON file")->required();
    cmd->add_option("recipe", o->recipe, "Recipe JSON file")->required();
    cmd->add_option("--preset", o->preset, "Accuracy preset: preview, standard or reference")
        ->capture_default_str();
    cmd->add_option("--scene-unit", o->scene_unit_m, "One scene unit in metres (pixel footprints)")
        ->capture_default_str();
    cmd->add_flag("--json", o->json, "JSON output");
    cmd->callback([o, &action] { action = [o] { return runPlan(*o); }; });
}

}  // namespace paintlab::cli
