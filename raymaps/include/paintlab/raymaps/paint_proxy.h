#pragma once
// The colour of the Lambertian stand-in for paint met by the precompute's
// secondary rays (RayMapSettings::paint_proxy_albedo): the recipe's albedo
// for uniform diffuse incidence (LayeredBrdf::diffuseAlbedo, mirror term
// included, since a mirror image of the paint shows its gloss too) as linear
// sRGB (D65 / 2°, brdf_colour.h), clamped to [0, 1] per channel (a saturated
// paint's out-of-gamut channel would otherwise be negative light).

#include "paintlab/raymaps/scene.h"

namespace paintlab {
class LayeredBrdf;
}

namespace paintlab::raymaps {

Rgb3 paintProxyAlbedo(const LayeredBrdf& brdf);

}  // namespace paintlab::raymaps
