// Sparkle statistics and texture (issue 7): the flake part of the BRDF
// against the fast model, the Poisson mean against a direct count in the full
// model's explicit flake tile, energy (the texture's mean is the BRDF: z-tests
// over many surface cells), the fading limits, and the texture's stability.

#include "flake_tile.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/optics/flake_orientation.h"
#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/engine/sparkle/sparkle_texture.h"
#include "test_recipes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

namespace paintlab {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSunSr = 6.8e-5;  // the sun's disk, 0.53 deg across

// 20 µm of clear binder over black with sparse mirror flakes: coverage
// 0.002 x 20 / 0.5 = 0.08 flake layers, so single scattering is nearly all of
// the flakes' light (multiple flake-flake scattering ~ coverage^2 ~ 0.6 %).
Recipe sparseFlakes(double volume_fraction = 0.002, double spread_deg = 20.0, double diameter_um = 15.0) {
    Recipe r = test::oneLayerRecipe(1.5, 20.0, BlackSubstrate{});
    MirrorFlake f = test::mirrorFlake(volume_fraction, spread_deg, 0.6);
    f.diameter_um = diameter_um;
    r.layers[0].components.push_back(f);
    return r;
}

SparkleGeometry geometry(double theta_i, double phi_i, double theta_o, double phi_o, double area_um2) {
    SparkleGeometry g;
    g.wi = directionFromAnglesDeg(theta_i, phi_i);
    g.wo = directionFromAnglesDeg(theta_o, phi_o);
    g.element_area_um2 = area_um2;
    g.light_solid_angle_sr = kSunSr;
    g.view_solid_angle_sr = viewApertureSr(1.0);
    return g;
}

// f_flake is single scattering; the fast model also has the light that two
// or more flakes reflect in turn, ~ coverage x R / 2 of it (coverage 0.08,
// R 0.6: 2.4 %; ten times sparser: 0.24 %), plus its angular discretisation
// of a 20 deg lobe at 32 nodes and orders (a few 0.1 %). Budgets 3.5 % and
// 0.8 %; the difference must shrink with the coverage as double scattering does.
TEST(Sparkle, FlakeBrdfIsTheFastModelsFlakeLight) {
    for (const auto& [vf, budget] :
         {std::array<double, 2>{0.002, 0.035}, std::array<double, 2>{0.0002, 0.008}}) {
        const Recipe r = sparseFlakes(vf);
        const SparkleModel model(r, {.bands = 2});
        FastModelSettings s;
        s.nodes = 32;
        s.orders = 32;
        s.bands = 2;
        s.order_tolerance = 1e-8;
        const LayeredBrdf brdf = computeLayeredBrdf(r, s);
        // Near the mirror direction and 25 deg off it: the lobe of a 20 deg spread.
        for (const auto& [ti, pi, to, po] :
             {std::array<double, 4>{45, 0, 40, 180}, std::array<double, 4>{30, 0, 20, 180},
              std::array<double, 4>{45, 0, 20, 180}, std::array<double, 4>{20, 0, 15, 90}}) {
            const SparkleStats stats = model.evaluate(geometry(ti, pi, to, po, 1e4));
            const auto f = brdf.eval(directionFromAnglesDeg(ti, pi), directionFromAnglesDeg(to, po));
            EXPECT_NEAR(stats.flake_brdf_per_sr[0], f[0], budget * f[0])
                << vf << ": " << ti << " " << to << " " << po;
            std::printf(
                "volume fraction %g: f_flake vs fast model at (%g, %g) -> (%g, %g): %.5g / %.5g = %+.2f %%\n",
                vf, ti, pi, to, po, stats.flake_brdf_per_sr[0], f[0],
                100.0 * (stats.flake_brdf_per_sr[0] / f[0] - 1.0));
        }
    }
}

TEST(Sparkle, GlintRadianceTimesCountIsTheMean) {
    // Eq. (2) and (3) are written separately; Lambda E[w] L_g(0) = f mu_i must hold.
    Recipe r = sparseFlakes(0.01);
    r.layers.insert(r.layers.begin(), test::oneLayerRecipe(1.55, 40.0, BlackSubstrate{}).layers[0]);
    r.layers[1].binder.absorption_per_um = Spectrum(0.01);
    const SparkleModel model(r, {.bands = 3});
    const SparkleGeometry g = geometry(50, 10, 35, 200, 2e4);
    const SparkleStats stats = model.evaluate(g);
    ASSERT_EQ(stats.terms.size(), 1U);
    const SparkleTerm& t = stats.terms[0];
    EXPECT_GT(t.mean_glints, 0.0);
    const std::size_t ref = 1;  // 580 nm of 380, 580, 780: the reference band
    EXPECT_NEAR(t.mean_glints * t.mean_weight * t.glint_radiance_per_irradiance[ref],
                t.flake_brdf_per_sr[ref] * g.wi.z, 1e-9 * t.flake_brdf_per_sr[ref]);
    EXPECT_EQ(t.layer, 1);
    EXPECT_EQ(t.component, 0);
}

// The Poisson mean (1) against the explicit flakes the full model traces: in
// half of a tile of ~40000 flakes (15 µm, 20 deg spread) count those whose
// normal lies within 5 deg of a half vector and compare with
// rho x area x height x D(h) x Omega. Positions are uniform, so the count in
// half the tile is binomial ~ Poisson: z = (count - lambda) / sqrt(lambda),
// |z| < 3 (two-sided 0.27 % per window; 4 windows, 1.1 % family-wise). The
// small-window form D(h) Omega differs from the integral of D over the cone
// by ~ beta^2 / 8 x (Laplacian D / D) ~ 1.5 % ~ 0.5 sigma here.
TEST(Sparkle, PoissonMeanMatchesExplicitFlakeTileCount) {
    const double density = 0.02 / 0.5;  // area per volume, 1/µm: volume fraction 2 %, 0.5 µm thick
    const double d = 15.0;
    const double spread = 20.0;
    const double height = 20.0;
    mc::FlakeGeometry kind{density, d, spread, nullptr};
    const mc::FlakeTile tile({kind}, 0.0, height, 7, 40000, 200000);
    const double L = tile.sideUm();
    const FlakeOrientation D(spread);
    const double beta = 5.0 * kPi / 180.0;
    const double window = 2.0 * kPi * (1.0 - std::cos(beta));
    const double a_f = 0.25 * kPi * d * d;
    for (const auto& [tilt, azimuth] : {std::array<double, 2>{0, 0}, std::array<double, 2>{10, 30},
                                        std::array<double, 2>{20, 200}, std::array<double, 2>{30, 300}}) {
        const Direction h = directionFromAnglesDeg(tilt, azimuth);
        long long count = 0;
        for (const auto& f : tile.flakes()) {
            if (f.centre.x >= 0.5 * L) continue;  // the element: half the tile
            const double c = std::abs(f.normal.x * h.x + f.normal.y * h.y + f.normal.z * h.z);
            if (c > std::cos(beta)) ++count;
        }
        const double lambda = expectedGlints(density / a_f, 0.5 * L * L, height, D.pdf(h.z), window);
        EXPECT_GT(lambda, 20.0);
        std::printf("tilt %g deg: %lld flakes counted, Poisson mean %.1f, z = %+.2f\n", tilt, count, lambda,
                    (static_cast<double>(count) - lambda) / std::sqrt(lambda));
        EXPECT_LT(std::abs(static_cast<double>(count) - lambda) / std::sqrt(lambda), 3.0)
            << "tilt " << tilt << ": counted " << count << ", Poisson mean " << lambda;
    }
}

struct Moments {
    double mean = 0.0;
    double variance = 0.0;
    double m4 = 0.0;  // fourth central moment
    int n = 0;
};

// X - 1 of the single term over n x n cells of the given side.
Moments textureMoments(const SparkleStats& stats, int n, double side_um, std::uint64_t seed = 0) {
    std::vector<double> x;
    x.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    double m = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double v = 0.0;
            drawSparkle(stats, sparkleCellKey((i + 0.5) * side_um, (j + 0.5) * side_um, 0.0, side_um, seed),
                        {&v, 1});
            x.push_back(v);
            m += v;
        }
    Moments mo;
    mo.n = static_cast<int>(x.size());
    mo.mean = m / mo.n;
    for (double v : x) {
        const double dv = v - mo.mean;
        mo.variance += dv * dv;
        mo.m4 += dv * dv * dv * dv;
    }
    mo.variance /= mo.n - 1;
    mo.m4 /= mo.n;
    return mo;
}

