#pragma once
// The fast model's f averaged over an exit cone the way the full model's
// histogram estimates it (McSettings::histogram_cone_deg), so that the two
// models can be compared.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/fast_model/layered_brdf.h"

#include <vector>

namespace paintlab::mc {

// Per band of `fast`: int_cone f(wi, w) cos dw / int_cone cos dw over the cone
// of half-angle cone_deg around `axis` (midpoint rule, 8 cone angles x 24
// azimuths); cone_deg <= 0: f(wi, axis). Never throws.
std::vector<double> coneAverage(const LayeredBrdf& fast, const Direction& wi, const Direction& axis,
                                double cone_deg);

}  // namespace paintlab::mc
