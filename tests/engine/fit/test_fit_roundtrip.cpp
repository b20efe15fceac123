// The fitter against its own forward model (issue 28, part 4): recipes drawn
// at random around each demo structure, measured with the simulated noise of
// observations.h, fitted back. The truth is known, so recovery, the sigma
// calibration and the identifiability verdicts can be checked against it.
// Everything runs at the preview preset (search and polish), the same preset
// that simulated the measurement: the model is then exact and the residuals
// are the noise alone, which is what makes sigma testable.

#include "fit_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace paintlab {
namespace {

using fit::FitResult;
using fit::Observations;

Observations multiAngle(fit::Side side = fit::Side::Top) {
    Observations o;
    o.multi_angle.push_back(fit::standardMultiAngleMeasurement(side));
    return o;
}

// An in-plane and out-of-plane grid of RGB BRDF samples (incidence 15-60°,
// 3 x 4 x 6 = 72 samples), each with 1 % noise on ln(1 + f cos θi): a good
// goniophotometer's repeatability. With the default 5 % these few samples
// leave the flake concentration to within about a tenth of its range only.
Observations brdfGrid() {
    Observations o;
    fit::BrdfMeasurement m;
    m.name = "gonio grid";
    for (double ti : {15.0, 35.0, 60.0})
        for (double to : {10.0, 30.0, 50.0, 70.0})
            for (double po : {0.0, 30.0, 90.0, 150.0, 170.0, 180.0})
                m.samples.push_back({ti, 0.0, to, po, {0, 0, 0}, 0.01});
    o.brdf.push_back(m);
    return o;
}

fit::FitSettings quickSettings(int starts) {
    fit::FitSettings s;
    s.starts = starts;
    s.search_preset = Preset::Preview;
    s.polish_preset = Preset::Preview;
    s.polish_count = 1;
    s.search_iterations = 4;
    s.polish_iterations = 20;
    return s;
}

// The truth: the demo with each free parameter scaled by a factor drawn
// uniformly in [0.85, 1.15] (a batch that drifted).
Recipe drawAround(const Recipe& demo, const std::vector<std::string>& paths, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> factor(0.85, 1.15);
    Recipe truth = demo;
    for (const auto& path : paths)
        fit::setParameterValue(truth, path, fit::parameterValue(demo, path) * factor(rng));
    return truth;
}

FitResult fitBack(const Recipe& truth, const Recipe& start, const std::vector<std::string>& paths,
                  const Observations& geometry, std::uint64_t seed, int starts = 1) {
    fit::FitProblem p = test::syntheticProblem(truth, start, paths, geometry, Preset::Preview, seed);
    p.settings = quickSettings(starts);
    return fit::fitRecipe(p);
}

// Every parameter within 3 sigma of the truth: 99.7 % each for a calibrated
// sigma (the calibration test below checks it is not too wide), and the
// determined ones with a sigma below a tenth of their bound range, so the
// check cannot pass by a vague answer.
void expectRecovered(const FitResult& r, const Recipe& truth) {
    for (const auto& p : r.parameters) {
        const double t = fit::parameterValue(truth, p.path);
        EXPECT_TRUE(p.determined) << p.path;
        EXPECT_LE(std::abs(p.value - t), 3.0 * p.sigma)
            << p.path << " " << p.value << " ± " << p.sigma << ", truth " << t;
        EXPECT_LT(p.sigma, 0.1 * (p.upper - p.lower)) << p.path;
    }
    // The noise is about 0.25 ΔE00 (observations.h); a fit at the truth's
    // preset leaves that and no model error.
    for (const auto& g : r.geometries) EXPECT_LT(g.delta_e00, 1.5) << g.aspecular_deg;
    EXPECT_GT(r.evaluations, 0);
    EXPECT_GT(r.modelShare(), 0.5);  // the fast model dominates a fit's time
}

// Draws a truth around `demo` (seed), fits it back from the demo and checks the recovery.
FitResult roundTrip(const Recipe& demo, const std::vector<std::string>& paths, const Observations& geometry,
                    std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    const Recipe truth = drawAround(demo, paths, rng);
    FitResult r = fitBack(truth, demo, paths, geometry, seed + 100);
    expectRecovered(r, truth);
    return r;
}

// The demo's red, thinned to 3 µm of 3 % so that the primer shows through:
// then the concentration, the primer and the pigment's anisotropy all matter.
Recipe semiHidingSolid() {
    Recipe demo = test::demoRecipe("solid-red");
    demo.layers[1].thickness_um = 3.0;
    fit::setParameterValue(demo, "layers[1].components[0].volume_fraction", 0.03);
    return demo;
}

const std::vector<std::string> kMetallicPaths{"layers[1].components[0].volume_fraction",
                                              "layers[1].components[0].orientation_spread_deg"};

TEST(FitRoundTrip, SemiHidingSolid) {
    roundTrip(semiHidingSolid(),
              {"layers[1].components[0].volume_fraction", "substrate.albedo", "layers[1].components[0].hg_g"},
              multiAngle(), 1);
}

TEST(FitRoundTrip, Metallic) {
    roundTrip(test::demoRecipe("silver-metallic"), kMetallicPaths, multiAngle(), 2);
}

TEST(FitRoundTrip, MetallicFromRgbBrdfSamples) {
    const FitResult r = roundTrip(test::demoRecipe("silver-metallic"), kMetallicPaths, brdfGrid(), 3);
    ASSERT_EQ(r.residuals.size(), brdfGrid().brdf[0].samples.size());
    for (const auto& o : r.residuals) EXPECT_EQ(o.kind, fit::ObservationKind::BrdfSample);
}

// Per-wavelength BRDF samples (400-700 nm, 10 nm) at a coarser grid (36 samples).
TEST(FitRoundTrip, MetallicFromSpectralBrdfSamples) {
    Observations geometry = brdfGrid();
    fit::BrdfMeasurement& m = geometry.brdf[0];
    m.values = fit::BrdfValues::Spectral;
    m.wavelengths_nm = uniformWavelengthGrid(400.0, 700.0, 10.0);
    std::vector<fit::BrdfSample> every_second;
    for (std::size_t k = 0; k < m.samples.size(); k += 2) {
        every_second.push_back(m.samples[k]);
        every_second.back().values.assign(m.wavelengths_nm.size(), 0.0);
    }
    m.samples = every_second;
    const FitResult r = roundTrip(test::demoRecipe("silver-metallic"), kMetallicPaths, geometry, 6);
    EXPECT_EQ(r.residual_count, 36U * 31U);
}

TEST(FitRoundTrip, Pearlescent) {
    roundTrip(test::demoRecipe("pearlescent-two-layer"),
              {"layers[1].components[0].volume_fraction", "layers[1].components[0].tio2_thickness_nm",
               "layers[1].components[0].orientation_spread_deg"},
              multiAngle(), 4);
}

TEST(FitRoundTrip, ThreeLayer) {
    roundTrip(test::demoRecipe("three-layer"),
              {"layers[1].components[0].volume_fraction", "layers[1].components[0].tio2_thickness_nm"},
              multiAngle(), 5);
}

// Sigma calibration: over 50 synthetic fits of a semi-hiding solid (two free
// parameters, 100 checks), the truth lies within ±2 sigma in 90-98 % of the
// checks (95.4 % for a calibrated Gaussian sigma; the window is about
// -2.6 and +1.2 binomial standard deviations of 100 checks around it, and the
// seeds are fixed, so the test is deterministic). Measured: see VALIDATION.md.
TEST(FitCalibration, TwoSigmaCoverageOfFiftyFits) {
    const Recipe demo = semiHidingSolid();
    const std::vector<std::string> paths{"layers[1].components[0].volume_fraction", "substrate.albedo"};
    std::mt19937_64 rng(28);
    int inside = 0;
    int checks = 0;
    double worst_z = 0.0;
    for (int k = 0; k < 50; ++k) {
        const Recipe truth = drawAround(demo, paths, rng);
        const FitResult r = fitBack(truth, demo, paths, multiAngle(), 1000 + static_cast<std::uint64_t>(k));
        for (const auto& p : r.parameters) {
            const double z = std::abs(p.value - fit::parameterValue(truth, p.path)) / p.sigma;
            worst_z = std::max(worst_z, z);
            inside += z <= 2.0 ? 1 : 0;
            ++checks;
        }
    }
    const double coverage = static_cast<double>(inside) / checks;
    RecordProperty("coverage_2sigma", std::to_string(coverage));
    std::printf("2-sigma coverage %d / %d = %.3f, largest |error|/sigma %.2f\n", inside, checks, coverage,
                worst_z);
    EXPECT_GE(coverage, 0.90);
    EXPECT_LE(coverage, 0.98);
}

// An opaque layer hides what is below it and its own thickness: the fitter
// must say so rather than report the thickness with a small sigma.
TEST(FitIdentifiability, OpaqueLayerThicknessIsUndetermined) {
    const Recipe demo = test::demoRecipe("solid-red");  // 25 µm of 10 % hematite: opaque
    Recipe start = demo;
    start.layers[1].thickness_um = 30.0;
    const std::vector<std::string> paths{"layers[1].thickness_um", "layers[1].components[0].hg_g"};
    const FitResult r = fitBack(demo, start, paths, multiAngle(), 7);
    std::printf("opaque: thickness %.2f ± %.1f µm (truth 25), hg_g %.4f ± %.4f\n", r.parameters[0].value,
                r.parameters[0].sigma, r.parameters[1].value, r.parameters[1].sigma);
    EXPECT_FALSE(r.parameters[0].determined);
    EXPECT_TRUE(r.parameters[1].determined);  // the pigment's anisotropy shows in every geometry
    const bool said = std::any_of(r.identifiability.begin(), r.identifiability.end(), [](const auto& issue) {
        return issue.kind == fit::IdentifiabilityKind::Undetermined &&
               issue.paths.front() == "layers[1].thickness_um" &&
               issue.message.find("not determined") != std::string::npos;
    });
    EXPECT_TRUE(said);
}

// The paper's two-sided case: a pearl coating whose flake concentration rises
// with depth, on a transparent carrier. From the top alone the gradient and
// the amount of flakes trade off; seen from both sides they separate.
TEST(FitIdentifiability, TwoSidedMeasurementSeparatesADepthGradient) {
    Recipe truth = test::demoRecipe("pearlescent-two-layer");
    truth.substrate = TransparentSubstrate{1.5};
    std::get<InterferenceFlake>(truth.layers[1].components[0]).depth_profile =
        DepthProfile{{0.0, 1.0}, {0.4, 1.6}};
    Recipe start = truth;
    std::get<InterferenceFlake>(start.layers[1].components[0]).depth_profile =
        DepthProfile{{0.0, 1.0}, {0.4, 1.0}};
    const std::vector<std::string> paths{"layers[1].components[0].volume_fraction",
                                         "layers[1].components[0].depth_profile.weight[1]"};

    const FitResult top = fitBack(truth, start, paths, multiAngle(), 8);
    EXPECT_FALSE(top.parameters[1].determined);
    const bool said =
        std::any_of(top.identifiability.begin(), top.identifiability.end(), [](const auto& issue) {
            return std::find(issue.paths.begin(), issue.paths.end(),
                             "layers[1].components[0].depth_profile.weight[1]") != issue.paths.end();
        });
    EXPECT_TRUE(said);

    Observations both = multiAngle();
    both.multi_angle.push_back(fit::standardMultiAngleMeasurement(fit::Side::Bottom));
    const FitResult two = fitBack(truth, start, paths, both, 8);
    for (const FitResult* r : {&top, &two})
        std::printf("%s: weight[1] %.4f ± %.4f (truth 1.6), volume fraction %.5f ± %.5f, correlation %.4f\n",
                    r == &top ? "top" : "both sides", r->parameters[1].value, r->parameters[1].sigma,
                    r->parameters[0].value, r->parameters[0].sigma, r->correlation[1]);
    expectRecovered(two, truth);
    // Sharper than from the top by more than a factor 5 (measured: ~20).
    EXPECT_LT(5.0 * two.parameters[1].sigma, top.parameters[1].sigma);
}

// Different recipes can look alike: the pearl's interference colour repeats
// as its TiO2 coating thickens by about λ / (2 n_TiO2) (~105 nm at 550 nm),
// so an instrument that reads only 540-560 nm, to 5 % (a handheld sorting
// instrument), sees the truth (120 nm) and a ~232 nm coating nearly alike
// (costs 6.5 and 10.6 with this seed). Alternatives are asked for within 4.5
// in cost (9 in chi-square: 3 sigma). The fit must show both minima; with the
// whole spectrum the hue tells them apart (the other order costs > 1,000
// more) and no alternative is left.
TEST(FitAlternatives, NarrowBandReadingShowsTheOtherInterferenceOrder) {
    const Recipe truth = test::demoRecipe("pearlescent-two-layer");  // TiO2 120 nm
    const std::string path = "layers[1].components[0].tio2_thickness_nm";
    Recipe start = truth;
    fit::setParameterValue(start, path, 200.0);
    const auto fitWith = [&](std::vector<double> wavelengths_nm) {
        Observations o;
        o.multi_angle.push_back(
            fit::standardMultiAngleMeasurement(fit::Side::Top, std::move(wavelengths_nm)));
        for (auto& reading : o.multi_angle[0].readings) reading.reflectance_relative_noise = 0.05;
        fit::FitProblem p = test::syntheticProblem(truth, start, {path}, o, Preset::Preview, 41);
        p.free[0].lower = 40.0;
        p.free[0].upper = 340.0;
        // Every start searched: the other order's basin is ~10 nm wide in a
        // 300 nm range, narrower than the starts' spacing, and the scatter's
        // one cost per start need not rank the start nearest it among the best.
        p.settings = quickSettings(12);
        p.settings.searches = 12;
        p.settings.polish_count = 4;
        p.settings.alternative_cost_abs = 4.5;
        return fit::fitRecipe(p);
    };

    const FitResult narrow = fitWith({540.0, 550.0, 560.0});
    std::vector<double> minima{narrow.parameters[0].value};
    for (const auto& alt : narrow.alternatives) minima.push_back(alt.values[0]);
    for (double v : minima) std::printf("narrow band: minimum at %.1f nm\n", v);
    ASSERT_FALSE(narrow.alternatives.empty()) << "best " << narrow.parameters[0].value;
    // One minimum is the truth (within 3 sigma of the best's uncertainty, or
    // 5 nm where the alternative's is not computed); another is a different
    // interference order, more than half a period away.
    const double tolerance = std::max(5.0, 3.0 * narrow.parameters[0].sigma);
    EXPECT_TRUE(
        std::any_of(minima.begin(), minima.end(), [&](double v) { return std::abs(v - 120.0) < tolerance; }));
    EXPECT_TRUE(
        std::any_of(minima.begin(), minima.end(), [&](double v) { return std::abs(v - 120.0) > 50.0; }));
    for (const auto& alt : narrow.alternatives)
        EXPECT_LE(alt.cost, narrow.cost + std::max(4.5, 0.25 * narrow.cost));

    const FitResult full = fitWith({});
    std::printf("full spectrum: %.1f ± %.1f nm, %zu alternatives\n", full.parameters[0].value,
                full.parameters[0].sigma, full.alternatives.size());
    EXPECT_LE(std::abs(full.parameters[0].value - 120.0), 3.0 * full.parameters[0].sigma);
    EXPECT_TRUE(full.alternatives.empty());
}

TEST(FitProgress, CancelThrowsAndReportsProgress) {
    const Recipe demo = test::demoRecipe("silver-metallic");
    fit::FitProblem p = test::syntheticProblem(demo, demo, {"layers[1].components[0].volume_fraction"},
                                               multiAngle(), Preset::Preview, 9);
    p.settings = quickSettings(3);
    const fit::FitProblem before = p;
    int calls = 0;
    EXPECT_THROW((void)fit::fitRecipe(p,
                                      [&](const fit::FitProgress& progress) {
                                          EXPECT_EQ(progress.stage, "search");
                                          return ++calls < 2;
                                      }),
                 fit::FitCancelled);
    EXPECT_EQ(calls, 2);
    EXPECT_EQ(p.recipe, before.recipe);  // nothing changed
}

}  // namespace
}  // namespace paintlab
