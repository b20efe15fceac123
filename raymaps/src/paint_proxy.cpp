// The paint stand-in's colour from the recipe's BRDF (paint_proxy.h).

#include "paintlab/raymaps/paint_proxy.h"

#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"

#include <algorithm>

namespace paintlab::raymaps {

Rgb3 paintProxyAlbedo(const LayeredBrdf& brdf) {
    const SpectralColour colour = spectrumColour(brdf.wavelengthsNm(), brdf.diffuseAlbedo());
    const auto clamp = [](double v) { return std::clamp(v, 0.0, 1.0); };
    return {clamp(colour.linear_srgb.r), clamp(colour.linear_srgb.g), clamp(colour.linear_srgb.b)};
}

}  // namespace paintlab::raymaps
