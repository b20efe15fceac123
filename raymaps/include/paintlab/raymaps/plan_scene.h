#pragma once
// The effect planner's view of a scene (engine/plan.h, issue 7): its compact
// lights, the rest of its lighting, and the pixel footprints on its paint,
// summarised into the engine's PlanScene; and plan() for a raymaps::Scene.
//
// Summary:
//   - lights: every sun (irradiance luminance, solid angle of its disk),
//     every point light (intensity / distance^2 to the paint's centre, solid
//     angle 0), and the environment's HDR hotspots as the ray map extracts
//     them (EnvironmentMap::withoutHotspots with the ray map's defaults);
//   - environment_radiance: mean luminance of the rest of the environment;
//   - environment_sharpness_deg: the width over which its brightest feature
//     rises, (L_max - L_mean) / max |dL / dangle| on a 128 x 64 grid of directions;
//   - footprints: the distance to the paint along a 32 x 18 grid of camera
//     rays (nearest, farthest hit) times the camera's pixel angle, in µm via
//     scene_unit_m (paint seen only in mirrors or through glass is not found);
//   - viewing_distance_m: the nearest paint distance.
// The RayMap overload reads the same from a traced map: the header's lights
// and the records' footprints (1st and 99th percentile), in µm via the
// header's scene unit (unless the options give one), and the viewing
// distance as the 1st-percentile footprint / the header's pixel angle
// (version-1 maps, without a camera: unknown, 0).

#include "paintlab/engine/plan/plan.h"

#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/scene.h"
#include <optional>

namespace paintlab::raymaps {

struct PlanSceneOptions {
    // One scene unit in metres; unset: 1 for a scene, the header's for a ray map.
    std::optional<double> scene_unit_m;
};

// Throws InputError as loading the scene's meshes and environment does, or
// for a non-positive scene_unit_m.
PlanScene summariseScene(const Scene& scene, const PlanSceneOptions& options = {});
PlanScene summariseRayMap(const RayMap& map, const PlanSceneOptions& options = {});

EffectPlan plan(const Recipe& recipe, const Scene& scene, Preset preset,
                const PlanSceneOptions& options = {});

}  // namespace paintlab::raymaps
