// Hard cases the fast model must survive (issue 3, "Hard cases"). Each is
// named; every one asserts: all values finite, albedo <= 1 + 1e-6 (no energy
// created; 1e-6 allows round-off of the LU solves), reciprocity of the BRDF,
// and, where cheap, that refining the grid changes the answer little.
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe_validation.h"

#include "test_recipes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace paintlab {
namespace {

using test::mirrorFlake;
using test::pigment;
using test::rawMedium;

FastModelSettings coarse() {
    FastModelSettings s;
    s.nodes = 12;
    s.orders = 6;
    s.bands = 2;
    s.max_start_tau = 1.0 / 256.0;
    s.slices = 3;
    s.flake_polar = 12;
    s.flake_azimuth = 24;
    return s;
}

Layer layer(const std::string& name, double thickness_um, double n = 1.5) {
    Layer l;
    l.name = name;
    l.thickness_um = thickness_um;
    l.binder.refractive_index = Spectrum(n);
    return l;
}

Recipe recipeOf(std::vector<Layer> layers, Substrate substrate = LambertianSubstrate{Spectrum(0.5)}) {
    Recipe r;
    r.name = "hard case";
    r.layers = std::move(layers);
    r.substrate = std::move(substrate);
    return r;
}

void expectSane(const Recipe& recipe, const FastModelSettings& settings = coarse()) {
    validateRecipe(recipe, "hard case");  // the case itself must be a legal recipe
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, settings);
    for (const auto& band : brdf.bands()) {
        for (double a : band.albedo) {
            ASSERT_TRUE(std::isfinite(a));
            EXPECT_LE(a, 1.0 + 1e-6);
            EXPECT_GE(a, -1e-12);
        }
    }
    for (double ti : {0.0, 40.0, 89.9}) {
        for (double to : {0.0, 60.0, 89.9}) {
            const Direction wi = directionFromAnglesDeg(ti, 10.0);
            const Direction wo = directionFromAnglesDeg(to, 200.0);
            const auto f = brdf.eval(wi, wo);
            const auto g = brdf.eval(wo, wi);
            for (std::size_t b = 0; b < f.size(); ++b) {
                ASSERT_TRUE(std::isfinite(f[b])) << ti << " -> " << to;
                // Reciprocity holds for the tables up to round-off; 1e-6 relative (or absolute below 1/sr).
                EXPECT_NEAR(f[b], g[b], 1e-6 * std::max(1.0, f[b])) << ti << " <-> " << to;
            }
        }
    }
}

TEST(FastModelStability, GrazingIncidenceAndExit) {
    // The 89.9° directions are in expectSane; here with a strong index contrast too.
    Layer l = layer("coat", 30.0, 2.9);
    l.components = {pigment(0.1, 1.0, 5.0, 0.5)};
    expectSane(recipeOf({l}));
}

TEST(FastModelStability, NodesNextToTheCriticalAngle) {
    // Two close indices put a split point very near another one.
    Layer top = layer("top", 20.0, 1.5);
    Layer bottom = layer("bottom", 20.0, 1.5 + 1e-6);
    bottom.components = {pigment(0.2, 0.5, 10.0, 0.3)};
    expectSane(recipeOf({top, bottom}));
}

TEST(FastModelStability, ConservativeThickLayer) {
    Layer l = layer("thick white", 50.0, 1.5);
    l.components = {rawMedium(1.0, 1e4, 0.0)};
    expectSane(recipeOf({l}, BlackSubstrate{}));
}

TEST(FastModelStability, VanishingAndMaximalConcentrations) {
    Layer tiny = layer("tiny", 20.0);
    tiny.components = {pigment(1e-12, 10.0, 10.0, 0.5), mirrorFlake(1e-12, 10.0, 0.9)};
    expectSane(recipeOf({tiny}));
    Layer full = layer("full", 20.0);
    full.components = {pigment(0.34, 5.0, 20.0, 0.5), mirrorFlake(0.3, 10.0, 0.9)};
    expectSane(recipeOf({full}));
}

TEST(FastModelStability, FlakeSpreadExtremes) {
    for (double spread : {0.1, 90.0}) {
        SCOPED_TRACE(spread);
        Layer l = layer("flakes", 15.0);
        l.components = {mirrorFlake(0.05, spread, 0.9)};
        expectSane(recipeOf({l}));
    }
}

