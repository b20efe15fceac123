// The flake-free bottom as one reflecting surface of the walk (mc_bottom.h,
// McSettings::bottom_operator): its sampling against its evaluation, energy,
// reciprocity, and the full model with it against the walk through those
// layers.
//
// Statistical tolerances: the full model with and without the operator are
// two independent estimates (different seeds); they pass when
// |a - b| <= 3 sqrt(se_a^2 + se_b^2) (3 combined sigma, two-sided 0.27 % per
// comparison under a normal error; the seeds are fixed, so a pass is
// reproducible). A weight 10 % off at the bottom fails AgreesWithTheWalk,
// ThreeLayerDemo, WhiteFurnace and SamplingMatchesEvaluation; an azimuth mirrored
// in the evaluation or in the draw fails AzimuthOfAForwardScatteringBottom. The operator's
// own quadrature and interpolation error (48 Gauss nodes, linear in mu between
// them; BottomOperator.Interpolation) is below 0.5 % within 80 degrees.

#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/multiangle.h"

#include "mc_bottom.h"
#include "mc_engine.h"
#include "test_recipes.h"
#include "z_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace paintlab {
namespace {

using test::expectClose;

constexpr double kPi = std::numbers::pi;
constexpr double kZ3 = 3.0;  // combined sigma (header)

Layer layer(const std::string& name, double thickness_um, double n) {
    Layer l;
    l.name = name;
    l.thickness_um = thickness_um;
    l.binder.refractive_index = Spectrum(n);
    return l;
}

// Clear coat (n 1.55, 20 µm) / 6 µm of sparse pearl flakes (n 1.5) / the given
// flake-free layers (n 1.5) over a Lambertian substrate of this albedo.
Recipe overBottom(const std::vector<Layer>& bottom, double substrate_albedo) {
    Recipe r = test::oneLayerRecipe(1.55, 20.0, LambertianSubstrate{Spectrum(substrate_albedo)});
    Layer flakes = layer("flakes", 6.0, 1.5);
    flakes.components = {test::interferenceFlake(0.01, 12.0, 15.0, 350.0, 60.0)};
    r.layers.push_back(flakes);
    for (const Layer& l : bottom) r.layers.push_back(l);
    return r;
}

// A coloured absorbing-scattering coat over a white one: the flake-free stack of test (1).
Recipe colouredBottom() {
    Layer tint = layer("tint", 8.0, 1.5);
    tint.components = {test::pigment(0.1, 1.5, 8.0, 0.3)};  // sigma_a 0.15, sigma_s 0.8 /µm
    Layer white = layer("white", 15.0, 1.5);
    white.components = {test::pigment(0.15, 0.0, 20.0, 0.5)};  // sigma_s 3 /µm, as the demo's white
    return overBottom({tint, white}, 0.5);
}

mc::BottomOperator operatorOf(const Recipe& recipe, std::size_t first_layer) {
    return {recipe, first_layer, 1.5, 550.0, 16};
}

mc::Vec3 down(double theta_deg, double phi_deg) {
    const double t = theta_deg * kPi / 180.0;
    const double p = phi_deg * kPi / 180.0;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), -std::cos(t)};
}

// int g(u) dOmega over the upper hemisphere by the midpoint rule in (mu^2, phi):
// dOmega = d(mu^2) dphi / (2 mu).
template <class G> double hemisphere(const G& g, int n_mu = 400, int n_phi = 360) {
    double sum = 0.0;
    for (int a = 0; a < n_mu; ++a) {
        const double mu = std::sqrt((a + 0.5) / n_mu);
        const double sin_t = std::sqrt(1.0 - mu * mu);
        for (int b = 0; b < n_phi; ++b) {
            const double phi = (b + 0.5) * 2.0 * kPi / n_phi;
            sum += g(mc::Vec3{sin_t * std::cos(phi), sin_t * std::sin(phi), mu}) / (2.0 * mu);
        }
    }
    return sum * (1.0 / n_mu) * (2.0 * kPi / n_phi);
}

mc::Vec3 up(double theta_deg, double phi_deg) {
    const mc::Vec3 d = down(theta_deg, phi_deg);
    return {d.x, d.y, -d.z};
}

