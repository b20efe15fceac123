// The fast model converges under refinement, and the flake kernels keep
// energy and reciprocity exact over the whole range of orientation spreads.
#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace paintlab {
namespace {

Recipe demo(const std::string& name) {
    return loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes" / (name + ".json"));
}

// Few bands (the spectral sampling is a separate knob, and colour needs only
// consistency between the runs compared) and a coarse start keep this cheap.
FastModelSettings coarse(int nodes, int orders) {
    FastModelSettings s;
    s.nodes = nodes;
    s.orders = orders;
    s.bands = 4;
    s.max_start_tau = 1.0 / 128.0;
    s.flake_polar = 8;
    s.flake_azimuth = 8;
    s.flake_table = 33;
    return s;
}

double worstDeltaE(const LayeredBrdf& a, const LayeredBrdf& b) {
    const auto ra = multiAngleColours(a);
    const auto rb = multiAngleColours(b);
    double worst = 0.0;
    for (std::size_t g = 0; g < ra.colours.size(); ++g)
        worst = std::max(worst, ciede2000(ra.colours[g].lab, rb.colours[g].lab));
    return worst;
}

class DemoConvergence : public ::testing::TestWithParam<std::string> {};

TEST_P(DemoConvergence, MultiAngleColourSettlesAsNodesDouble) {
    const Recipe recipe = demo(GetParam());
    const LayeredBrdf n12 = computeLayeredBrdf(recipe, coarse(12, 16));
    const LayeredBrdf n24 = computeLayeredBrdf(recipe, coarse(24, 16));
    const LayeredBrdf n48 = computeLayeredBrdf(recipe, coarse(48, 16));
    const double first = worstDeltaE(n12, n24);
    const double second = worstDeltaE(n24, n48);
    // Measured (Release, these settings): 12 -> 24 nodes 0.024 / 0.017 / 0.052
    // (pearlescent / silver / solid red), 24 -> 48 nodes 0.039 / 0.037 / 0.008.
    // The flake paints sit on a floor of ~0.04 that does not shrink further with
    // n (the grid moves with the binder's dispersion from band to band; the
    // reference preset's 64 -> 128 nodes also moves them by ~0.03), so the
    // bounds are ~3x the measured values, far below the 5-10 that the binned
    // flake kernels and linear interpolation gave.
    EXPECT_LT(first, 0.15);
    EXPECT_LT(second, 0.15);
}

TEST_P(DemoConvergence, MultiAngleColourSettlesAsOrdersDouble) {
    const Recipe recipe = demo(GetParam());
    FastModelSettings s = coarse(24, 8);
    s.order_tolerance = 0.0;  // compute every order asked for
    const LayeredBrdf m8 = computeLayeredBrdf(recipe, s);
    s.orders = 16;
    const LayeredBrdf m16 = computeLayeredBrdf(recipe, s);
    s.orders = 32;
    const LayeredBrdf m32 = computeLayeredBrdf(recipe, s);
    // The flakes' azimuthal lobes are Gaussian-like, so their Fourier
    // coefficients fall like exp(-m^2 s^2 / 2) with s >= 2 sigma (~0.35 rad).
    // Measured: 8 -> 16 orders 0.012 / 0.006 / 0.0003, 16 -> 32 orders
    // 0.0011 / < 1e-4 / < 1e-4; bounds ~4x. (Before, the mirror-direction
    // remainder carried every order at full weight, a delta in azimuth, and
    // the colour drifted by ~1 as orders were added.)
    EXPECT_LT(worstDeltaE(m8, m16), 0.05);
    EXPECT_LT(worstDeltaE(m16, m32), 0.005);
}

INSTANTIATE_TEST_SUITE_P(Demos, DemoConvergence,
                         ::testing::Values("pearlescent-two-layer", "silver-metallic", "solid-red"));

TEST(FastModelFlakes, NeutralAluminiumStaysNeutral) {
    // Aluminium reflects almost equally across the visible, so a silver
    // metallic must have small chroma at every geometry. The binned flake
    // kernels gave a* = 9.9 at 45as45 (aliasing between the per-band grids).
    const LayeredBrdf brdf = computeLayeredBrdf(demo("silver-metallic"), coarse(24, 16));
    for (const auto& c : multiAngleColours(brdf).colours) {
        EXPECT_LT(std::abs(c.lab.a), 1.5) << c.aspecular_deg;
        EXPECT_LT(std::abs(c.lab.b), 3.0) << c.aspecular_deg;
    }
}

Recipe whiteFlakes(double spread_deg, double reflectance, Substrate substrate) {
    Recipe r;
    r.name = "flakes";
    Layer layer;
    layer.name = "basecoat";
    layer.thickness_um = 15.0;
    layer.binder.refractive_index = Spectrum(1.5);
    MirrorFlake flake;
    flake.name = "mirror";
    flake.volume_fraction = 0.04;
    flake.thickness_um = 0.3;
    flake.diameter_um = 15.0;
    flake.orientation_spread_deg = spread_deg;
    flake.reflectance = Spectrum(reflectance);
    layer.components = {flake};
    r.layers = {layer};
    r.substrate = std::move(substrate);
    return r;
}

class FlakeSpread : public ::testing::TestWithParam<double> {};

TEST_P(FlakeSpread, WhiteFlakesOverAWhiteBaseLoseNothing) {
    // Lossless flakes over a white Lambertian base: the albedo is 1 in every
    // direction, whether the lobe is far narrower than the node spacing
    // (0.1 deg: all of it is the mirror-direction remainder), resolved (12
    // deg: Nystrom kernel scaled to the exact power) or random (90 deg).
    const LayeredBrdf brdf =
        computeLayeredBrdf(whiteFlakes(GetParam(), 1.0, LambertianSubstrate{Spectrum(1.0)}), coarse(16, 16));
    for (double a : brdf.bands()[0].albedo) EXPECT_NEAR(a, 1.0, 1e-6);  // round-off of the LU solves
}

TEST_P(FlakeSpread, GreyFlakesAreReciprocalAndFinite) {
    const LayeredBrdf brdf =
        computeLayeredBrdf(whiteFlakes(GetParam(), 0.6, LambertianSubstrate{Spectrum(0.3)}), coarse(16, 16));
    for (double a : brdf.bands()[0].albedo) {
        EXPECT_TRUE(std::isfinite(a));
        EXPECT_LE(a, 1.0 + 1e-6);
    }
    for (double ti : {5.0, 40.0, 80.0}) {
        for (double to : {0.0, 35.0, 89.0}) {
            const Direction wi = directionFromAnglesDeg(ti, 0.0);
            const Direction wo = directionFromAnglesDeg(to, 170.0);
            const auto f1 = brdf.eval(wi, wo);
            const auto f2 = brdf.eval(wo, wi);
            for (std::size_t b = 0; b < f1.size(); ++b) {
                EXPECT_TRUE(std::isfinite(f1[b]));
                // The kernels are symmetric by construction (Nystrom at the
                // nodes, symmetric scaling D K D, diagonal remainder) and the
                // interpolation uses one basis in both directions.
                EXPECT_NEAR(f1[b], f2[b], 1e-9 + 1e-6 * f1[b]) << ti << " <-> " << to;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Spreads, FlakeSpread, ::testing::Values(0.1, 2.0, 12.0, 45.0, 90.0));

TEST(FastModelInterpolation, PolynomialInAngleIsExactForSmoothTables) {
    // Index-matched absorber over a Lambertian base: f = rho/pi exp(-tau/mu_i - tau/mu_o)
    // is smooth in the polar angle, so interpolation through the Gauss nodes
    // (mirrored about the normal) is accurate far beyond the linear
    // interpolation's 1 % (test_layered_brdf.cpp).
    Recipe r;
    r.name = "absorber";
    Layer layer;
    layer.name = "layer";
    layer.thickness_um = 10.0;
    layer.binder.refractive_index = Spectrum(1.0);
    RawMedium raw;
    raw.name = "raw";
    raw.albedo = Spectrum(0.0);
    raw.optical_thickness = Spectrum(0.5);
    raw.hg_g = 0.0;
    layer.components = {raw};
    r.layers = {layer};
    r.substrate = LambertianSubstrate{Spectrum(0.8)};
    FastModelSettings s = coarse(24, 1);
    const LayeredBrdf brdf = computeLayeredBrdf(r, s);
    for (double ti : {0.0, 10.0, 35.0, 60.0}) {
        for (double to : {5.0, 50.0, 75.0}) {
            const Direction wi = directionFromAnglesDeg(ti, 0.0);
            const Direction wo = directionFromAnglesDeg(to, 90.0);
            const double expected = 0.8 / 3.141592653589793 * std::exp(-0.5 / wi.z - 0.5 / wo.z);
            EXPECT_NEAR(brdf.eval(wi, wo)[0], expected, 1e-5 * expected) << ti << " -> " << to;
        }
    }
}

}  // namespace
}  // namespace paintlab
