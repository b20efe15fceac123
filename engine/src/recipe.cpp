#include "paintlab/engine/recipe.h"

#include <algorithm>
#include <numeric>

namespace paintlab {

double DepthProfile::weightAt(double z) const {
    return Spectrum(depth, weight)(z);  // same piecewise-linear, end-held interpolation
}

double DepthProfile::meanWeight() const {
    double integral = 0.0;
    for (std::size_t i = 1; i < depth.size(); ++i)
        integral += 0.5 * (weight[i] + weight[i - 1]) * (depth[i] - depth[i - 1]);
    return integral;
}

double DepthProfile::peakRelativeConcentration() const {
    const double mean = meanWeight();
    if (weight.empty() || !(mean > 0.0)) return 0.0;
    return *std::max_element(weight.begin(), weight.end()) / mean;
}

std::string_view componentKind(const Component& component) {
    return std::visit([](const auto& c) { return std::decay_t<decltype(c)>::kKind; }, component);
}

const std::string& componentName(const Component& component) {
    return std::visit([](const auto& c) -> const std::string& { return c.name; }, component);
}

double componentVolumeFraction(const Component& component) {
    return std::visit(
        [](const auto& c) {
            if constexpr (requires { c.volume_fraction; })
                return c.volume_fraction;
            else
                return 0.0;
        },
        component);
}

const std::optional<DepthProfile>* componentDepthProfile(const Component& component) {
    return std::visit(
        [](const auto& c) -> const std::optional<DepthProfile>* {
            if constexpr (requires { c.depth_profile; })
                return &c.depth_profile;
            else
                return nullptr;
        },
        component);
}

double Layer::totalVolumeFraction() const {
    return std::accumulate(components.begin(), components.end(), 0.0,
                           [](double sum, const Component& c) { return sum + componentVolumeFraction(c); });
}

std::string_view substrateKind(const Substrate& substrate) {
    return std::visit([](const auto& s) { return std::decay_t<decltype(s)>::kKind; }, substrate);
}

double Recipe::totalThicknessUm() const {
    return std::accumulate(layers.begin(), layers.end(), 0.0,
                           [](double sum, const Layer& l) { return sum + l.thickness_um; });
}

}  // namespace paintlab
