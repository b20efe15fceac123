// The fast model's angle-resolved BRDF where the phase function is sharply
// peaked (Henyey-Greenstein g up to 0.95), against
// tests/data/reference/sharp_phase_slabs.csv: index-matched slabs over a black
// surface, 10 slabs x 4 incidences x 16 views, grazing ones included. Its
// truth is the fast model converged far beyond the reference preset (96
// nodes and Legendre moments, 64 Fourier orders; sharp_phase_reference.cpp),
// checked here against two things stored beside it: the same model at 72
// nodes and 48 orders (convergence) and a Monte Carlo solution that shares no
// code with the engine (tools/reference_slab: exact single scattering plus a
// point estimator for the higher orders).
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/io/csv.h"

#include "test_recipes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

namespace paintlab {
namespace {

struct Row {
    double a, tau, g, theta_i, theta_o, phi_o;
    double mc, mc_error, truth, coarser;
};

std::vector<Row> referenceRows() {
    const std::string path = PAINTLAB_TEST_DATA_DIR "/reference/sharp_phase_slabs.csv";
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const io::CsvTable table = io::CsvTable::parse(text.str(), path);
    std::vector<Row> rows;
    for (const io::CsvRecord& r : table.records()) {
        const auto x = [&](const char* column) { return table.requiredNumber(r, column); };
        rows.push_back({x("albedo"), x("optical_thickness"), x("g"), x("theta_i_deg"), x("theta_o_deg"),
                        x("phi_o_deg"), x("mc_brdf_per_sr"), x("mc_standard_error_per_sr"),
                        x("converged_brdf_per_sr"), x("coarser_brdf_per_sr")});
    }
    return rows;
}

// "a 0.9 tau 1 g 0.9: 30 -> 75 at 180"
std::string where(const Row& r) {
    std::ostringstream out;
    out << "a " << r.a << " tau " << r.tau << " g " << r.g << ": " << r.theta_i << " -> " << r.theta_o
        << " at " << r.phi_o;
    return out.str();
}

// How far the truth itself may be off: three times its change from 72 to 96
// nodes, the bound for an error falling as 1/N (72 -> 96 removes a quarter of
// it). Below 5e-4 relative for 592 of the 640 values; at most 1.3 % where
// light and view are both grazing (80 -> 85 degrees) on the light's side,
// where the Monte Carlo's standard error is 3 % and settles nothing either.
double truthUncertainty(const Row& r) { return 3.0 * std::abs(r.coarser - r.truth); }

using SlabKey = std::tuple<double, double, double>;

// The preset's angular settings; raw media are grey, so two bands suffice.
// `sharp_lobe_cures` false: the tables alone on the preset's own grid, as the fast model was
// before it computed single scattering exactly and refined its grid for sharp lobes.
LayeredBrdf slabBrdf(const SlabKey& slab, Preset preset, bool sharp_lobe_cures = true) {
    Recipe r = test::oneLayerRecipe(1.0, 1.0, BlackSubstrate{});
    r.layers[0].components = {test::rawMedium(std::get<0>(slab), std::get<1>(slab), std::get<2>(slab))};
    FastModelSettings s = presetSettings(preset);
    s.bands = 2;
    s.output_bands = 0;
    s.exact_single_scattering = sharp_lobe_cures;
    if (!sharp_lobe_cures) {
        s.sharp_nodes = s.sharp_orders = 0;
        s.sharp_max_start_tau = 1.0;
    }
    return computeLayeredBrdf(r, s);
}

double evalAt(const LayeredBrdf& brdf, const Row& row) {
    return brdf.eval(directionFromAnglesDeg(row.theta_i, 0.0),
                     directionFromAnglesDeg(row.theta_o, row.phi_o))[0];
}

// The largest true value at each (slab, incidence).
std::map<std::tuple<double, double, double, double>, double>
largestPerIncidence(const std::vector<Row>& rows) {
    std::map<std::tuple<double, double, double, double>, double> largest;
    for (const Row& r : rows) {
        double& v = largest[{r.a, r.tau, r.g, r.theta_i}];
        v = std::max(v, r.truth);
    }
    return largest;
}

TEST(SharpPhaseReference, IsConvergedAndAgreesWithAnIndependentMonteCarlo) {
    const std::vector<Row> rows = referenceRows();
    ASSERT_EQ(rows.size(), 640U);
    double chi2 = 0.0;
    int converged = 0;
    for (const Row& r : rows) {
        // Convergence: 72 -> 96 nodes changes 592 of the 640 values by less than 0.05 %, a tenth
        // of the 0.5 % the reference preset is held to below, and none by more than 1.3 %
        // (grazing light and view; the tests below allow for it: truthUncertainty).
        EXPECT_NEAR(r.coarser, r.truth, 1.5e-2 * r.truth) << where(r);
        converged += std::abs(r.coarser / r.truth - 1.0) < 5e-4 ? 1 : 0;
        // The Monte Carlo value is a sum of many independent photons: within 4.5 standard errors
        // (640 values: a false alarm has odds of 1 in 300).
        const double z = (r.mc - r.truth) / r.mc_error;
        EXPECT_LT(std::abs(z), 4.5) << where(r);
        chi2 += z * z;
    }
    EXPECT_GE(converged, 590);
    // And no bias hiding in the spread: the mean squared z-score of 640 is 1 +- 0.06 (the 16
    // views of one incidence share photons, so the spread is wider: measured 1.01).
    EXPECT_NEAR(chi2 / static_cast<double>(rows.size()), 1.0, 0.25);
}

TEST(SharpPhase, ReferencePresetIsWithinHalfAPercentEverywhere) {
    const std::vector<Row> rows = referenceRows();
    std::map<SlabKey, LayeredBrdf> brdfs;
    double worst = 0.0;
    for (const Row& r : rows) {
        const SlabKey key{r.a, r.tau, r.g};
        auto it = brdfs.find(key);
        if (it == brdfs.end()) it = brdfs.emplace(key, slabBrdf(key, Preset::Reference)).first;
        const double value = evalAt(it->second, r);
        worst = std::max(worst, std::abs(value / r.truth - 1.0));
        EXPECT_NEAR(value, r.truth, 5e-3 * r.truth + truthUncertainty(r)) << where(r);
    }
    RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(SharpPhase, StandardPresetIsWithinTwoPercentWhereItMatters) {
    const std::vector<Row> rows = referenceRows();
    const auto largest = largestPerIncidence(rows);
    std::map<SlabKey, LayeredBrdf> brdfs;
    for (const Row& r : rows) {
        const SlabKey key{r.a, r.tau, r.g};
        auto it = brdfs.find(key);
        if (it == brdfs.end()) it = brdfs.emplace(key, slabBrdf(key, Preset::Standard)).first;
        const double value = evalAt(it->second, r);
        EXPECT_GT(value, 0.0) << "never zero where the truth is positive";
        // The goal: 2 % wherever the value is at least 1 % of the largest at that incidence.
        if (r.truth >= 0.01 * largest.at({r.a, r.tau, r.g, r.theta_i})) {
            EXPECT_NEAR(value, r.truth, 2e-2 * r.truth + truthUncertainty(r)) << where(r);
        }
    }
}

TEST(SharpPhase, TruncatedTablesAloneMissTheLobe) {
    // What the tests above guard against: the tables alone miss a g = 0.9 slab straight back
    // by 22 % at the reference preset (the delta-M series at 48 moments is wrong there) and
    // give zero at the standard one.
    const std::vector<Row> rows = referenceRows();
    const Row& normal = rows.front();
    ASSERT_EQ(normal.g, 0.9);
    ASSERT_EQ(normal.theta_i, 0.0);
    ASSERT_EQ(normal.theta_o, 0.0);
    const SlabKey key{normal.a, normal.tau, normal.g};
    EXPECT_LT(evalAt(slabBrdf(key, Preset::Reference, false), normal), 0.9 * normal.truth);
    EXPECT_LT(evalAt(slabBrdf(key, Preset::Standard, false), normal), 0.5 * normal.truth);
}

}  // namespace
}  // namespace paintlab
