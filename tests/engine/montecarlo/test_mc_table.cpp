// The full model tabulated on the fast model's basis (mc_table.h), and the
// transmittance estimate against published slab values.
//
// Statistics: the table's entries have standard errors over many paths
// (normal); eval() and colours of the table get theirs from the spread of
// kBatches per-batch tables, a Student t with kBatches - 1 = 15 degrees of
// freedom. Both are compared at kZ = 4.5: two-sided significance 7e-6 for the
// normal and 4e-4 for t(15) per comparison. Deterministic differences of the
// estimator are not hand-picked allowances but computed: the projection's
// cell bias and the grid's interpolation error come from a fine fast model
// (32 nodes) pushed through the same projection (cellAveragedTables below),
// added in quadrature as in test_monte_carlo.cpp.

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/layered/quadrature.h"
#include "paintlab/engine/montecarlo/mc_table.h"
#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/optics/fresnel.h"

#include "test_recipes.h"
#include "z_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

namespace paintlab {
namespace {

using test::mirrorFlake;
using test::oneLayerRecipe;
using test::pigment;
using test::rawMedium;

constexpr double kPi = std::numbers::pi;
constexpr double kZ = 4.5;
constexpr int kBatches = 16;

bool verbose() { return std::getenv("PAINTLAB_MC_VERBOSE") != nullptr; }

void expectWithin(double value, double se, double reference, double allowance, const std::string& what) {
    test::expectClose(value, se, reference, allowance, what, kZ);
}
// What the projection converges to if `fine` were the truth: per band of
// `grid`, f^m of `fine` (by the exact discrete cosine transform of its eval
// over 64 azimuths, divided by the top interface's transmittances) averaged
// with weight mu over each of the grid's cells (mc_table.h), 6 Gauss points
// per cell, except the orders m >= 1 at the node on the normal, which are 0
// (mc_table.cpp); and fine's albedo at the nodes.
std::vector<LayeredBrdf::BandTable> cellAveragedTables(const LayeredBrdf& fine, const LayeredBrdf& grid,
                                                       double n_top) {
    constexpr int kAzimuths = 64;  // > 2 x fine's orders: the transform of its Fourier series is exact
    std::vector<LayeredBrdf::BandTable> tables;
    for (std::size_t b = 0; b < grid.bands().size(); ++b) {
        const auto& g = grid.bands()[b];
        const auto n = g.mu.size();
        const auto orders = g.f.size();
        LayeredBrdf::BandTable t;
        t.f.assign(orders, Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(n)));
        t.albedo = Eigen::VectorXd::Zero(Eigen::Index(n));
        for (std::size_t j = 0; j < n; ++j) {
            const Direction wi{std::sqrt(1.0 - g.mu[j] * g.mu[j]), 0.0, g.mu[j]};
            const double t_i = 1.0 - fresnelDielectric(wi.z, n_top);
            t.albedo(Eigen::Index(j)) = fine.albedo(wi)[b];
            for (std::size_t i = 0; i < n; ++i) {
                const double lo = i == 0 ? 0.0 : 0.5 * (g.mu[i - 1] + g.mu[i]);
                const double hi = i + 1 == n ? 1.0 : 0.5 * (g.mu[i] + g.mu[i + 1]);
                std::vector<double> x;
                std::vector<double> w;
                layered::gaussLegendre(6, lo, hi, x, w);
                double norm = 0.0;
                for (std::size_t q = 0; q < x.size(); ++q) {
                    const double mu_o = x[q];
                    const double t_o = 1.0 - fresnelDielectric(mu_o, n_top);
                    const double s = std::sqrt(1.0 - mu_o * mu_o);
                    norm += w[q] * mu_o;
                    for (int a = 0; a < kAzimuths; ++a) {
                        const double phi = 2.0 * kPi * a / kAzimuths;
                        const double f =
                            fine.eval(wi, Direction{s * std::cos(phi), s * std::sin(phi), mu_o})[b];
                        const double delta = phi - kPi;  // from the incident propagation direction
                        for (std::size_t m = 0; m < orders; ++m)
                            t.f[m](Eigen::Index(i), Eigen::Index(j)) +=
                                w[q] * mu_o * f / (t_i * t_o) * std::cos(double(m) * delta) / kAzimuths;
                    }
                }
                for (std::size_t m = 0; m < orders; ++m) t.f[m](Eigen::Index(i), Eigen::Index(j)) /= norm;
                if (g.mu[i] == 1.0 || g.mu[j] == 1.0)
                    for (std::size_t m = 1; m < orders; ++m) t.f[m](Eigen::Index(i), Eigen::Index(j)) = 0.0;
            }
        }
        tables.push_back(std::move(t));
    }
    return tables;
}

struct Models {
    LayeredBrdf grid;      // the fast model on the table's grid
    LayeredBrdf fine;      // the fast model converged (32 nodes, 32 orders)
    LayeredBrdf expected;  // fine pushed through the projection on grid's basis
    mc::McTable table;
};

// The tables' grid: few nodes, orders and bands, so that every test runs in seconds.
FastModelSettings smallGrid(int nodes, int orders) {
    FastModelSettings gs;
    gs.nodes = nodes;
    gs.orders = orders;
    gs.bands = 2;
    return gs;
}

Models runModels(const Recipe& recipe, double n_top, std::int64_t paths_per_node) {
    const FastModelSettings gs = smallGrid(8, 6);
    FastModelSettings fs = gs;
    fs.nodes = 32;
    fs.orders = 32;
    mc::McSettings ms;
    ms.seed = 11;
    ms.max_paths = paths_per_node;
    ms.batches = kBatches;
    Models m{computeLayeredBrdf(recipe, gs), computeLayeredBrdf(recipe, fs), {}, {}};
    m.expected = LayeredBrdf::withTables(m.grid, cellAveragedTables(m.fine, m.grid, n_top), 0.0);
    m.table = mc::tabulateMonteCarlo(recipe, gs, ms);
    return m;
}

// The table entries against their expectation (fine model through the projection; its own error 0.2 %).
void checkEntries(const Models& m) {
    const auto& t = m.table.brdf.bands()[0];
    const auto& e = m.expected.bands()[0];
    const auto n = Eigen::Index(t.mu.size());
    for (Eigen::Index j = 0; j < n; ++j) {
        expectWithin(t.albedo(j), m.table.albedo_std_error[0](j), e.albedo(j), 2e-3 * e.albedo(j),
                     "albedo node " + std::to_string(j));
        for (std::size_t k = 0; k < t.f.size(); ++k)
            for (Eigen::Index i = 0; i < n; ++i)
                expectWithin(t.f[k](i, j), m.table.f_std_error[0][k](i, j), e.f[k](i, j),
                             2e-3 * std::abs(e.f[0](i, j)),
                             "f^" + std::to_string(k) + "(" + std::to_string(i) + "," + std::to_string(j) +
                                 ")");
    }
}

// eval() at the multi-angle geometries and in other directions: against the
// expectation (statistics only), the fast model on the same grid (plus the
// computed cell bias) and the full model's own next-event point estimate
// (plus the basis' error: expected vs fine).
void checkEval(const Recipe& recipe, const Models& m) {
    std::vector<std::pair<Direction, Direction>> pairs;
    pairs.reserve(kAspecularAnglesDeg.size() + 2);
    for (double as : kAspecularAnglesDeg)
        pairs.emplace_back(multiAngleGeometry(as).wi, multiAngleGeometry(as).wo);
    pairs.emplace_back(directionFromAnglesDeg(10.0, 0.0), directionFromAnglesDeg(50.0, 90.0));
    pairs.emplace_back(directionFromAnglesDeg(60.0, 0.0), directionFromAnglesDeg(30.0, 150.0));
    pairs.emplace_back(directionFromAnglesDeg(15.0, 0.0), directionFromAnglesDeg(0.0, 0.0));  // on the normal
    std::vector<mc::IncidenceRequest> requests;
    requests.reserve(pairs.size());
    for (const auto& [wi, wo] : pairs) requests.push_back({wi, {wo}});
    mc::McSettings ms;
    ms.seed = 5;
    ms.max_paths = 40000;
    const mc::McResult point =
        mc::runMonteCarlo(recipe, std::vector<double>{m.grid.wavelengthsNm()[0]}, requests, ms);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        const auto& [wi, wo] = pairs[p];
        std::vector<double> per_batch;
        for (const auto& b : m.table.batch_brdfs) per_batch.push_back(b.eval(wi, wo)[0]);
        const mc::Estimate batch = mc::batchEstimate(per_batch);
        const double f = m.table.brdf.eval(wi, wo)[0];
        const double expected = m.expected.eval(wi, wo)[0];
        const double fast = m.grid.eval(wi, wo)[0];
        const double fine = m.fine.eval(wi, wo)[0];
        const std::string where = "eval pair " + std::to_string(p);
        expectWithin(f, batch.std_error, expected, 2e-3 * fine, where + " vs expectation");
        expectWithin(f, batch.std_error, fast, std::abs(expected - fast) + 2e-3 * fine, where + " vs fast");
        const mc::Estimate& ne = point.bands[0][p].brdf_per_sr[0];
        expectWithin(f, std::hypot(batch.std_error, ne.std_error), ne.mean, std::abs(expected - fine),
                     where + " vs next-event");
    }
}