// Energy: over 300 x 300 surface cells the texture's mean modulation is 0
// (mean of texture + remaining BRDF = full BRDF) and its variance is eq. (4),
// from 0.1 glints per element to 10^4 (the gamma regime). Under the sun the
// window of normals is small (the sun's disk and a flake's own 1 deg lobe,
// ~1e-3 sr), so these sparse flakes glint about once per 10^5 µm^2: the
// elements are 0.3 to 100 mm across. z-tests, |z| < 3 each (two-sided 0.27 %).
TEST(Sparkle, TextureMeanIsTheBrdfAndVarianceIsEq4) {
    const SparkleModel model(sparseFlakes(0.004), {.bands = 2});
    for (double area : {1e5, 1e6, 1e7, 1e8, 1e10}) {
        const SparkleStats stats = model.evaluate(geometry(45, 0, 38, 175, area));
        ASSERT_EQ(stats.terms.size(), 1U);
        const SparkleTerm& t = stats.terms[0];
        const Moments mo = textureMoments(stats, 300, std::sqrt(area));
        const double z_mean = mo.mean / std::sqrt(mo.variance / mo.n);
        EXPECT_LT(std::abs(z_mean), 3.0) << "Lambda " << t.mean_glints;
        std::printf("Lambda %.3g: mean(X - 1) z = %+.2f, variance %.4g vs eq. (4) %.4g\n", t.mean_glints,
                    z_mean, mo.variance, t.relativeVariance());
        // The sample variance's standard error from the sample fourth moment.
        const double se_var = std::sqrt(std::max(mo.m4 - mo.variance * mo.variance, 0.0) / mo.n);
        EXPECT_LT(std::abs(mo.variance - t.relativeVariance()) / se_var, 3.0)
            << "Lambda " << t.mean_glints << ": variance " << mo.variance << ", eq. (4) "
            << t.relativeVariance();
    }
}

