#pragma once
// A relight that follows the effect plan (engine/plan.h, issue 7): what the
// CLI's `relight --plan` runs and the workstation's recompute runs, in one
// place so the two cannot drift apart. The plan comes from the ray map's
// lights and footprints (summariseRayMap); the fast model runs at the plan's
// settings (applyPlan on the preset's); the sparkle pass runs after the
// relight where the plan finds glints visible (EffectPlan::sparkle).

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/sparkle_pass.h"

#include <optional>
#include <string>

namespace paintlab::raymaps {

// The effect plan for the recipe in the map's scene. Throws InputError as
// summariseRayMap() and plan() do (a bad recipe, a corrupt band, a bad scene unit).
EffectPlan planForRayMap(const RayMap& map, const Recipe& recipe, Preset preset,
                         const PlanSceneOptions& options = {});

// The fast model's settings a relight that follows `plan` computes with.
FastModelSettings plannedSettings(const EffectPlan& plan);

// Why the plan skips the sparkle pass (its sparkle decision's reason); empty
// when the plan runs it.
std::string sparkleSkipReason(const EffectPlan& plan);

// The sparkle pass of the recipe's flakes on `image` (the relight of `map`),
// at the map's scene unit unless one is given. Throws InputError as addSparkle().
SparklePassStats addRecipeSparkle(const RayMap& map, const Recipe& recipe, RgbImage& image,
                                  std::optional<double> scene_unit_m = std::nullopt);

}  // namespace paintlab::raymaps
