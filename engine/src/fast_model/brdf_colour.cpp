#include "paintlab/engine/fast_model/brdf_colour.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/spectrum.h"

#include <numbers>
#include <stdexcept>

namespace paintlab {

SpectralColour spectrumColour(std::span<const double> wavelengths_nm, std::span<const double> reflectance,
                              const ColourConditions& conditions) {
    SpectralColour c;
    c.reflectance.assign(reflectance.begin(), reflectance.end());
    Spectrum spectrum;
    try {
        spectrum = Spectrum(std::vector<double>(wavelengths_nm.begin(), wavelengths_nm.end()), c.reflectance);
    } catch (const std::invalid_argument& e) {
        throw InputError("<argument>", "reflectance", e.what());
    }
    c.xyz = reflectanceToXyz(spectrum, conditions.illuminant, conditions.observer);
    c.lab = xyzToLab(c.xyz, whitePoint(conditions.illuminant, conditions.observer));
    // sRGB is defined for D65 and the 2° observer (IEC 61966-2-1); its matrix
    // expects XYZ with Y = 1 for that white, which reflectanceToXyz gives.
    const Xyz d65 = conditions.illuminant == Illuminant::D65 && conditions.observer == Observer::Cie1931_2deg
                        ? c.xyz
                        : reflectanceToXyz(spectrum, Illuminant::D65, Observer::Cie1931_2deg);
    c.linear_srgb = xyzToLinearSrgb(d65);
    return c;
}

SpectralColour reflectanceFactorColour(const SpectralBrdf& brdf, const Direction& wi, const Direction& wo,
                                       const ColourConditions& conditions) {
    std::vector<double> factor = brdf.eval(wi, wo);
    for (double& r : factor) r *= std::numbers::pi;  // pi f: 1 for the perfect diffuser
    return spectrumColour(brdf.wavelengthsNm(), factor, conditions);
}

SpectralColour albedoColour(const LayeredBrdf& brdf, const Direction& wi,
                            const ColourConditions& conditions) {
    return spectrumColour(brdf.wavelengthsNm(), brdf.albedo(wi), conditions);
}

}  // namespace paintlab