TEST(Sparkle, SpectralModulationHasZeroMeanInEveryBand) {
    const SparkleModel model(sparseFlakes(0.004), {.bands = 3});
    const SparkleStats stats = model.evaluate(geometry(45, 0, 38, 175, 1e9));
    ASSERT_GT(stats.expected_glints, 1.0);
    const int n = 200;
    std::vector<double> sum(3, 0.0);
    std::vector<double> sum_sq(3, 0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const auto m = sparkleBrdfModulation(stats, sparkleCellKey(4e4 * i, 4e4 * j, 0.0, 3.2e4));
            for (std::size_t b = 0; b < 3; ++b) {
                sum[b] += m[b];
                sum_sq[b] += m[b] * m[b];
            }
        }
    const double count = n * n;
    for (std::size_t b = 0; b < 3; ++b) {
        const double mean = sum[b] / count;
        const double se = std::sqrt((sum_sq[b] / count - mean * mean) / count);
        EXPECT_LT(std::abs(mean) / se, 3.0) << "band " << b;
        EXPECT_GT(se, 0.0);
    }
}

// Fading: at a fixed concentration, Lambda ~ 1 / a_f and each glint ~ a_f, so
// the relative variance (4) scales as d^2 while flakes are smaller than the
// element (exact: everything else in (4) is the same); more flakes per
// element (a larger element, or a denser but still transparent paint) give
// proportionally less contrast.
TEST(Sparkle, FadesForSmallFlakesDenseFlakesAndLargeElements) {
    const SparkleGeometry g = geometry(45, 0, 38, 175, 1e4);
    const double big =
        SparkleModel(sparseFlakes(0.002, 20.0, 30.0), {.bands = 1}).evaluate(g).relative_variance;
    const double tiny =
        SparkleModel(sparseFlakes(0.002, 20.0, 1.0), {.bands = 1}).evaluate(g).relative_variance;
    EXPECT_NEAR(tiny / big, 1.0 / 900.0, 1e-9);
    // Ten times the flakes, little extinction (coverage 0.008 -> 0.08): ~1/10.
    const double sparse = SparkleModel(sparseFlakes(0.0002), {.bands = 1}).evaluate(g).relative_variance;
    const double dense = SparkleModel(sparseFlakes(0.002), {.bands = 1}).evaluate(g).relative_variance;
    EXPECT_NEAR(dense / sparse, 0.1, 0.01);
    // The sampled texture fades too: std/mean -> 0 as the element grows.
    const SparkleModel model(sparseFlakes(0.002), {.bands = 1});
    const Moments small_el = textureMoments(model.evaluate(geometry(45, 0, 38, 175, 1e5)), 100, 316.0);
    const Moments huge_el = textureMoments(model.evaluate(geometry(45, 0, 38, 175, 1e13)), 100, 3.162e6);
    EXPECT_GT(small_el.variance, 1.0);
    EXPECT_LT(huge_el.variance, 1e-3);
}

