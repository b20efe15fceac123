// Narrow flakes (issue 28: fits of real metallics land at 4-5° spreads): the
// fast model at the preview and standard presets against the same model on a
// much finer angular grid, at the six multi-angle geometries. Flakes of
// spread σ reflect into a lobe ~2σ wide, which 16 nodes and 8 orders (the
// standard grid) cannot hold below ~8°: before the grid followed the spread,
// the silver metallic at 3° read L* 0 at 45as75 (10.7 converged).

#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "test_recipes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

namespace paintlab {
namespace {

Recipe withSpread(const char* demo, double spread_deg) {
    Recipe r = test::demoRecipe(demo);
    for (Layer& layer : r.layers)
        for (Component& c : layer.components) {
            if (auto* m = std::get_if<MirrorFlake>(&c)) m->orientation_spread_deg = spread_deg;
            if (auto* i = std::get_if<InterferenceFlake>(&c)) i->orientation_spread_deg = spread_deg;
        }
    return r;
}

// Four bands: both sides of each comparison run on the same wavelengths, so
// the difference is the angular grid's alone, and the fine grid stays cheap.
FastModelSettings fewBands(FastModelSettings s) {
    s.bands = 4;
    s.output_bands = 0;
    return s;
}

double worstDeltaE(const Recipe& recipe, const FastModelSettings& coarse, const FastModelSettings& fine) {
    const MultiAngleReport a = multiAngleColours(computeLayeredBrdf(recipe, coarse));
    const MultiAngleReport b = multiAngleColours(computeLayeredBrdf(recipe, fine));
    double worst = 0.0;
    for (std::size_t k = 0; k < a.colours.size(); ++k)
        worst = std::max(worst, ciede2000(a.colours[k].lab, b.colours[k].lab));
    return worst;
}

// The converged side: 64 nodes and 48 orders, where doubling to 96 / 64
// changed the silver metallic at 3° by < 0.01 ΔE00 (measured 2026-12-05).
FastModelSettings fineGrid(Preset preset) {
    FastModelSettings s = fewBands(presetSettings(preset));
    s.nodes = 64;
    s.orders = 48;
    return s;
}

struct Case {
    const char* demo;
    double spread_deg;
};

TEST(NarrowFlakes, StandardPresetFollowsTheSpread) {
    // ΔE00 0.3: a tenth of a just-noticeable difference in a paint match
    // (~1) and 50x below the 15.8 of the fixed grid at 3°.
    for (const Case c : {Case{"silver-metallic", 3.0}, Case{"silver-metallic", 4.0},
                         Case{"silver-metallic", 6.0}, Case{"pearlescent-two-layer", 3.0}}) {
        const Recipe r = withSpread(c.demo, c.spread_deg);
        const double e =
            worstDeltaE(r, fewBands(presetSettings(Preset::Standard)), fineGrid(Preset::Standard));
        std::printf("%s at %.0f°: worst ΔE00 %.3f against the fine grid\n", c.demo, c.spread_deg, e);
        EXPECT_LT(e, 0.3) << c.demo << " " << c.spread_deg;
    }
}

TEST(NarrowFlakes, WithoutTheRuleTheStandardGridFails) {
    // The check above has teeth: the fixed grid is far off at 3°.
    FastModelSettings fixed = fewBands(presetSettings(Preset::Standard));
    fixed.flake_nodes_times_spread_deg = 0.0;
    fixed.flake_orders_times_spread_deg = 0.0;
    const double e = worstDeltaE(withSpread("silver-metallic", 3.0), fixed, fineGrid(Preset::Standard));
    std::printf("fixed standard grid at 3°: worst ΔE00 %.2f\n", e);
    EXPECT_GT(e, 3.0);
}

TEST(NarrowFlakes, PreviewStaysWithinItsLooserBudget) {
    // Preview is what a slider drag shows before the workstation refines to
    // standard (the fit's search uses a coarser grid still, fit.cpp, only to rank starts): it must stay
    // within one just-noticeable difference (ΔE00 1), the fixed grid's error being tens at 3°. Narrow flakes
    // are preview's hardest case: ~0.9 at 3°, ~0.3 at 5°, ~0.09 at the demo's 12° (printed;
    // docs/VALIDATION.md).
    for (const double spread : {3.0, 5.0, 12.0}) {
        const double e = worstDeltaE(withSpread("silver-metallic", spread),
                                     fewBands(presetSettings(Preset::Preview)), fineGrid(Preset::Preview));
        std::printf("preview at %.0f°: worst ΔE00 %.3f\n", spread, e);
        EXPECT_LT(e, 1.0) << spread;
    }
}

TEST(NarrowFlakes, SettingsReportTheGridThatRan) {
    const LayeredBrdf brdf =
        computeLayeredBrdf(withSpread("silver-metallic", 4.0), fewBands(presetSettings(Preset::Standard)));
    EXPECT_GE(brdf.settings().nodes, 28);   // 112 / 4
    EXPECT_GE(brdf.settings().orders, 20);  // 80 / 4
    const LayeredBrdf demo =
        computeLayeredBrdf(test::demoRecipe("silver-metallic"),
                           fewBands(presetSettings(Preset::Standard)));  // 12°: unchanged
    EXPECT_EQ(demo.settings().nodes, 16);
    EXPECT_EQ(demo.settings().orders, 8);
}

}  // namespace
}  // namespace paintlab