// The multi-angle incidence (45 deg) with its six exits, and normal incidence with four.
std::vector<mc::IncidenceRequest> requests() {
    mc::IncidenceRequest oblique{multiAngleGeometry(kAspecularAnglesDeg[0]).wi, {}};
    for (double as : kAspecularAnglesDeg) oblique.wo.push_back(multiAngleGeometry(as).wo);
    mc::IncidenceRequest normal{directionFromAnglesDeg(0.0, 0.0),
                                {directionFromAnglesDeg(0.0, 0.0), directionFromAnglesDeg(30.0, 0.0),
                                 directionFromAnglesDeg(60.0, 90.0), directionFromAnglesDeg(75.0, 180.0)}};
    return {oblique, normal};
}

bool attaches(const Recipe& recipe) {
    mc::McSettings s;
    const mc::McEngine engine(recipe, s);
    return engine.band(550.0).stack.substrate == mc::SubstrateKind::Operator;
}

void expectSameResults(const mc::McResult& a, const mc::McResult& b, const std::string& what) {
    ASSERT_EQ(a.bands.size(), b.bands.size());
    for (std::size_t band = 0; band < a.bands.size(); ++band)
        for (std::size_t i = 0; i < a.bands[band].size(); ++i)
            test::expectSameIncidence(a.bands[band][i], b.bands[band][i],
                                      what + " " + std::to_string(a.wavelengths_nm[band]) + " nm incidence " +
                                          std::to_string(i) + ": ",
                                      kZ3);
}

// Test (3): the density sample() draws with integrates to 1 and is what its
// histogram shows (chi-square), and the weights f cos / pdf average to the
// integral of f cos, which is the tabulated albedo.
TEST(BottomOperator, SamplingMatchesEvaluation) {
    const mc::BottomOperator op = operatorOf(colouredBottom(), 2);
    mc::PathRng rng(3, 1, 4, 1);
    for (const double theta_i : {0.0, 35.0, 70.0, 88.0}) {
        const mc::Vec3 v = down(theta_i, 25.0);
        const std::string at = "theta_i " + std::to_string(theta_i);
        // Midpoint rule over 1200 x 360 cells: the pdf is constant on the
        // sampling cells (49 in mu, 128 in azimuth), so the few quadrature cells
        // that straddle their edges err by < 2e-3 of the total (2.8e-3 at 400 x 360).
        EXPECT_NEAR(hemisphere([&](const mc::Vec3& u) { return op.pdf(v, u); }, 1200), 1.0, 2e-3) << at;
        const double albedo = hemisphere([&](const mc::Vec3& u) { return op.eval(v, u) * u.z; });
        // f is continuous and the tabulated albedo is its exact integral (the rescaling).
        EXPECT_NEAR(albedo, op.albedo(-v.z), 2e-3 * albedo) << at;
        // Histogram of 200k draws in 8 x 8 cells of (mu^2, |dphi|) against the pdf's integrals.
        constexpr int kCells = 8;
        constexpr int kDraws = 200000;
        std::vector<double> counts(static_cast<std::size_t>(kCells) * kCells, 0.0);
        const auto cell = [](int a, int b) {
            return static_cast<std::size_t>(a) * kCells + static_cast<std::size_t>(b);
        };
        double sum = 0.0;
        double sum2 = 0.0;
        for (int d = 0; d < kDraws; ++d) {
            double factor = 0.0;
            const mc::Vec3 u = op.sample(v, rng, factor);
            // Each draw's weight is f cos / pdf of the direction it returns: a
            // sampler that returned another direction than the one it weighted
            // (say pi - dphi) could pass the histogram and the mean, not this.
            if (d % 997 == 0 && factor > 0.0) {
                EXPECT_NEAR(factor, op.eval(v, u) * u.z / op.pdf(v, u), 1e-9 * factor) << at;
            }
            sum += factor;
            sum2 += factor * factor;
            const double dphi =
                std::abs(std::remainder(std::atan2(u.y, u.x) - 25.0 * kPi / 180.0, 2.0 * kPi));
            const int a = std::min(kCells - 1, static_cast<int>(u.z * u.z * kCells));
            const int b = std::min(kCells - 1, static_cast<int>(dphi / kPi * kCells));
            counts[cell(a, b)] += 1.0;
        }
        const double mean = sum / kDraws;
        const double se = std::sqrt((sum2 / kDraws - mean * mean) / kDraws);
        expectClose(mean, se, albedo, 2e-3 * albedo, at + " mean weight");
        double chi2 = 0.0;
        for (int a = 0; a < kCells; ++a) {
            for (int b = 0; b < kCells; ++b) {
                // The cell's probability by a finer midpoint rule inside it (both signs of dphi).
                double p = 0.0;
                constexpr int kSub = 40;
                for (int i = 0; i < kSub; ++i) {
                    const double mu = std::sqrt((a + (i + 0.5) / kSub) / kCells);
                    for (int k = 0; k < kSub; ++k) {
                        const double phi = 25.0 * kPi / 180.0 + (b + (k + 0.5) / kSub) * kPi / kCells;
                        const double st = std::sqrt(1.0 - mu * mu);
                        p += op.pdf(v, {st * std::cos(phi), st * std::sin(phi), mu}) / (2.0 * mu);
                    }
                }
                p *= 2.0 * (1.0 / (kCells * kSub)) * (kPi / (kCells * kSub));
                const double expected = p * kDraws;
                const double diff = counts[cell(a, b)] - expected;
                chi2 += diff * diff / expected;
            }
        }
        // 63 degrees of freedom: mean 63, sd 11.2; 120 is 5 sd above (the cells' own
        // quadrature, ~1e-3 relative, adds < 1 to chi2 at these counts).
        std::printf("  %s: chi2 %.1f (63 dof)\n", at.c_str(), chi2);
        EXPECT_LT(chi2, 120.0) << at;
    }
}