TEST(Sparkle, NoSparkleWithoutFlakesOrAlignedOnlyFlakes) {
    const SparkleGeometry g = geometry(45, 0, 38, 175, 1e4);
    EXPECT_FALSE(SparkleModel(test::oneLayerRecipe(1.5, 20.0, BlackSubstrate{}), {.bands = 1}).hasFlakes());
    const SparkleModel aligned(sparseFlakes(0.002, 0.0), {.bands = 1});  // spread 0: a mirror, no density
    EXPECT_FALSE(aligned.hasFlakes());
    EXPECT_EQ(aligned.evaluate(g).terms.size(), 0U);
    // Below the horizon: nothing.
    SparkleGeometry below = g;
    below.wo.z = -0.1;
    EXPECT_EQ(SparkleModel(sparseFlakes(), {.bands = 1}).evaluate(below).expected_glints, 0.0);
}

// Stability: the keys do not depend on the recipe, so a denser paint turns
// more of the same draws into glints (Poisson inversion is monotone in
// Lambda for a fixed uniform): every cell that glints at c glints at 2c. A
// light moved by many window widths meets other flakes: the glinting cells
// are then (nearly) independent of the first set.
TEST(Sparkle, TextureIsStableUnderRecipeChangesAndMovesWithTheLight) {
    const SparkleGeometry g = geometry(45, 0, 38, 175, 1e8);
    const SparkleStats thin = SparkleModel(sparseFlakes(0.002), {.bands = 1}).evaluate(g);
    const SparkleStats thick = SparkleModel(sparseFlakes(0.004), {.bands = 1}).evaluate(g);
    SparkleGeometry moved = g;
    moved.wi = directionFromAnglesDeg(47, 2);  // ~2 deg: the half vector moves ~4 window widths (0.18 deg)
    const SparkleStats other = SparkleModel(sparseFlakes(0.002), {.bands = 1}).evaluate(moved);
    int glints = 0;
    int both_moved = 0;
    int glints_moved = 0;
    for (int i = 0; i < 300; ++i)
        for (int j = 0; j < 300; ++j) {
            const auto key = sparkleCellKey(1e4 * i, 1e4 * j, 0.0, 1e4);
            double a = 0.0;
            double b = 0.0;
            double c = 0.0;
            drawSparkle(thin, key, {&a, 1});
            drawSparkle(thick, key, {&b, 1});
            drawSparkle(other, key, {&c, 1});
            if (a > -1.0) {
                ++glints;
                EXPECT_GT(b, -1.0);
            }
            if (c > -1.0) ++glints_moved;
            if (a > -1.0 && c > -1.0) ++both_moved;
        }
    ASSERT_GT(glints, 100);
    // Independent sets: E[both] = glints x P(moved); a 5 sigma bound (Poisson).
    const double expected = glints * (glints_moved / (300.0 * 300.0));
    EXPECT_LT(both_moved, expected + 5.0 * std::sqrt(expected) + 1.0);
}

