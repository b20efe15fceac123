#pragma once
// Scenes and ray-map settings that the ray-map tests and benchmarks share.

#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/scene.h"

#include <string>

namespace paintlab::test {

// The cheapest precompute: one camera sample, 16 moment rays (4 raised to
// M_L per cell), one bake path and shadow ray, short paths. The relight's
// work depends on the paint pixel count, J, M_L and the lights only, so its
// timings need nothing better.
inline raymaps::RayMapSettings cheapRayMapSettings() {
    raymaps::RayMapSettings s;
    s.aa_samples = 1;
    s.light_rays = 4;
    s.bake_paths = 1;
    s.sun_shadow_rays = 1;
    s.max_depth = 2;
    s.indirect_depth = 1;
    return s;
}

// A paint sphere (radius 0.8, 20 x 4^subdivisions triangles) on a floor
// under one sun, seen from 4 m.
inline raymaps::Scene paintSphereOnFloor(int width, int height, int subdivisions) {
    return raymaps::parseSceneJson(R"({"schema_version": 1,
      "camera": {"position": [0, 1, 4], "look_at": [0, 0.8, 0], "vertical_fov_deg": 30, "width": )" +
                                       std::to_string(width) + R"(, "height": )" + std::to_string(height) +
                                       R"(},
      "lights": [{"type": "sun", "direction": [0.5, 0.8, 0.6], "irradiance": [2, 2, 2]}],
      "materials": [{"name": "paint", "kind": "paint"}, {"name": "ground", "kind": "diffuse"}],
      "objects": [{"name": "ball", "sphere": {"radius": 0.8, "subdivisions": )" +
                                       std::to_string(subdivisions) + R"(}, "material": "paint",
                   "transform": {"translate": [0, 0.8, 0]}},
                  {"name": "floor", "plane": {"size": 30}, "material": "ground"}]})",
                                   "sphere.json");
}

}  // namespace paintlab::test