// Multi-angle colours of the table against the fast model's, with the
// difference the projection alone makes (expected vs fast) as the allowance.
void checkColours(const Models& m) {
    const MultiAngleReport table = multiAngleColours(m.table.brdf);
    const MultiAngleReport fast = multiAngleColours(m.grid);
    const MultiAngleReport expected = multiAngleColours(m.expected);
    std::vector<MultiAngleReport> batches;
    for (const auto& b : m.table.batch_brdfs) batches.push_back(multiAngleColours(b));
    for (std::size_t g = 0; g < kAspecularAnglesDeg.size(); ++g) {
        const auto component = [&](const MultiAngleReport& r, int c) {
            const Lab& lab = r.colours[g].lab;
            return c == 0 ? lab.L : (c == 1 ? lab.a : lab.b);
        };
        for (int c = 0; c < 3; ++c) {
            std::vector<double> per_batch;
            per_batch.reserve(batches.size());
            for (const auto& r : batches) per_batch.push_back(component(r, c));
            const mc::Estimate e = mc::batchEstimate(per_batch);
            const double allowance = std::abs(component(expected, c) - component(fast, c));
            expectWithin(component(table, c), e.std_error, component(fast, c), allowance,
                         "Lab[" + std::to_string(c) + "] at " + std::to_string(kAspecularAnglesDeg[g]));
        }
    }
}

