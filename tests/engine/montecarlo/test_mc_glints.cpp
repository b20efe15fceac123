// The beam's single flake reflections averaged over every azimuth of a tile
// (mc_connection.h, azimuthGlintSets / azimuthGlintSample) against the
// per-view glint lists they replace (glintSets / scoreGlints).
//
// Unbiasedness rests on two facts checked here: every flake that glints into a
// cone at some view is listed with that view's azimuth inside its interval
// (exact, no tolerance), and the sample's mean is the average over views of
// the per-view estimate (z-test, z = 4: two-sided significance ~6e-5 per
// comparison, four comparisons).

#include "mc_connection.h"
#include "mc_engine.h"
#include "mc_random.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"

#include "test_recipes.h"
#include "z_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace paintlab {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The small pearlescent (test_recipes.h) with an absorbing, weakly scattering
// black over a 0.3 grey base; ~1500 flakes per tile.
Recipe pearlescent() {
    Pigment black = test::pigment(0.01, 10.0, 0.5, 0.0);
    black.name = "black";
    return test::smallPearlescent(black, 0.3);
}

struct Fixture {
    Recipe recipe = pearlescent();
    mc::McSettings settings;
    std::unique_ptr<mc::McEngine> engine;
    mc::McEngine::Band band;
    mc::Vec3 v_in;  // the beam refracted into the top slice
    std::vector<mc::HistogramBin> bins;

    explicit Fixture(double cone_deg) {
        settings.explicit_flakes = true;
        settings.histogram_cone_deg = cone_deg;
        settings.batches = 1;
        settings.tile_flakes = 1500;
        engine = std::make_unique<mc::McEngine>(recipe, settings);
        band = engine->band(450.0);
        const Direction wi = directionFromAnglesDeg(45.0, 0.0);
        const double ratio = band.stack.ambient_n / band.stack.slices.front().n;
        v_in = {-wi.x * ratio, -wi.y * ratio, 0.0};
        v_in.z = -std::sqrt(1.0 - v_in.x * v_in.x - v_in.y * v_in.y);
        const double alpha = cone_deg * std::numbers::pi / 180.0;
        // Near the specular direction, across it, at the flop, and a cone that crosses the horizon.
        for (const Direction& wo : {directionFromAnglesDeg(45.0, 180.0), directionFromAnglesDeg(25.0, 180.0),
                                    directionFromAnglesDeg(20.0, 0.0), directionFromAnglesDeg(60.0, 150.0),
                                    directionFromAnglesDeg(88.0, 180.0)})
            bins.push_back({{wo.x, wo.y, wo.z},
                            std::cos(alpha),
                            std::numbers::pi * std::sin(alpha) * std::sin(alpha) * std::max(wo.z, 1e-9),
                            kTwoPi * (1.0 - std::cos(alpha))});
    }
    std::span<const mc::LayerFlakes> tiles() const { return band.explicit_flakes[0]; }
};

mc::Vec3 turned(const mc::Vec3& a, double psi) {
    return {std::cos(psi) * a.x - std::sin(psi) * a.y, std::sin(psi) * a.x + std::cos(psi) * a.y, a.z};
}

TEST(GlintAzimuths, EveryGlintingFlakeIsListedAtItsAzimuth) {
    const Fixture fx(5.0);
    const auto sets = mc::azimuthGlintSets(fx.band.stack, fx.tiles(), fx.v_in, fx.bins);
    mc::PathRng rng(1, 2, 3, 4);
    std::vector<int> glints(fx.bins.size(), 0);
    std::vector<int> missing(fx.bins.size(), 0);
    for (int view = 0; view < 400; ++view) {
        const double psi = kTwoPi * rng.uniform();
        std::vector<mc::HistogramBin> bins = fx.bins;
        for (auto& bin : bins) bin.wo = turned(bin.wo, psi);
        // The per-view lists: the flakes that glint into each cone at this view.
        const auto lists = mc::glintSets(fx.band.stack, fx.tiles(), turned(fx.v_in, psi), bins);
        for (std::size_t k = 0; k < bins.size(); ++k)
            for (const auto& g : lists[k].flakes) {
                ++glints[k];
                bool listed = false;
                for (const auto& a : sets[k].flakes) {
                    if (a.layer != g.layer || a.flake != g.flake) continue;
                    const double offset = std::fmod(std::fmod(psi - a.psi_lo, kTwoPi) + kTwoPi, kTwoPi);
                    listed = listed || offset <= a.psi_width + 1e-12;
                }
                if (!listed) ++missing[k];
            }
    }
    for (std::size_t k = 0; k < fx.bins.size(); ++k) {
        EXPECT_EQ(missing[k], 0) << "cone " << k << ": " << missing[k] << " of " << glints[k]
                                 << " glints unlisted";
        if (k < 4) {
            EXPECT_GT(glints[k], 20) << "cone " << k << " (the test needs glints)";
        }
    }
}

TEST(GlintAzimuths, SampleMeanIsTheAverageOverViews) {
    const Fixture fx(5.0);
    const auto sets = mc::azimuthGlintSets(fx.band.stack, fx.tiles(), fx.v_in, fx.bins);
    mc::PathRng rng(5, 6, 7, 8);
    // Reference: views on a randomly shifted grid of azimuths (stratified, unbiased for the
    // average over all azimuths), 40 per-view glint samples each; its error from the
    // spread of the views' means (an upper bound for the stratified grid).
    constexpr int kViews = 720;
    constexpr int kPerView = 40;
    const double shift = rng.uniform();
    std::vector<std::vector<double>> per_view(fx.bins.size(), std::vector<double>(kViews, 0.0));
    for (int m = 0; m < kViews; ++m) {
        const double psi = kTwoPi * (m + shift) / kViews;
        std::vector<mc::HistogramBin> bins = fx.bins;
        for (auto& bin : bins) bin.wo = turned(bin.wo, psi);
        const auto lists = mc::glintSets(fx.band.stack, fx.tiles(), turned(fx.v_in, psi), bins);
        std::vector<double> f(bins.size(), 0.0);
        for (int i = 0; i < kPerView; ++i)
            mc::scoreGlints(fx.band.stack, fx.tiles(), lists, bins, 1.0 / kPerView, rng, f);
        for (std::size_t k = 0; k < bins.size(); ++k) per_view[k][static_cast<std::size_t>(m)] = f[k];
    }
    for (std::size_t k = 0; k < 4; ++k) {
        double mean = 0.0;
        for (double x : per_view[k]) mean += x / kViews;
        double var = 0.0;
        for (double x : per_view[k]) var += (x - mean) * (x - mean) / (kViews - 1);
        constexpr int kSamples = 40000;
        double s1 = 0.0;
        double s2 = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            mc::GlintUniforms u;
            u.pick = rng.uniform();
            u.psi = rng.uniform();
            u.choose = rng.uniform();
            u.u1 = rng.uniform();
            u.u2 = rng.uniform();
            u.u3 = rng.uniform();
            const double x = mc::azimuthGlintSample(fx.band.stack, fx.tiles(), sets[k], fx.bins[k], u);
            s1 += x;
            s2 += x * x;
        }
        const double sample_mean = s1 / kSamples;
        const double sample_se =
            std::sqrt(std::max(0.0, s2 / kSamples - sample_mean * sample_mean) / kSamples);
        ASSERT_GT(mean, 0.0) << "cone " << k;
        test::expectClose(sample_mean, sample_se, mean, std::sqrt(var / kViews),
                          "glint f, cone " + std::to_string(k));
    }
}

}  // namespace
}  // namespace paintlab
