// The recipe's spectra and depth profiles as the planner sees them (plan_spectra.h).

#include "plan_spectra.h"

#include "paintlab/engine/layer_optics.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>
#include <vector>

namespace paintlab::plan_detail {

namespace {

// Collects every spectrum a struct exposes through its traverse() hook.
struct SpectrumCollector {
    std::vector<const Spectrum*> spectra;
    void scalar(const ParameterDecl& /*decl*/, const double& /*value*/) {}
    void spectrum(const ParameterDecl& /*decl*/, const Spectrum& s) { spectra.push_back(&s); }
    void optionalSpectrum(const ParameterDecl& /*decl*/, const std::optional<Spectrum>& s) {
        if (s) spectra.push_back(&*s);
    }
};

double samplingError(const Spectrum& s, int bands) {
    if (s.isConstant()) return 0.0;
    const double scale = std::max(std::abs(s.minValue()), std::abs(s.maxValue()));
    if (!(scale > 0.0)) return 0.0;
    const double step = (kVisibleMaxNm - kVisibleMinNm) / (bands - 1);
    double worst = 0.0;
    for (double nm = kVisibleMinNm; nm <= kVisibleMaxNm + 1e-9; nm += 2.0) {
        const int k = std::min(static_cast<int>((nm - kVisibleMinNm) / step), bands - 2);
        const double a = kVisibleMinNm + k * step;
        const double t = (nm - a) / step;
        const double interpolated = (1.0 - t) * s(a) + t * s(a + step);
        worst = std::max(worst, std::abs(interpolated - s(nm)) / scale);
    }
    return worst;
}

}  // namespace

double spectralSamplingError(const Recipe& recipe, int bands) {
    SpectrumCollector c;
    for (const Layer& layer : recipe.layers) {
        Binder::traverse(layer.binder, c);
        for (const Component& component : layer.components)
            std::visit([&](const auto& x) { std::decay_t<decltype(x)>::traverse(x, c); }, component);
    }
    std::visit([&](const auto& x) { std::decay_t<decltype(x)>::traverse(x, c); }, recipe.substrate);
    double worst = 0.0;
    for (const Spectrum* s : c.spectra) worst = std::max(worst, samplingError(*s, std::max(bands, 2)));
    return worst;
}

bool hasDepthProfiles(const Recipe& recipe) {
    for (const Layer& layer : recipe.layers)
        for (const Component& component : layer.components) {
            const auto* p = componentDepthProfile(component);
            if (p != nullptr && p->has_value()) return true;
        }
    return false;
}

double sliceConcentrationError(const Recipe& recipe, int slices) {
    double worst = 0.0;
    constexpr int kSteps = 400;  // midpoint rule per profile; w is piecewise linear
    for (const Layer& layer : recipe.layers)
        for (const Component& component : layer.components) {
            const auto* p = componentDepthProfile(component);
            if (p == nullptr || !p->has_value()) continue;
            const DepthProfile& profile = **p;
            const double mean = profile.meanWeight();
            if (!(mean > 0.0)) continue;
            double deviation = 0.0;
            for (int i = 0; i < kSteps; ++i) {
                const double z = (i + 0.5) / kSteps;
                const int s = std::min(static_cast<int>(z * slices), slices - 1);
                const double slice_mean =
                    mean * meanRelativeConcentration(*p, static_cast<double>(s) / slices,
                                                     static_cast<double>(s + 1) / slices);
                deviation += std::abs(profile.weightAt(z) - slice_mean) / kSteps;
            }
            worst = std::max(worst, deviation / mean);
        }
    return worst;
}

}  // namespace paintlab::plan_detail