// Against a closed form: a thin non-absorbing HG layer over a black substrate
// reflects by single scattering, f = p(v.u) (1 - e^(-tau (1/mu_i + 1/mu_o))) / (mu_i + mu_o)
// (p in 1/sr; the beam's radiance scattered along the exit path, integrated
// over depth), which fixes the azimuth's sign: forward scattering (g > 0)
// favours exits that go on in the incident azimuth. Tolerance 2 %: twice
// scattered light adds ~0.8 % at tau = 0.002 (at tau = 0.02 the operator and the
// walk both exceed the single-scattering form by 8 % at 45as-15-like back
// exits, where g = 0.5 scatters once weakly and twice through two mild angles).
TEST(BottomOperator, SingleScatteringClosedForm) {
    Layer thin = layer("haze", 1.0, 1.5);
    thin.components = {test::pigment(0.1, 0.0, 0.02, 0.5)};  // tau 0.002, g 0.5
    const Recipe recipe = overBottom({thin}, 0.0);
    const mc::BottomOperator op = operatorOf(recipe, 2);
    const double tau = 0.002;
    for (const double ti : {20.0, 50.0})
        for (const double to : {10.0, 40.0, 65.0})
            for (const double phi : {0.0, 90.0, 180.0}) {
                const mc::Vec3 v = down(ti, 0.0);
                const mc::Vec3 u = up(to, phi);
                const double mu_i = -v.z;
                const double mu_o = u.z;
                const double c = v.x * u.x + v.y * u.y + v.z * u.z;
                const double p = (1.0 - 0.25) / (4.0 * kPi * std::pow(1.0 + 0.25 - 2.0 * 0.5 * c, 1.5));
                const double exact = p * -std::expm1(-tau * (1.0 / mu_i + 1.0 / mu_o)) / (mu_i + mu_o);
                EXPECT_NEAR(op.eval(v, u), exact, 0.02 * exact) << ti << " " << to << " " << phi;
            }
}

// Reciprocity of the evaluation, f(v -> u) = f(-u -> -v): the adding and doubling
// is reciprocal; only the per-node rescaling (largestRescale) breaks it.
TEST(BottomOperator, Reciprocity) {
    const mc::BottomOperator op = operatorOf(colouredBottom(), 2);
    std::printf("  largest rescaling to the albedo: %.2e, orders %d\n", op.largestRescale(), op.orders());
    EXPECT_LT(op.largestRescale(), 0.01);
    for (const double ti : {5.0, 30.0, 60.0, 80.0})
        for (const double to : {10.0, 45.0, 75.0})
            for (const double phi : {0.0, 60.0, 180.0}) {
                const mc::Vec3 v = down(ti, 10.0);
                const mc::Vec3 u = up(to, 10.0 + phi);
                const double forward = op.eval(v, u);
                const double back = op.eval({-u.x, -u.y, -u.z}, {-v.x, -v.y, -v.z});
                EXPECT_NEAR(forward, back, (2.0 * op.largestRescale() + 1e-9) * forward)
                    << ti << " " << to << " " << phi;
            }
}

