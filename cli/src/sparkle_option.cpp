// `--sparkle on|off|plan`, `--scene-unit`, `--plan` (sparkle_option.h).

#include "sparkle_option.h"

#include "paintlab/engine/error.h"
#include "paintlab/raymaps/planned_relight.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <utility>

namespace paintlab::cli {

void addSparkleOptions(CLI::App* command, SparkleOption& o) {
    command
        ->add_option("--sparkle", o.mode,
                     "Flake glints: on, off, or plan (on where the planner finds them visible)")
        ->check(CLI::IsMember({"on", "off", "plan"}))
        ->each([&o](const std::string&) { o.mode_given = true; })
        ->capture_default_str();
    command
        ->add_option("--scene-unit", o.scene_unit_m,
                     "One scene unit in metres (sparkle and plan: pixel footprints; default: the ray map's, "
                     "1 for maps written before the header held it)")
        ->each([&o](const std::string&) { o.scene_unit_given = true; })
        ->capture_default_str();
    command->add_flag("--plan", o.plan,
                      "Run the effect plan: the fast model at the plan's orders, bands and slices, sparkle "
                      "where the plan finds it visible (an explicit --sparkle overrides that)");
}

EffectPlan planForMap(const SparkleOption& o, const raymaps::RayMap& map, const Recipe& recipe,
                      Preset preset) {
    return raymaps::planForRayMap(map, recipe, preset, {.scene_unit_m = o.sceneUnit()});
}

std::vector<std::string> appliedPlanLines(const SparkleOption& o, const EffectPlan& plan) {
    std::vector<std::string> lines;
    for (const AppliedDecision& a : appliedDecisions(plan)) {
        std::string applied = a.applied;
        double accepted = a.accepted_error_de;
        if (a.effect == "sparkle") {
            const std::string mode = o.effectiveMode();
            if (mode == "on" || mode == "off") {
                applied = mode;
                applied.append(" (--sparkle ")
                    .append(mode)
                    .append("; the plan: ")
                    .append(a.applied)
                    .append(")");
            }
            if (mode == "on") accepted = 0.0;
            if (mode == "off")
                for (const auto& d : plan.decisions)
                    if (d.effect == "sparkle") accepted = d.skip_error_de;
        } else if (!o.plan) {
            continue;  // --sparkle plan alone: the fast model runs at the preset's settings
        }
        char text[512];
        std::snprintf(text, sizeof text, "  %-12s %-40s accepted dE00 %.3g: ", a.effect.c_str(),
                      applied.c_str(), accepted);
        std::string line = text;
        line.append(a.reason);
        lines.push_back(std::move(line));
    }
    return lines;
}

std::string applySparkle(const SparkleOption& o, const raymaps::RayMap& map, const Recipe& recipe,
                         const EffectPlan* plan, raymaps::RgbImage& image) {
    const std::string mode = o.effectiveMode();
    if (mode == "off") return "";
    if (mode == "plan") {
        if (plan == nullptr) throw Error("applySparkle: --sparkle plan without a plan");
        if (!plan->sparkle) return "sparkle: skipped by the plan (" + raymaps::sparkleSkipReason(*plan) + ")";
    }
    const raymaps::SparklePassStats s = raymaps::addRecipeSparkle(map, recipe, image, o.sceneUnit());
    char text[256];
    std::snprintf(text, sizeof text,
                  "sparkle: %llu paint pixels, %llu with glints, %.3g glinting flakes per pixel, %.1f ms",
                  static_cast<unsigned long long>(s.pixels), static_cast<unsigned long long>(s.glint_pixels),
                  s.mean_glints, 1e3 * s.seconds);
    return text;
}

}  // namespace paintlab::cli