// The effect planner builds its sparkle model on interference tables of 65
// cosines instead of 257 (linear interpolation in between). Convergence
// under refinement: the error of linear interpolation falls as the square of
// the spacing (h^2 f'' / 8), so 17 points (h = 1/16) must be ~16 times worse
// than 65 (h = 1/64), and the 65-point model's difference from the
// 257-point one is ~16/15 of its own error. Measured on this pearl: 7.4e-4
// at 65, 1.4e-2 at 17 (ratio 19). Budget 2e-3: the planner compares its
// estimates with tolerances of tenths of a CIEDE2000 unit, where 2e-3 of a
// flake term moves dE00 by under 0.08.
TEST(Sparkle, CoarseInterferenceTablesConvergeToTheFullModelsTables) {
    const Recipe r = test::smallPearlescent(test::pigment(0.01, 2.0, 0.5, 0.3), 0.2);
    const SparkleModel fine(r, {.bands = 3});
    const SparkleModel coarse(r, {.bands = 3, .flake_table_cosines = 65});
    const SparkleModel coarser(r, {.bands = 3, .flake_table_cosines = 17});
    double worst65 = 0.0;
    double worst17 = 0.0;
    for (const auto& [ti, to] :
         {std::pair{15.0, 0.0}, {45.0, 0.0}, {75.0, 0.0}, {30.0, 30.0}, {60.0, 10.0}}) {
        const SparkleGeometry g = geometry(ti, 0.0, to, 180.0, 1e6);
        const SparkleStats a = fine.evaluate(g);
        const SparkleStats b = coarse.evaluate(g);
        const SparkleStats c = coarser.evaluate(g);
        ASSERT_EQ(a.flake_brdf_per_sr.size(), b.flake_brdf_per_sr.size());
        for (std::size_t k = 0; k < a.flake_brdf_per_sr.size(); ++k) {
            ASSERT_GT(a.flake_brdf_per_sr[k], 0.0);
            worst65 = std::max(worst65, std::abs(b.flake_brdf_per_sr[k] / a.flake_brdf_per_sr[k] - 1.0));
            worst17 = std::max(worst17, std::abs(c.flake_brdf_per_sr[k] / a.flake_brdf_per_sr[k] - 1.0));
        }
    }
    std::printf("flake BRDF, tables of 65 / 17 cosines against 257: worst relative change %.2g / %.2g\n",
                worst65, worst17);
    EXPECT_LT(worst65, 2e-3);
    // Refinement works as linear interpolation does (16x from 17 to 65 points; 8x allowed).
    EXPECT_GT(worst17, 8.0 * worst65);
}

TEST(Sparkle, BadSettingsAreInputErrors) {
    EXPECT_THROW(SparkleModel(sparseFlakes(), {.bands = 0}), InputError);
    EXPECT_THROW(SparkleModel(sparseFlakes(), {.bands = 4, .flake_table_cosines = 3}), InputError);
    EXPECT_THROW(SparkleModel(sparseFlakes(), {.bands = 4, .slices_per_profiled_layer = 0}), InputError);
    Recipe bad = sparseFlakes();
    bad.layers[0].thickness_um = -1.0;
    EXPECT_THROW(SparkleModel(bad, {.bands = 1}), InputError);
}

}  // namespace
}  // namespace paintlab
