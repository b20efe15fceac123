#pragma once
// `--sparkle on|off|plan`, `--scene-unit` and `--plan` of `relight` and
// `render` (issue 7): after the relight, the sparkle pass
// (raymaps/sparkle_pass.h) adds the paint's glints; `--sparkle plan` asks the
// effect planner (from the ray map's lights and footprints) whether they are
// visible at this scene's footprints first; `--plan` runs the whole plan:
// the fast model at the plan's settings (engine/plan.h, applyPlan) and
// sparkle as the plan says (unless --sparkle is given too: then --sparkle wins).

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace paintlab::cli {

struct SparkleOption {
    std::string mode = "off";  // on, off, plan
    bool mode_given = false;   // --sparkle was on the command line
    double scene_unit_m = 1.0;
    bool scene_unit_given = false;  // --scene-unit was: it overrides the ray map's
    bool plan = false;              // --plan

    // The sparkle mode that runs: --sparkle's, or "plan" under --plan without --sparkle.
    std::string effectiveMode() const { return plan && !mode_given ? "plan" : mode; }
    // Whether the effect plan is needed (--plan, or --sparkle plan).
    bool needsPlan() const { return plan || effectiveMode() == "plan"; }
    // --scene-unit if given; unset: the ray map's header (1 m for a version-1 map).
    std::optional<double> sceneUnit() const {
        return scene_unit_given ? std::optional<double>(scene_unit_m) : std::nullopt;
    }
};

void addSparkleOptions(CLI::App* command, SparkleOption& o);

// The effect plan for the recipe in the map's scene (raymaps::summariseRayMap).
EffectPlan planForMap(const SparkleOption& o, const raymaps::RayMap& map, const Recipe& recipe,
                      Preset preset);

// The lines that say which of the plan's decisions the relight applied
// (`--plan`: every one; `--sparkle plan` alone: the sparkle decision).
std::vector<std::string> appliedPlanLines(const SparkleOption& o, const EffectPlan& plan);

// Runs the sparkle pass on `image` if the mode says so; returns the line to
// print ("" for off). `plan` must be given when effectiveMode() is "plan".
// Throws InputError for a bad setting.
std::string applySparkle(const SparkleOption& o, const raymaps::RayMap& map, const Recipe& recipe,
                         const EffectPlan* plan, raymaps::RgbImage& image);

}  // namespace paintlab::cli
