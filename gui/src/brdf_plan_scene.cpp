#include "brdf_plan_scene.h"

namespace paintlab::gui {

const PlanScene& brdfPlanScene() {
    static const PlanScene scene = [] {
        PlanScene s;
        s.source = "no scene open: the BRDF alone (a collimated light from any direction, spectral)";
        // Irradiance of the sun at noon (luminance-weighted, W/m^2): the
        // brightest light a paint is judged under.
        s.lights.push_back({"collimated light", 1000.0, 0.0});
        s.spectral_lighting = true;
        return s;
    }();
    return scene;
}

}  // namespace paintlab::gui