TEST(McTable, PigmentSlabMatchesFastModelAndPointEstimates) {
    const double n = 1.5;
    Recipe r = oneLayerRecipe(n, 20.0, LambertianSubstrate{Spectrum(0.5)});
    r.layers[0].components = {pigment(0.1, 0.5, 10.0, 0.4)};
    const Models m = runModels(r, n, 40000);
    ASSERT_EQ(m.table.batch_brdfs.size(), std::size_t(kBatches));
    checkEntries(m);
    checkEval(r, m);
    checkColours(m);
}

TEST(McTable, FlakeRecipeMatchesFastModelAndPointEstimates) {
    const double n = 1.5;
    Recipe r = oneLayerRecipe(n, 20.0, BlackSubstrate{});
    r.layers[0].components = {mirrorFlake(0.02, 20.0, 0.9), pigment(0.05, 0.2, 4.0, 0.3)};
    const Models m = runModels(r, n, 40000);
    checkEntries(m);
    checkEval(r, m);
    checkColours(m);
}

// In the incidence plane the view crossing the normal turns the azimuth
// difference by pi, so the table's odd orders change sign there; a BRDF is
// continuous, so both one-sided limits must equal the value on the normal.
// At +-kEps = 0.01 deg a continuous BRDF changes by about the fast model's
// |f(+eps) - f(-eps)| on the same grid (~1e-5 of f), the allowance. The step
// of the table may be at most one standard error of its value on the normal
// (over the batch tables): a step below the value's own noise cannot be seen
// in any plot of it, a larger one is an artefact (both sides come from the
// same paths). Each batch table must be continuous too. What the steps
// were before the node on the normal held 0: docs/VALIDATION.md.
void checkContinuousAtNormal(const mc::McTable& table, const LayeredBrdf& fast, const std::string& paint) {
    constexpr double kEps = 0.01;
    const Direction plus = directionFromAnglesDeg(kEps, 0.0);
    const Direction minus = directionFromAnglesDeg(kEps, 180.0);
    const Direction normal{0.0, 0.0, 1.0};
    for (double theta_i : {15.0, 45.0}) {
        const Direction wi = directionFromAnglesDeg(theta_i, 0.0);
        for (std::size_t b = 0; b < table.brdf.bands().size(); ++b) {
            std::vector<double> at_normal;
            double batch_step = 0.0;
            for (const auto& t : table.batch_brdfs) {
                at_normal.push_back(t.eval(wi, normal)[b]);
                batch_step = std::max(batch_step, std::abs(t.eval(wi, plus)[b] - t.eval(wi, minus)[b]));
            }
            const double se = mc::batchEstimate(at_normal).std_error;
            const double step = table.brdf.eval(wi, plus)[b] - table.brdf.eval(wi, minus)[b];
            const double allowance = std::abs(fast.eval(wi, plus)[b] - fast.eval(wi, minus)[b]);
            const std::string what =
                paint + ", light at " + std::to_string(theta_i) + " deg, band " + std::to_string(b);
            if (verbose())
                std::printf("  %s: f %.5f +- %.5f, step %.3g (%.2f se), largest batch step %.3g\n",
                            what.c_str(), table.brdf.eval(wi, normal)[b], se, step, step / se, batch_step);
            ASSERT_GT(se, 0.0) << what;
            EXPECT_LE(std::abs(step), se + allowance) << what;
            // Each batch table within its own standard deviation (sqrt(batches) standard errors).
            EXPECT_LE(batch_step, std::sqrt(double(kBatches)) * se + allowance) << what;
        }
    }
}

