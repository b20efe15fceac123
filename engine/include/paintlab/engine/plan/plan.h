#pragma once
// The effect planner (issue 7): from the recipe, a summary of how the scene
// lights and sees the paint (PlanScene; raymaps/plan_scene.h makes one from a
// scene, since the engine knows no scenes) and an accuracy preset, decide
// what to simulate, each decision with its reason and the error it accepts.
//
// Errors are CIEDE2000 differences per pixel (99th percentile over the
// paint). A relative radiance change delta changes L* by at most
// 116 |(1 + delta)^(1/3) - 1| for pixels no brighter than white, which bounds
// Delta E_00 (S_L, S_C >= 1, CIE 142-2001): deltaEForRelativeChange. An
// effect is skipped or reduced only when its claimed error is below half the
// preset's tolerance, so that two accepted errors together stay within it.

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe.h"

#include <string>
#include <vector>

namespace paintlab {

// A compact light (a sun, a lamp, an HDR hotspot) as the paint sees it.
struct PlanLight {
    std::string name;
    double irradiance_w_m2 = 0.0;  // luminance-weighted, on a surface facing it
    double solid_angle_sr = 0.0;   // of its disk (0: a point)
};

struct PlanScene {
    std::string source;  // what was summarised (for the reasons)
    std::vector<PlanLight> lights;
    // The rest of the lighting (environment without the compact lights,
    // light from other objects): mean luminance radiance, W/(m^2 sr).
    double environment_radiance = 0.0;
    // Angular width (degrees) of its sharpest feature: how narrow a BRDF lobe
    // the environment can reveal (180: uniform).
    double environment_sharpness_deg = 180.0;
    // Pixel footprint on the paint (width of a pixel at the hit, µm), smallest
    // and largest over the paint; 0: unknown (then viewing_distance_m and the
    // eye's 1 arcmin are used).
    double footprint_min_um = 0.0;
    double footprint_max_um = 0.0;
    double viewing_distance_m = 0.0;
    // Whether the lighting has spectra (true) or only RGB (the ray maps: then
    // the band count is the ingredients' matter alone).
    bool spectral_lighting = false;
};

struct PlanDecision {
    std::string effect;    // "interference", "sparkle", "angular", "bands", "slices", "full_model"
    bool simulate = true;  // computed (fully or at the chosen setting) or skipped
    std::string setting;   // what the engine runs, e.g. "orders 8, nodes 16"
    std::string reason;
    double accepted_error_de = 0.0;  // claimed Delta E_00 (99th percentile) of what is skipped or reduced
    // The plan's estimate of what skipping the effect would cost (Delta E_00),
    // also when it decides to simulate it: what a caller that cannot or will
    // not run it accepts instead (sparkle and full_model; 0 for the others).
    double skip_error_de = 0.0;
};

struct EffectPlan {
    Preset preset = Preset::Standard;
    double tolerance_de = 1.0;
    FastModelSettings fast;  // the preset's settings, reduced where the plan allows
    bool interference = false;
    bool sparkle = false;
    bool full_model = false;
    std::vector<PlanDecision> decisions;
};

// The preset's colour tolerance (Delta E_00): preview 2, standard 1, reference 0.3.
double planToleranceDe(Preset preset);

// Upper bound of the Delta E_00 of a pixel whose radiance changes by the
// relative amount delta (> -1), for pixels no brighter than white (see above).
double deltaEForRelativeChange(double delta);

// Throws InputError if the recipe is invalid or the scene summary holds a
// negative or non-finite number (naming the field of PlanScene).
EffectPlan plan(const Recipe& recipe, const PlanScene& scene, Preset preset);

// The plan's reductions applied to fast-model settings (the preset's, or a
// caller's own): orders, bands and depth slices are lowered to the plan's
// where the plan lowered them from its preset's, and nothing is raised, so
// applyPlan(p, presetSettings(p.preset)) == p.fast. Interference and sparkle
// are not settings of the fast model: interference optics are skipped only
// when the recipe has no interference flakes (exact, nothing to change),
// sparkle is a pass after the relight (EffectPlan::sparkle), and the full
// model is another model (EffectPlan::full_model: the caller reports it).
FastModelSettings applyPlan(const EffectPlan& plan, FastModelSettings settings);

// One decision as a caller applied it, for reports: what runs and what the
// preset would have run ("orders 8 -> 6", "skipped", "on").
struct AppliedDecision {
    std::string effect;
    std::string applied;             // e.g. "orders 8 -> 6", "bands 24 (preset's)", "skipped", "on"
    bool changed = false;            // the plan (or the caller) runs less than the preset here
    double accepted_error_de = 0.0;  // the decision's, or its skip_error_de when the caller skips it
    std::string reason;
};

// The plan's decisions against its preset's settings, in the plan's order,
// as a relight that uses applyPlan() and EffectPlan::sparkle runs them;
// `full_model_available`: whether the caller can run the full model (a
// relight cannot: a decision to run it is reported as advised, not applied).
std::vector<AppliedDecision> appliedDecisions(const EffectPlan& plan, bool full_model_available = false);

}  // namespace paintlab
