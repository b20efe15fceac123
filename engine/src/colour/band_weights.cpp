#include "paintlab/engine/colour/band_weights.h"

namespace paintlab {

namespace {

// sum_k spectrum[k] * weights[k], channel by channel, over the samples both have.
template <typename Colour, double Colour::*... kChannel>
Colour weightedSum(const std::vector<Colour>& weights, std::span<const double> spectrum) {
    Colour sum;
    for (std::size_t k = 0; k < spectrum.size() && k < weights.size(); ++k)
        ((sum.*kChannel += spectrum[k] * weights[k].*kChannel), ...);
    return sum;
}

}  // namespace

BandColourWeights bandColourWeights(std::span<const double> wavelengths_nm,
                                    const ColourConditions& conditions) {
    BandColourWeights w;
    w.conditions = conditions;
    std::vector<double> unit(wavelengths_nm.size(), 0.0);
    for (std::size_t k = 0; k < unit.size(); ++k) {
        unit[k] = 1.0;
        const SpectralColour c = spectrumColour(wavelengths_nm, unit, conditions);
        w.xyz.push_back(c.xyz);
        w.linear_srgb.push_back(c.linear_srgb);
        unit[k] = 0.0;
    }
    return w;
}

Xyz weightedXyz(const BandColourWeights& weights, std::span<const double> spectrum) {
    return weightedSum<Xyz, &Xyz::X, &Xyz::Y, &Xyz::Z>(weights.xyz, spectrum);
}

Rgb weightedLinearSrgb(const BandColourWeights& weights, std::span<const double> spectrum) {
    return weightedSum<Rgb, &Rgb::r, &Rgb::g, &Rgb::b>(weights.linear_srgb, spectrum);
}

}  // namespace paintlab
