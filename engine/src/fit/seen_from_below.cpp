// The stack seen from below through its transparent carrier (fit.h,
// recipeSeenFromBelow): what a measurement "through the glass" sees.

#include "paintlab/engine/error.h"
#include "paintlab/engine/fit/fit.h"

#include <algorithm>

namespace paintlab::fit {

namespace {

// Thickness of the carrier layer: it neither absorbs nor scatters, so its
// thickness does not change the result; any allowed value does.
constexpr double kCarrierThicknessUm = 1000.0;

void turnOver(std::optional<DepthProfile>& profile) {
    if (!profile) return;
    // Relative depth z seen from below is 1 - z: reverse both lists.
    std::vector<double> depth(profile->depth.rbegin(), profile->depth.rend());
    for (double& z : depth) z = 1.0 - z;
    profile->depth = std::move(depth);
    std::reverse(profile->weight.begin(), profile->weight.end());
}

}  // namespace

Recipe recipeSeenFromBelow(const Recipe& recipe) {
    const auto* glass = std::get_if<TransparentSubstrate>(&recipe.substrate);
    if (glass == nullptr)
        throw InputError("<recipe>", "substrate",
                         "a bottom-side measurement needs a transparent substrate, not '" +
                             std::string(substrateKind(recipe.substrate)) + "'");
    Recipe below = recipe;
    below.name = recipe.name + " (seen from below)";
    below.ambient_refractive_index = recipe.ambient_refractive_index;
    below.layers.clear();
    Layer carrier;
    carrier.name = "carrier (substrate)";
    carrier.thickness_um = kCarrierThicknessUm;
    carrier.binder.name = "carrier";
    carrier.binder.refractive_index = Spectrum(glass->refractive_index);
    below.layers.push_back(std::move(carrier));
    for (auto it = recipe.layers.rbegin(); it != recipe.layers.rend(); ++it) {
        Layer layer = *it;
        for (Component& c : layer.components)
            std::visit(
                [](auto& component) {
                    if constexpr (requires { component.depth_profile; }) turnOver(component.depth_profile);
                },
                c);
        below.layers.push_back(std::move(layer));
    }
    below.substrate = TransparentSubstrate{.refractive_index = recipe.ambient_refractive_index};
    return below;
}

}  // namespace paintlab::fit