TEST(McTable, ContinuousAcrossTheNormal) {
    const FastModelSettings gs = smallGrid(8, 6);
    mc::McSettings ms;
    ms.seed = 3;
    ms.max_paths = 8000;  // per node, reduced: the criterion scales with the noise
    ms.batches = kBatches;
    // A flake paint: aluminium-like mirror flakes (12 deg spread) and a little pigment over black.
    Recipe flakes = oneLayerRecipe(1.5, 20.0, BlackSubstrate{});
    flakes.layers[0].components = {mirrorFlake(0.02, 12.0, 0.9), pigment(0.05, 0.2, 4.0, 0.3)};
    // A pigment paint over a grey base.
    Recipe pigmented = oneLayerRecipe(1.5, 20.0, LambertianSubstrate{Spectrum(0.5)});
    pigmented.layers[0].components = {pigment(0.1, 0.5, 10.0, 0.4)};
    for (const auto& [recipe, paint] :
         {std::pair{flakes, "flake paint"}, std::pair{pigmented, "pigment paint"}}) {
        const mc::McTable table = mc::tabulateMonteCarlo(recipe, gs, ms);
        ASSERT_EQ(table.batch_brdfs.size(), std::size_t(kBatches));
        checkContinuousAtNormal(table, computeLayeredBrdf(recipe, gs), paint);
    }
}

