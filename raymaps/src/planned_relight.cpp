// A relight that follows the effect plan (planned_relight.h).

#include "paintlab/raymaps/planned_relight.h"

#include "paintlab/engine/sparkle/sparkle.h"

namespace paintlab::raymaps {

EffectPlan planForRayMap(const RayMap& map, const Recipe& recipe, Preset preset,
                         const PlanSceneOptions& options) {
    return plan(recipe, summariseRayMap(map, options), preset);
}

FastModelSettings plannedSettings(const EffectPlan& plan) {
    return applyPlan(plan, presetSettings(plan.preset));
}

std::string sparkleSkipReason(const EffectPlan& plan) {
    if (plan.sparkle) return {};
    for (const PlanDecision& d : plan.decisions)
        if (d.effect == "sparkle") return d.reason;
    return "the plan has no sparkle decision";
}

SparklePassStats addRecipeSparkle(const RayMap& map, const Recipe& recipe, RgbImage& image,
                                  std::optional<double> scene_unit_m) {
    SparklePassSettings settings;
    settings.scene_unit_m = scene_unit_m;
    const SparkleModel model(recipe);
    return addSparkle(map, model, image, settings);
}

}  // namespace paintlab::raymaps
