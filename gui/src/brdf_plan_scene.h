#pragma once
// The scene the effect planner is given when no ray map is open: the BRDF
// alone, as the plots show it (Qt-free). The plots evaluate the BRDF for a
// collimated light from any direction and colour it from its full spectrum,
// so the summary is one point light (solid angle 0: the sharpest lobe
// matters, no angular order may be dropped) with spectral lighting (no band
// may be dropped for an RGB scene's sake). Pixel footprints are unknown: the
// sparkle decision then assumes a close inspection (plan.h), and nothing
// draws glints without an image anyway.

#include "paintlab/engine/plan/plan.h"

namespace paintlab::gui {

const PlanScene& brdfPlanScene();

}  // namespace paintlab::gui
