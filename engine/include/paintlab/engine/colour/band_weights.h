#pragma once
// The colour of a spectrum sampled at fixed wavelengths, as a weighted sum of
// its samples. XYZ and linear sRGB are linear in the spectrum (reflectanceToXyz
// integrates a spectrum that is linear between its samples), so the colours of
// the unit spectra, computed once, turn any spectrum on those wavelengths into
// its colour with one product per sample: what the plots, the relight tables
// and the sparkle pass apply to thousands of spectra.

#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/fast_model/brdf_colour.h"

#include <span>
#include <vector>

namespace paintlab {

struct BandColourWeights {
    ColourConditions conditions;  // of xyz; linear sRGB is D65 / 2° by definition (brdf_colour.h)
    std::vector<Xyz> xyz;         // per sample: the colour of the spectrum that is 1 there, 0 elsewhere
    std::vector<Rgb> linear_srgb;
};

// Throws as spectrumColour (fewer than 2 wavelengths, not ascending, ...).
BandColourWeights bandColourWeights(std::span<const double> wavelengths_nm,
                                    const ColourConditions& conditions = {});
// Sums over the samples both have, in ascending order.
Xyz weightedXyz(const BandColourWeights& weights, std::span<const double> spectrum);
Rgb weightedLinearSrgb(const BandColourWeights& weights, std::span<const double> spectrum);

}  // namespace paintlab