TEST(FastModelStability, PerfectlyReflectingFlakes) {
    Layer l = layer("mirrors", 15.0);
    l.components = {mirrorFlake(0.1, 5.0, 1.0)};
    expectSane(recipeOf({l}, LambertianSubstrate{Spectrum(1.0)}));
}

TEST(FastModelStability, ExtremeAsymmetry) {
    for (double g : {0.999, -0.999}) {
        SCOPED_TRACE(g);
        Layer l = layer("lobe", 20.0);
        l.components = {pigment(0.2, 0.1, 10.0, g)};
        expectSane(recipeOf({l}));
    }
}

TEST(FastModelStability, IndexMatchedAndHighContrastInterfaces) {
    Layer matched = layer("matched", 20.0, 1.0);
    matched.components = {pigment(0.1, 1.0, 5.0, 0.2)};
    expectSane(recipeOf({matched}));
    Layer clear = layer("clear", 20.0, 2.9);
    Layer base = layer("base", 20.0, 1.0);
    base.components = {pigment(0.1, 1.0, 5.0, 0.2)};
    expectSane(recipeOf({clear, base}, TransparentSubstrate{1.0}));
}

TEST(FastModelStability, LayersOfOneNanometreAndOneMillimetre) {
    Layer thin = layer("1 nm", 0.001);
    thin.components = {pigment(0.2, 5.0, 20.0, 0.5)};
    Layer thick = layer("1 mm", 1000.0);
    thick.components = {pigment(0.01, 0.01, 0.5, 0.5)};
    expectSane(recipeOf({thin, thick}));
}

TEST(FastModelStability, OneAndTwentyLayers) {
    Layer one = layer("only", 20.0);
    one.components = {pigment(0.1, 1.0, 5.0, 0.5)};
    expectSane(recipeOf({one}));
    std::vector<Layer> many;
    for (int i = 0; i < 20; ++i) {
        Layer l = layer("layer " + std::to_string(i + 1), 2.0 + i, 1.45 + 0.01 * (i % 5));
        l.components = {pigment(0.02 * (i % 3), 1.0, 5.0, 0.4)};
        many.push_back(l);
    }
    expectSane(recipeOf(many));
}

TEST(FastModelStability, MixedTinyAndHugeOpticalThicknesses) {
    Layer tiny = layer("tiny", 10.0);
    tiny.components = {rawMedium(0.9, 1e-9, 0.5)};
    Layer huge = layer("huge", 10.0);
    huge.components = {rawMedium(0.99, 1e3, 0.8)};
    expectSane(recipeOf({tiny, huge}));
}

TEST(FastModelStability, DepthProfileAtTheLimit) {
    Layer l = layer("graded", 20.0);
    Pigment p = pigment(0.32, 1.0, 10.0, 0.5);
    p.depth_profile = DepthProfile{{0.0, 1.0}, {2.0, 0.0}};  // peak 0.64, the allowed maximum
    l.components = {p};
    expectSane(recipeOf({l}));
}

TEST(FastModelConvergence, RefiningTheGridConverges) {
    // A pigmented coat: the diffuse albedo at successive node counts changes by
    // less and less (the differences must shrink; 1e-12 slack for round-off).
    Layer l = layer("base", 25.0);
    l.components = {pigment(0.15, 0.3, 8.0, 0.6)};
    const Recipe r = recipeOf({l});
    double previous = 0.0;
    double previous_change = 1.0;
    for (int nodes : {8, 16, 32}) {
        FastModelSettings s = coarse();
        s.nodes = nodes;
        const double albedo = computeLayeredBrdf(r, s).diffuseAlbedo()[0];
        if (nodes > 8) {
            const double change = std::abs(albedo - previous);
            EXPECT_LT(change, previous_change + 1e-12) << nodes << " nodes";
            previous_change = change;
        }
        previous = albedo;
    }
    EXPECT_LT(previous_change, 2e-3);  // 16 -> 32 nodes moves the diffuse albedo by < 0.2 %
}

}  // namespace
}  // namespace paintlab
