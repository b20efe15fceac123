// `--sparkle on|off|plan` (sparkle_option.h).

#include "sparkle_option.h"

#include "paintlab/engine/plan.h"
#include "paintlab/engine/sparkle.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/scene.h"
#include "paintlab/raymaps/sparkle_pass.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace paintlab::cli {

void addSparkleOptions(CLI::App* command, SparkleOption& o) {
    command
        ->add_option("--sparkle", o.mode,
                     "Flake glints: on, off, or plan (on where the planner finds them visible)")
        ->check(CLI::IsMember({"on", "off", "plan"}))
        ->capture_default_str();
    command
        ->add_option("--scene-unit", o.scene_unit_m, "One scene unit in metres (sparkle: pixel footprints)")
        ->capture_default_str();
}

std::string applySparkle(const SparkleOption& o, const raymaps::RayMap& map, const Recipe& recipe,
                         Preset preset, raymaps::RgbImage& image) {
    if (o.mode == "off") return "";
    std::string why;
    if (o.mode == "plan") {
        const EffectPlan p =
            plan(recipe, raymaps::summariseRayMap(map, {.scene_unit_m = o.scene_unit_m}), preset);
        for (const auto& d : p.decisions)
            if (d.effect == "sparkle") why = d.reason;
        if (!p.sparkle) return "sparkle: skipped by the plan (" + why + ")";
    }
    raymaps::SparklePassSettings settings;
    settings.scene_unit_m = o.scene_unit_m;
    if (!o.camera_scene.empty()) {
        const raymaps::Scene scene = raymaps::loadSceneFile(o.camera_scene);
        const int height = o.camera_height > 0 ? o.camera_height : scene.camera.height;
        settings.pixel_angle_rad = 2.0 *
                                   std::tan(0.5 * scene.camera.vertical_fov_deg * std::numbers::pi / 180.0) /
                                   std::max(1, height);
    }
    const SparkleModel model(recipe);
    const raymaps::SparklePassStats s = raymaps::addSparkle(map, model, image, settings);
    char text[256];
    std::snprintf(text, sizeof text,
                  "sparkle: %llu paint pixels, %llu with glints, %.3g glinting flakes per pixel, %.1f ms",
                  static_cast<unsigned long long>(s.pixels), static_cast<unsigned long long>(s.glint_pixels),
                  s.mean_glints, 1e3 * s.seconds);
    return text;
}

}  // namespace paintlab::cli