TEST(McTable, SameSeedSameTable) {
    Recipe r = oneLayerRecipe(1.5, 10.0, BlackSubstrate{});
    r.layers[0].components = {rawMedium(0.9, 1.0, 0.5)};
    const FastModelSettings gs = smallGrid(4, 3);
    mc::McSettings ms;
    ms.max_paths = 3000;
    ms.threads = 1;
    const mc::McTable one = mc::tabulateMonteCarlo(r, gs, ms);
    ms.threads = 2;
    const mc::McTable two = mc::tabulateMonteCarlo(r, gs, ms);
    for (std::size_t b = 0; b < one.brdf.bands().size(); ++b) {
        EXPECT_EQ(one.brdf.bands()[b].albedo, two.brdf.bands()[b].albedo);
        for (std::size_t k = 0; k < one.brdf.bands()[b].f.size(); ++k)
            EXPECT_EQ(one.brdf.bands()[b].f[k], two.brdf.bands()[b].f[k]);
    }
}

// Prahl's adding-doubling totals for an index-matched slab at normal
// incidence (as quoted in the iadpython tests; tests/engine/layered/
// test_slab_totals.cpp uses them too): UR1 reflected, UT1 transmitted (the
// unscattered beam included). The slab: a raw medium in a binder of index 1,
// in air, over a transparent substrate of index 1. The criterion is
// 3 standard errors (two-sided significance 0.27 % per comparison).
TEST(McTransmittance, IndexMatchedSlabsEqualPublishedTotals) {
    struct Case {
        double a, b, g, UR1, UT1;
    };
    for (const Case& c : {Case{0.8, 1.0, 0.0, 0.21085, 0.54140}, Case{0.8, 1.0, 0.8, 0.03041, 0.76388}}) {
        Recipe r = oneLayerRecipe(1.0, 10.0, TransparentSubstrate{1.0});
        r.layers[0].components = {rawMedium(c.a, c.b, c.g)};
        mc::McSettings ms;
        ms.seed = 2;
        ms.max_paths = 100000;
        const std::vector<mc::IncidenceRequest> normal{{directionFromAnglesDeg(0.0, 0.0), {}}};
        const mc::McResult mc = mc::runMonteCarlo(r, std::vector<double>{550.0}, normal, ms);
        const auto& inc = mc.bands[0][0];
        const std::string what = "a " + std::to_string(c.a) + " g " + std::to_string(c.g);
        if (verbose())
            std::printf("  %s: UR1 %.5f +- %.5f (%.5f), UT1 %.5f +- %.5f (%.5f)\n", what.c_str(),
                        inc.albedo.mean, inc.albedo.std_error, c.UR1, inc.transmittance.mean,
                        inc.transmittance.std_error, c.UT1);
        EXPECT_NEAR(inc.albedo.mean, c.UR1, 3.0 * inc.albedo.std_error) << what;
        EXPECT_NEAR(inc.transmittance.mean, c.UT1, 3.0 * inc.transmittance.std_error) << what;
        EXPECT_GT(inc.transmittance.std_error, 0.0);
    }
}

TEST(McTransmittance, ZeroWithoutTransparentSubstrate) {
    Recipe r = oneLayerRecipe(1.5, 10.0, LambertianSubstrate{Spectrum(0.5)});
    r.layers[0].components = {rawMedium(0.8, 1.0, 0.0)};
    mc::McSettings ms;
    ms.max_paths = 2000;
    const std::vector<mc::IncidenceRequest> normal{{directionFromAnglesDeg(0.0, 0.0), {}}};
    const mc::McResult mc = mc::runMonteCarlo(r, std::vector<double>{550.0}, normal, ms);
    EXPECT_EQ(mc.bands[0][0].transmittance.mean, 0.0);
}

}  // namespace
}  // namespace paintlab