// The operator's error, quadrature and interpolation: the 48-node operator against
// a 96-node one at directions between the nodes.
TEST(BottomOperator, Interpolation) {
    const Recipe recipe = colouredBottom();
    const mc::BottomOperator coarse = operatorOf(recipe, 2);
    const mc::BottomOperator fine(recipe, 2, 1.5, 550.0, 16, 96);
    double worst = 0.0;
    double worst_grazing = 0.0;
    for (int a = 0; a < 30; ++a)
        for (int b = 0; b < 30; ++b)
            for (const double phi : {0.0, 90.0, 180.0}) {
                const double ti = 89.0 * (a + 0.37) / 30.0;
                const double to = 89.0 * (b + 0.61) / 30.0;
                const mc::Vec3 v = down(ti, 0.0);
                const mc::Vec3 u = up(to, phi);
                const double reference = fine.eval(v, u);
                const double error = std::abs(coarse.eval(v, u) - reference) / reference;
                (ti < 80.0 && to < 80.0 ? worst : worst_grazing) =
                    std::max(ti < 80.0 && to < 80.0 ? worst : worst_grazing, error);
            }
    std::printf("  %d nodes, linear in mu: largest relative error %.2e (both within 80 deg), %.2e (beyond)\n",
                mc::BottomOperator::kNodes, worst, worst_grazing);
    // Measured 4.8e-3 and 6.3e-3, at a near-normal exit after a near-grazing
    // incidence (docs/PERFORMANCE.md); below 0.4 % where both are within 60 deg.
    EXPECT_LT(worst, 6e-3);
    EXPECT_LT(worst_grazing, 1e-2);
}

// Test (2), energy: a non-absorbing white over a white substrate reflects
// everything, in the operator (the adding-doubling conserves to rounding) and in
// the full model with it (under flakes that reflect or pass all: R + T = 1).
TEST(BottomOperator, WhiteFurnace) {
    Layer white = layer("white", 25.0, 1.5);
    white.components = {test::pigment(0.15, 0.0, 23.0, 0.5)};
    const Recipe recipe = overBottom({white}, 1.0);
    const mc::BottomOperator op = operatorOf(recipe, 2);
    for (const double mu : {0.05, 0.3, 0.7, 1.0}) EXPECT_NEAR(op.albedo(mu), 1.0, 1e-9) << mu;
    ASSERT_TRUE(attaches(recipe));
    mc::McSettings s;
    s.max_paths = 4000;
    s.seed = 11;
    const std::vector<double> wavelengths{550.0};
    const mc::McResult r = mc::runMonteCarlo(recipe, wavelengths, requests(), s);
    for (const auto& inc : r.bands[0])
        expectClose(inc.albedo.mean, inc.albedo.std_error, 1.0, 0.0, "furnace albedo", test::kZ);
}

// Test (1): a coloured pigment stack under a clear coat and a sparse flake
// layer, by the full model with the operator and walking it, at two bands, the
// multi-angle geometries and four exits at normal incidence.
TEST(BottomOperator, AgreesWithTheWalk) {
    const Recipe recipe = colouredBottom();
    ASSERT_TRUE(attaches(recipe));
    mc::McSettings s;
    s.max_paths = 20000;
    s.seed = 5;
    const std::vector<double> wavelengths{450.0, 600.0};
    const mc::McResult with = mc::runMonteCarlo(recipe, wavelengths, requests(), s);
    s.bottom_operator = false;
    s.seed = 6;
    const mc::McResult without = mc::runMonteCarlo(recipe, wavelengths, requests(), s);
    expectSameResults(with, without, "coloured bottom");
}

