// Issue 30: the connections' Russian roulette by transmittance
// (McSettings::connection_roulette, mc_connection.h) keeps the estimate's
// mean: exactly for one connection against its deterministic transmittance,
// and on every demo recipe against the estimator before it.

#include "mc_connection.h"
#include "mc_engine.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"

#include "z_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace paintlab {
namespace {

Recipe demo(const std::string& name) {
    return loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes" / (name + ".json"));
}

TEST(ConnectionRoulette, KeepsTheMeanTransmittanceOfADeepConnection) {
    // The three-layer demo's white ground coat under its pearl flake tile: a
    // connection from below the white's top, at the depth where the white's
    // transmittance up to its top is 0.3 kConnectionRouletteT, so that the
    // roulette keeps ~30 % of the draws. Its mean over N draws (each from its
    // own lateral point) must equal the mean of the transmittances traced
    // without the roulette at the same points (deterministic); each draw is
    // 0 or T / p, so the error of the mean is ~T sqrt((1 - p) / (p N)) (~0.4 %
    // here), and kZ = 4 of it (~6e-5 two-sided) is the tolerance. Dropping the
    // 1 / p weight would miss by (1 - p) T, ~300 errors.
    const Recipe recipe = demo("three-layer");
    mc::McSettings settings;
    settings.explicit_flakes = true;
    settings.histogram_cone_deg = 5.0;
    settings.batches = 1;
    settings.tile_flakes = 2000;
    settings.bottom_operator = false;  // the white walked, not one reflecting surface (mc_bottom.h)
    const mc::McEngine engine(recipe, settings);
    const mc::McEngine::Band band = engine.band(550.0);
    const mc::PaintStack& stack = band.stack;
    const auto tiles = std::span<const mc::LayerFlakes>(band.explicit_flakes[0]);
    const double white_top = recipe.layers[0].thickness_um + recipe.layers[1].thickness_um;
    const mc::Vec3 u{0.1, 0.05, std::sqrt(1.0 - 0.0125)};
    const mc::Slice& white = stack.slices[mc::sliceAt(stack, 2, white_top + 0.01)];
    ASSERT_GT(white.sigma_s_per_um, 1.0);
    // Within the white's first slice (one slice per layer of uniform concentration).
    const double depth = white_top + std::log(1.0 / (0.3 * mc::kConnectionRouletteT)) * u.z /
                                         (white.sigma_s_per_um + white.sigma_a_per_um);
    const std::size_t j = mc::sliceAt(stack, 2, depth);
    ASSERT_LT(j, stack.slices.size());
    ASSERT_LE(stack.slices[j].top_um, white_top + 1e-9);
    double exact_sum = 0.0;
    double sum = 0.0;
    double sum2 = 0.0;
    int survived = 0;
    constexpr int kDraws = 40000;
    mc::PathRng rng(7, 1, 2, 3);
    for (int i = 0; i < kDraws; ++i) {
        // A fresh lateral point per draw: the mean is over points, each with its own exact value.
        const double x = rng.uniform() * 100.0;
        const double y = rng.uniform() * 100.0;
        exact_sum += mc::straightToAmbient(stack, tiles, j, depth, x, y, u);
        const double t = mc::straightToAmbient(stack, tiles, j, depth, x, y, u, nullptr, &rng);
        sum += t;
        sum2 += t * t;
        survived += t > 0.0 ? 1 : 0;
    }
    const double n = kDraws;
    const double mean = sum / n;
    const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0));
    // The roulette ran (most draws cut, some kept), so the comparison is not trivial.
    EXPECT_GT(survived, kDraws / 10);
    EXPECT_LT(survived, kDraws / 2);
    test::expectClose(mean, se, exact_sum / n, 0.0, "mean transmittance with the roulette");
}

TEST(ConnectionRoulette, AgreesWithTheEstimatorBeforeItOnEveryDemoRecipe) {
    // Each demo recipe at 550 nm, explicit flakes, the albedo at normal and
    // 45 degree incidence and f at the six multi-angle geometries, with the
    // roulette and without it (the estimator before issue 30): independent
    // seeds and tiles, errors over 16 batches each (Student t, 15 degrees of
    // freedom). kZ = 4.5 in the combined errors: ~4e-4 two-sided per
    // comparison, 40 comparisons, ~2 % that one fails by chance. Small tiles
    // and few paths keep it to seconds; the paints without flakes run no
    // connections (the same estimator twice: a check that nothing else moved).
    const std::vector<std::pair<std::string, std::int64_t>> paints{{"pearlescent-two-layer", 16000},
                                                                   {"silver-metallic", 16000},
                                                                   {"three-layer", 1600},
                                                                   {"solid-red", 8000},
                                                                   {"raw-medium-slab", 8000}};
    std::vector<mc::IncidenceRequest> requests{{directionFromAnglesDeg(0.0, 0.0), {}},
                                               {multiAngleGeometry(kAspecularAnglesDeg[0]).wi, {}}};
    for (double as : kAspecularAnglesDeg) requests[1].wo.push_back(multiAngleGeometry(as).wo);
    for (const auto& [name, paths] : paints) {
        const Recipe recipe = demo(name);
        mc::McSettings s;
        s.explicit_flakes = true;
        s.histogram_cone_deg = 5.0;
        s.tile_flakes = 2000;
        s.batches = 16;
        s.max_paths = paths;
        s.seed = 41;
        const auto with = mc::runMonteCarlo(recipe, std::vector<double>{550.0}, requests, s);
        s.seed = 42;
        s.connection_roulette = false;
        const auto without = mc::runMonteCarlo(recipe, std::vector<double>{550.0}, requests, s);
        for (std::size_t i = 0; i < requests.size(); ++i)
            test::expectSameIncidence(with.bands[0][i], without.bands[0][i],
                                      name + " incidence " + std::to_string(i) + ": ", 4.5);
    }
}

}  // namespace
}  // namespace paintlab
