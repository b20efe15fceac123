#include "paintlab/engine/layer_optics.h"
#include "paintlab/engine/recipe_json.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace paintlab {
namespace {

Layer minimalLayer() {
    return loadRecipeFile(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json").layers.at(0);
}

// All expectations below are closed forms of the recipe's numbers; 1e-12
// allows only floating-point rounding.
TEST(LayerOptics, PigmentAndFlakeCoefficientsFollowTheConcentrations) {
    const SlabOptics s = slabOptics(minimalLayer(), 590.0);
    EXPECT_DOUBLE_EQ(s.thickness_um, 20.0);
    EXPECT_DOUBLE_EQ(s.binder_index, 1.5);
    EXPECT_NEAR(s.sigma_a_per_um, 0.1 * 9.5, 1e-12);  // sigma_a(590) = 9.5 per unit volume fraction
    EXPECT_NEAR(s.sigma_s_per_um, 0.1 * 5.0, 1e-12);
    EXPECT_NEAR(s.albedo(), 0.5 / 1.45, 1e-12);
    EXPECT_NEAR(s.opticalThickness(), 1.45 * 20.0, 1e-12);
    ASSERT_EQ(s.lobes.size(), 1u);
    EXPECT_DOUBLE_EQ(s.lobes[0].g, 0.4);
    ASSERT_EQ(s.mirror_flakes.size(), 1u);
    // Volume fraction 0.05 of 0.3 µm thick flakes: 0.05 / 0.3 µm^2 of flake face per µm^3.
    EXPECT_NEAR(s.mirror_flakes[0].area_density_per_um, 0.05 / 0.3, 1e-12);
    EXPECT_DOUBLE_EQ(*s.mirror_flakes[0].reflectance, 0.9);
}

TEST(LayerOptics, MixturesKeepEveryLobeWithScatteringWeights) {
    Layer layer = minimalLayer();
    Pigment white;
    white.name = "white";
    white.volume_fraction = 0.2;
    white.sigma_s_per_um = Spectrum(20.0);
    white.hg_g = 0.6;
    layer.components.push_back(white);
    const SlabOptics s = slabOptics(layer, 590.0);
    ASSERT_EQ(s.lobes.size(), 2u);
    const double s1 = 0.5, s2 = 4.0;
    EXPECT_NEAR(s.lobes[0].weight, s1 / (s1 + s2), 1e-12);
    EXPECT_NEAR(s.lobes[1].weight, s2 / (s1 + s2), 1e-12);
    EXPECT_NEAR(s.meanCosine(), (s1 * 0.4 + s2 * 0.6) / (s1 + s2), 1e-12);
}

TEST(LayerOptics, SlicesConserveTheAmountOfMaterial) {
    // A ramp profile (all pigment near the top) split into 7 slices: the
    // slices' pigment adds up to the layer's, exactly, because the
    // piecewise-linear profile is integrated exactly.
    Layer layer = minimalLayer();
    std::get<Pigment>(layer.components[0]).depth_profile = DepthProfile{{0.0, 0.3, 1.0}, {3.0, 1.0, 0.0}};
    const auto bounds = sliceBoundaries(layer, 7);
    ASSERT_EQ(bounds.size(), 8u);
    const double whole = slabOptics(layer, 590.0).sigma_s_per_um * layer.thickness_um;
    double sum = 0.0;
    double top = 0.0;
    for (std::size_t i = 1; i < bounds.size(); ++i) {
        const SlabOptics s = slabOptics(layer, 590.0, bounds[i - 1], bounds[i]);
        sum += s.sigma_s_per_um * s.thickness_um;
        if (i == 1) top = s.sigma_s_per_um;
    }
    EXPECT_NEAR(sum, whole, 1e-12 * whole);
    EXPECT_GT(top, slabOptics(layer, 590.0).sigma_s_per_um);   // the top slice is richer
    EXPECT_EQ(sliceBoundaries(minimalLayer(), 7).size(), 2u);  // no profile: one slice
}

TEST(LayerOptics, RawMediumOpticalThicknessSplitsAcrossSlices) {
    Layer layer;
    layer.name = "raw";
    layer.thickness_um = 3.0;
    RawMedium raw;
    raw.name = "raw";
    raw.albedo = Spectrum(0.9);
    raw.optical_thickness = Spectrum(2.0);
    layer.components = {raw};
    const SlabOptics whole = slabOptics(layer, 550.0);
    EXPECT_NEAR(whole.opticalThickness(), 2.0, 1e-12);
    EXPECT_NEAR(whole.albedo(), 0.9, 1e-12);
    EXPECT_NEAR(slabOptics(layer, 550.0, 0.0, 0.25).opticalThickness(), 0.5, 1e-12);
}

TEST(LayerOptics, MeanRelativeConcentrationIsExact) {
    const std::optional<DepthProfile> ramp = DepthProfile{{0.0, 1.0}, {2.0, 0.0}};  // w/mean = 2 - 2z
    EXPECT_NEAR(meanRelativeConcentration(ramp, 0.0, 0.5), 1.5, 1e-14);
    EXPECT_NEAR(meanRelativeConcentration(ramp, 0.5, 1.0), 0.5, 1e-14);
    EXPECT_NEAR(meanRelativeConcentration(ramp, 0.0, 1.0), 1.0, 1e-14);
    EXPECT_EQ(meanRelativeConcentration(std::nullopt, 0.2, 0.4), 1.0);
}

}  // namespace
}  // namespace paintlab