// The operator's azimuth against the walk's, under a bottom whose f depends
// on it: a thin haze (tau 0.6, HG g 0.55, non-absorbing) over a black base,
// under the clear coat and the sparse pearl flakes. Its light is mostly
// scattered once, so f follows the phase function of the angle between the
// refracted ways in and out: brighter on the specular side (exits going on in
// the light's azimuth, phi 180 here) than on the light's own side (phi 0).
// g 0.55 is about the most the operator takes: its Fourier series must fall
// to 1e-7 within kOrders (32 orders at g 0.55; g 0.57 and above are walked,
// and the delta-M truncation at 48 nodes refuses g above 0.82), and the binder
// sees only directions within 42 deg of the normal, so the contrast is 1.4
// (28 -> 38 deg) rather than the several-fold of a grazing exit.
// What it catches (checked by planting each, 2026-12-05): the operator's
// evaluation mirrored (dphi -> pi - dphi) moves the exits by -15 % to +33 %
// (|z| 9-22 at 40k paths; AgreesWithTheWalk and SingleScatteringClosedForm fail
// too); a draw that returns the direction at pi - dphi but weights the one at
// dphi (so the connections, which evaluate, are right and only the paths that
// go on after the bottom are wrong) moves them by 2.5-4.5 % (all but the
// normal exit, 45as45, which has no azimuth), |z| 4.3-8.6 at these paths, and
// passes AgreesWithTheWalk, whose 53 optical depths of multiple scattering
// hide it (SamplingMatchesEvaluation's per-draw check fails as well).
// Tolerance: 3 combined sigma (header); 300k paths each (about 1.3 s) give the
// exits standard errors of 0.07-0.3 % (operator) and 0.35-0.55 % (walk), so
// 3 sigma is at most 1.9 %, below the 2.5 % a flipped draw moves them.
TEST(BottomOperator, AzimuthOfAForwardScatteringBottom) {
    Layer haze = layer("haze", 2.0, 1.5);
    haze.components = {test::pigment(0.1, 0.0, 3.0, 0.55)};  // sigma_s 0.3 /um: tau 0.6
    const Recipe recipe = overBottom({haze}, 0.0);
    ASSERT_TRUE(attaches(recipe));
    // The premise: the bottom's own f, forward against backward in azimuth,
    // along the refracted 45 deg incidence (28 deg in n 1.5) to a 38 deg exit
    // (measured 0.0321 and 0.0227 /sr).
    const mc::BottomOperator op = operatorOf(recipe, 2);
    const double forward = op.eval(down(28.0, 180.0), up(38.0, 180.0));
    const double backward = op.eval(down(28.0, 180.0), up(38.0, 0.0));
    EXPECT_GT(forward, 1.3 * backward);
    mc::IncidenceRequest oblique{multiAngleGeometry(kAspecularAnglesDeg[0]).wi, {}};
    for (double as : kAspecularAnglesDeg) oblique.wo.push_back(multiAngleGeometry(as).wo);
    // Out of the plane, on the specular side (phi 150, 120) and on the light's (30, 60).
    for (const auto& [theta, phi] : {std::pair{50.0, 150.0}, {50.0, 30.0}, {70.0, 120.0}, {70.0, 60.0}})
        oblique.wo.push_back(directionFromAnglesDeg(theta, phi));
    const std::vector<mc::IncidenceRequest> incidences{oblique};
    mc::McSettings s;
    s.max_paths = 300000;
    s.seed = 31;
    const std::vector<double> wavelengths{550.0};
    const mc::McResult with = mc::runMonteCarlo(recipe, wavelengths, incidences, s);
    s.bottom_operator = false;
    s.seed = 32;
    const mc::McResult without = mc::runMonteCarlo(recipe, wavelengths, incidences, s);
    expectSameResults(with, without, "forward-scattering haze");
}

// Test (4): the three-layer white pearl demo with explicit flakes, one band,
// the six multi-angle geometries (a short run: errors of several percent).
TEST(BottomOperator, ThreeLayerDemo) {
    const Recipe recipe = test::demoRecipe("three-layer");
    ASSERT_TRUE(attaches(recipe));
    mc::McSettings s;
    s.explicit_flakes = true;
    s.histogram_cone_deg = 5.0;
    s.max_paths = 6000;
    s.seed = 21;
    const std::vector<double> wavelengths{550.0};
    const std::vector<mc::IncidenceRequest> oblique{requests().front()};
    const mc::McResult with = mc::runMonteCarlo(recipe, wavelengths, oblique, s);
    s.bottom_operator = false;
    s.seed = 22;
    const mc::McResult without = mc::runMonteCarlo(recipe, wavelengths, oblique, s);
    expectSameResults(with, without, "three-layer");
}

// Where it does not apply, nothing changes: no flake-free bottom (the demo
// metallic and pearlescent), no flakes at all (solid red: the walk is the whole
// model), and an index step into the bottom (a mirror part).
TEST(BottomOperator, OnlyUnderTheLowestFlakes) {
    EXPECT_FALSE(attaches(test::demoRecipe("silver-metallic")));
    EXPECT_FALSE(attaches(test::demoRecipe("pearlescent-two-layer")));
    EXPECT_FALSE(attaches(test::demoRecipe("solid-red")));
    Layer white = layer("white", 25.0, 1.6);
    white.components = {test::pigment(0.15, 0.0, 23.0, 0.5)};
    EXPECT_FALSE(attaches(overBottom({white}, 0.6)));
    EXPECT_TRUE(attaches(test::demoRecipe("three-layer")));
}

}  // namespace
}  // namespace paintlab
