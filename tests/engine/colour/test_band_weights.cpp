// A spectrum's colour as weights per sample (colour/band_weights.h) against
// spectrumColour of the whole spectrum.
#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace paintlab {
namespace {

// XYZ and linear sRGB are linear in the samples: the weighted sum is the
// colour of the spectrum, to round-off, for any illuminant and observer.
TEST(BandColourWeights, WeightedSumIsTheSpectrumsColour) {
    const std::vector<double> nm = visibleBands(21);
    std::vector<double> spectrum;
    for (std::size_t k = 0; k < nm.size(); ++k) spectrum.push_back(0.3 + 0.2 * std::sin(0.4 * double(k)));
    for (const ColourConditions conditions :
         {ColourConditions{}, ColourConditions{Illuminant::D65, Observer::Cie1931_2deg}}) {
        const BandColourWeights weights = bandColourWeights(nm, conditions);
        ASSERT_EQ(weights.xyz.size(), nm.size());
        const SpectralColour expected = spectrumColour(nm, spectrum, conditions);
        const Xyz xyz = weightedXyz(weights, spectrum);
        const Rgb rgb = weightedLinearSrgb(weights, spectrum);
        EXPECT_NEAR(xyz.X, expected.xyz.X, 1e-12);
        EXPECT_NEAR(xyz.Y, expected.xyz.Y, 1e-12);
        EXPECT_NEAR(xyz.Z, expected.xyz.Z, 1e-12);
        EXPECT_NEAR(rgb.r, expected.linear_srgb.r, 1e-12);
        EXPECT_NEAR(rgb.g, expected.linear_srgb.g, 1e-12);
        EXPECT_NEAR(rgb.b, expected.linear_srgb.b, 1e-12);
    }
}

// Only the samples both have are summed.
TEST(BandColourWeights, ShorterSpectrumSumsItsOwnSamples) {
    const BandColourWeights weights = bandColourWeights(visibleBands(4));
    const std::vector<double> first{1.0};
    EXPECT_EQ(weightedXyz(weights, first).Y, weights.xyz[0].Y);
    EXPECT_EQ(weightedLinearSrgb(weights, first).g, weights.linear_srgb[0].g);
}

}  // namespace
}  // namespace paintlab
