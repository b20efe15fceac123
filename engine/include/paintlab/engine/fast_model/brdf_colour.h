#pragma once
// Colour of a spectral BRDF (issue 3, item 4): a reflectance spectrum at the
// BRDF's wavelengths -> CIE XYZ, CIELAB and linear sRGB.
//
// Which spectrum:
//   - the reflectance factor R = pi f(wi, wo) at one geometry (1 for the
//     perfect diffuser; what a goniospectrophotometer reports, multiangle.h),
//   - the directional-hemispherical albedo for light from wi, mirror term of a
//     smooth top included (the colour of the paint under a collimated light
//     seen by an integrating sphere, specular included),
//   - or any spectrum the caller already has.
//
// XYZ and CIELAB are for the chosen illuminant and observer (Y = 1 and L* = 100
// for the perfect white, colour.h conventions). Linear sRGB is, by its
// definition (IEC 61966-2-1), the colour under D65 seen by the CIE 1931 2°
// observer: it is always computed for D65 / 2°, whatever illuminant and
// observer XYZ and CIELAB use, so a white paint is (1, 1, 1) and no chromatic
// adaptation transform has to be chosen. Channels are not clipped.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/colour/colour.h"

#include <span>
#include <vector>

namespace paintlab {

class LayeredBrdf;

struct ColourConditions {
    Illuminant illuminant = Illuminant::D65;
    Observer observer = Observer::Cie1964_10deg;  // what lab instruments report by default
};

struct SpectralColour {
    std::vector<double> reflectance;  // the spectrum, at the BRDF's wavelengths
    Xyz xyz;                          // for the conditions' illuminant and observer, Y = 1 for white
    Lab lab;                          // relative to that illuminant's white for that observer
    Rgb linear_srgb;                  // D65 / 2° (see above), unclipped
};

// The colour of `reflectance` sampled at `wavelengths_nm` (ascending). Between
// samples the spectrum is linear and beyond them its end values are held
// (reflectanceToXyz). Throws InputError (source "<argument>") if the two
// sizes differ, fewer than 2 samples are given, the wavelengths are not strictly
// ascending, or a value is not finite; Error if a CIE table cannot be loaded.
SpectralColour spectrumColour(std::span<const double> wavelengths_nm, std::span<const double> reflectance,
                              const ColourConditions& conditions = {});

// The reflectance factor pi f(wi, wo) of any spectral BRDF (no mirror term:
// SpectralBrdf::eval has none). Throws as spectrumColour.
SpectralColour reflectanceFactorColour(const SpectralBrdf& brdf, const Direction& wi, const Direction& wo,
                                       const ColourConditions& conditions = {});

// The directional-hemispherical albedo of the fast model's BRDF for light
// from wi (LayeredBrdf::albedo, mirror term included). Throws as spectrumColour.
SpectralColour albedoColour(const LayeredBrdf& brdf, const Direction& wi,
                            const ColourConditions& conditions = {});

}  // namespace paintlab
