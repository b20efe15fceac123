#pragma once
// CIEDE2000 colour difference (CIE 142-2001), implemented as in G. Sharma,
// W. Wu, E. N. Dalal, "The CIEDE2000 color-difference formula: implementation
// notes, supplementary test data, and mathematical observations", Color Res.
// Appl. 30(1), 21-30, 2005, including their notes on the hue
// angle: h' = 0 when a' = b' = 0, and when C1' C2' = 0 the hue difference is 0
// and the mean hue is h1' + h2'.

#include "paintlab/engine/colour/colour.h"

namespace paintlab {

// Delta E_00 between two CIELAB colours. kL, kC, kH are the parametric factors
// (1 for the reference conditions; textiles often use kL = 2). Symmetric in
// its two colours. The formula is discontinuous where the hue difference
// crosses 180 degrees (Sharma et al., section "Mathematical observations").
double ciede2000(const Lab& first, const Lab& second, double kL = 1.0, double kC = 1.0,
                 double kH = 1.0) noexcept;

}  // namespace paintlab
