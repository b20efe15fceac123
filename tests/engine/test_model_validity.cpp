// The fast model's validity boundary (model_validity.h) against the
// measurements it was fitted to (docs/fast_vs_full.csv, the full model with
// explicit flakes against the fast model), its surface-depletion factor
// against direct quadrature, and what must hold whatever the fit: no flakes
// is exact, absorption darkens the full model only through tilted flakes.

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/model_validity.h"
#include "paintlab/engine/recipe_json.h"

#include "test_recipes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace paintlab {
namespace {

// docs/fast_vs_full.csv: 96 grid points, 6 small-flake, 18 absorbing-film.
constexpr std::size_t kReportRows = 120;
// The rule is 4-9 points low for metal flakes at 1 % by volume (0.7 flake
// layers): one of them (10 µm, spread 5°, +11.2 ± 0.4 %) is measured outside
// and called inside. No paint measured inside is called outside.
constexpr int kAllowedMisses = 1;
constexpr int kAllowedFalseAlarms = 0;

// The report's paint (tools/compare_report/compare_report.py): one 20 µm
// layer of index 1.5 over black, with one kind of flake.
MirrorFlake aluminium(double volume_fraction, double diameter_um, double spread_deg) {
    MirrorFlake f;
    f.name = "aluminium";
    f.volume_fraction = volume_fraction;
    f.diameter_um = diameter_um;
    f.thickness_um = 0.3;
    f.orientation_spread_deg = spread_deg;
    f.metal_n = Spectrum(1.015);
    f.metal_k = Spectrum(6.63);
    return f;
}

InterferenceFlake platelet(const std::string& type, double volume_fraction, double diameter_um,
                           double spread_deg) {
    InterferenceFlake f;
    f.name = type;
    f.volume_fraction = volume_fraction;
    f.diameter_um = diameter_um;
    f.orientation_spread_deg = spread_deg;
    if (type == "interference") {
        f.mica_thickness_nm = 350.0;
        f.mica_thickness_spread_nm = 40.0;
        f.tio2_thickness_nm = 120.0;
        f.tio2_thickness_spread_nm = 8.0;
        f.mica_refractive_index = Spectrum(1.58);
        f.tio2_refractive_index = Spectrum(2.65);
    } else {  // "dielectric": an uncoated platelet of index 2.0
        f.mica_thickness_nm = 250.0;
        f.mica_thickness_spread_nm = 40.0;
        f.tio2_thickness_nm = 0.0;
        f.mica_refractive_index = Spectrum(2.0);
    }
    return f;
}

// absorption_per_um: the report's grey absorber (compare_report.py, the
// absorbing-film series), 1 % by volume.
Recipe reportPaint(const std::string& type, double volume_fraction, double diameter_um, double spread_deg,
                   double absorption_per_um = 0.0) {
    Recipe r = test::oneLayerRecipe(1.5, 20.0, BlackSubstrate{});
    if (type == "mirror")
        r.layers[0].components.emplace_back(aluminium(volume_fraction, diameter_um, spread_deg));
    else
        r.layers[0].components.emplace_back(platelet(type, volume_fraction, diameter_um, spread_deg));
    if (absorption_per_um > 0.0)
        r.layers[0].components.emplace_back(test::pigment(0.01, absorption_per_um / 0.01, 0.0, 0.0));
    return r;
}

// The report's rows by column name, read by the one CSV reader (io/csv.h).
std::vector<std::map<std::string, std::string>> readCsv(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    const io::CsvTable table = io::CsvTable::parse(text.str(), path);
    std::vector<std::map<std::string, std::string>> rows;
    for (const io::CsvRecord& record : table.records()) {
        std::map<std::string, std::string> row;
        for (const std::string& column : table.header()) row[column] = table.field(record, column);
        rows.push_back(std::move(row));
    }
    return rows;
}

TEST(ModelValidity, NoFlakesIsExact) {
    // Pigments and raw media only: both models solve the same transfer
    // equation (docs/VALIDATION.md: pigment slabs agree within 3 std errors).
    Recipe r = test::oneLayerRecipe(1.5, 20.0, LambertianSubstrate{Spectrum(0.5)});
    r.layers[0].components.emplace_back(test::pigment(0.1, 0.5, 20.0, 0.3));
    const FastModelValidity v = fastModelValidity(r);
    EXPECT_EQ(v.expected_rel_difference, 0.0);
    EXPECT_TRUE(v.within);
    EXPECT_NE(v.reason.find("no flakes"), std::string::npos) << v.reason;

    Recipe raw = test::oneLayerRecipe(1.0, 1.0, BlackSubstrate{});
    raw.layers[0].components.emplace_back(test::rawMedium(0.9, 2.0, 0.5));
    EXPECT_EQ(fastModelValidity(raw).expected_rel_difference, 0.0);

    // A flake component with no flakes in it contributes nothing either, nor
    // does an uncoated platelet of the binder's index (it is not there optically).
    EXPECT_EQ(fastModelValidity(reportPaint("mirror", 0.0, 20.0, 10.0)).expected_rel_difference, 0.0);
    Recipe matched = reportPaint("dielectric", 0.3, 50.0, 10.0);
    std::get<InterferenceFlake>(matched.layers[0].components[0]).mica_refractive_index = Spectrum(1.5);
    EXPECT_NEAR(fastModelValidity(matched).expected_rel_difference, 0.0, 1e-9);
}

TEST(ModelValidity, ReproducesTheReport) {
    // Every point of the report (the grid, the small-flake series and the
    // absorbing-film series; the rule's four constants were fitted to their
    // geometries): the rule against the measured signal-weighted difference
    // of the full model from the fast one.
    const auto rows = readCsv(PAINTLAB_TEST_DATA_DIR "/../../docs/fast_vs_full.csv");
    ASSERT_EQ(rows.size(), kReportRows);
    int misses = 0;
    int false_alarms = 0;
    for (const auto& row : rows) {
        const std::string type = row.at("flake_type");
        const double d_um = std::stod(row.at("diameter_um"));
        const Recipe r = reportPaint(type, std::stod(row.at("volume_fraction")), d_um,
                                     std::stod(row.at("spread_deg")), std::stod(row.at("absorption_per_um")));
        const double measured = std::stod(row.at("weighted_rel"));
        const double se = std::stod(row.at("weighted_rel_se"));
        const FastModelValidity v = fastModelValidity(r);
        // A curve of four constants through paints from -40 % to +115 %:
        // good to 5 points plus 30 % of the difference (fit_boundary.py prints
        // the residuals: RMS 6.6 points over the 120 paints, largest 40 at +108 %), plus 3 times the
        // measurement's error: the paths' standard error and the flake tile's realisation, which the report
        // measured by changing the seed (spread ~2 points).
        constexpr double kTileError = 0.02;
        const double error = std::hypot(se, kTileError);
        EXPECT_NEAR(v.expected_rel_difference, measured, 0.05 + 0.3 * std::abs(measured) + 3.0 * error)
            << row.at("series") << " " << type << " d " << d_um << " c " << row.at("volume_fraction")
            << " spread " << row.at("spread_deg") << " absorption " << row.at("absorption_per_um");
        // The boundary: measured outside / inside by more than 2 standard errors.
        if (std::abs(measured) - 2.0 * se > kDefaultFastModelTolerance && v.within) {
            ++misses;
            EXPECT_EQ(type, "mirror");
            EXPECT_EQ(row.at("volume_fraction"), "0.01") << "d " << d_um;
            EXPECT_LT(measured, 2.0 * kDefaultFastModelTolerance) << "a miss by more than the tolerance";
        }
        if (std::abs(measured) + 2.0 * se < kDefaultFastModelTolerance && !v.within) ++false_alarms;
    }
    EXPECT_LE(misses, kAllowedMisses);
    EXPECT_LE(false_alarms, kAllowedFalseAlarms);
}

TEST(ModelValidity, SurfaceDepletionMatchesQuadrature) {
    // F = E[exp(-kappa z)] over the full model's reflecting depths (centre
    // uniform in [delta, H - delta] plus delta u, u by the semicircle law)
    // over the continuum's (z uniform in [0, H]), by a 2-D midpoint rule in
    // (centre, phi) with u = cos(phi), whose weight sqrt(1 - u^2) du =
    // sin^2(phi) dphi is smooth: 1000 x 1000 cells give ~1e-7 relative here,
    // so 1e-5 tests the closed form (and its Bessel identity), not the rule.
    const auto quadrature = [](double kappa, double H, double delta) {
        constexpr int kCells = 1000;
        double full = 0.0;
        double weight = 0.0;
        for (int i = 0; i < kCells; ++i) {
            const double centre = delta + (H - 2.0 * delta) * (i + 0.5) / kCells;
            for (int j = 0; j < kCells; ++j) {
                const double phi = std::numbers::pi * (j + 0.5) / kCells;
                const double w = std::sin(phi) * std::sin(phi);
                full += w * std::exp(-kappa * (centre + delta * std::cos(phi)));
                weight += w;
            }
        }
        full /= weight;
        double continuum = 0.0;
        for (int i = 0; i < kCells; ++i) continuum += std::exp(-kappa * H * (i + 0.5) / kCells);
        return full / (continuum / kCells);
    };
    for (const auto& [kappa, H, delta] : std::vector<std::array<double, 3>>{
             {0.39, 15.0, 1.56}, {0.05, 20.0, 4.0}, {2.0, 20.0, 0.6}, {1.0, 5.0, 2.4}, {0.01, 40.0, 10.0}}) {
        const double F = tiltedFlakeSurfaceDepletion(kappa, H, delta);
        EXPECT_NEAR(F, quadrature(kappa, H, delta), 1e-5 * F) << kappa << " " << H << " " << delta;
        EXPECT_GT(F, 0.0);
        EXPECT_LE(F, 1.0);
    }
    // Limits: horizontal flakes, a clear film, flakes that cannot fit.
    EXPECT_EQ(tiltedFlakeSurfaceDepletion(0.5, 15.0, 0.0), 1.0);
    EXPECT_EQ(tiltedFlakeSurfaceDepletion(0.0, 15.0, 2.0), 1.0);
    EXPECT_EQ(tiltedFlakeSurfaceDepletion(0.5, 3.0, 2.0), 1.0);
    // Finite where the Bessel function alone would overflow (kappa delta =
    // 2000), and the asymptote there: only the flakes' lowest rims reach the
    // top, so F falls as a power, e^(-t) 2 I1(t) / t ~ 2 / (t sqrt(2 pi t)),
    // times H / (H - 2 delta) from the narrower span of centres (1e-3: the
    // next term of the asymptotic series is 3 / (8 t) ~ 2e-4).
    const double t = 1000.0 * 2.0;
    const double dense = tiltedFlakeSurfaceDepletion(1000.0, 15.0, 2.0);
    EXPECT_TRUE(std::isfinite(dense));
    EXPECT_NEAR(dense, 2.0 / (t * std::sqrt(2.0 * std::numbers::pi * t)) * 15.0 / 11.0, 1e-3 * dense);
}

TEST(ModelValidity, InsideAndOutside) {
    // Small sparse flakes: the limit in which the full model converges to the
    // fast one (docs/VALIDATION.md: 0.5 µm flakes, |z| <= 1.75).
    const FastModelValidity small = fastModelValidity(reportPaint("mirror", 0.005, 0.5, 15.0));
    EXPECT_TRUE(small.within) << small.reason;
    EXPECT_LT(small.expected_rel_difference, 0.02);

    // The silver-metallic demo (18 µm aluminium, 4 % in 15 µm): the full
    // model measured +39 % to +53 % (docs/VALIDATION.md).
    const Recipe silver = loadRecipeFile(PAINTLAB_DEMO_DIR "/recipes/silver-metallic.json");
    const FastModelValidity v = fastModelValidity(silver);
    EXPECT_FALSE(v.within) << v.reason;
    EXPECT_GT(v.expected_rel_difference, 0.25);
    EXPECT_NE(v.reason.find("basecoat"), std::string::npos) << v.reason;
    EXPECT_NE(v.reason.find("aluminium"), std::string::npos) << v.reason;

    // The pearlescent demo (18 µm pearl, 6 % in a 15 µm basecoat with 1 %
    // carbon black): the full model is darker, by -16.7 % signal-weighted
    // and -11, -12, -21, -32, -35, -12 % at the six geometries (paintlab-cli
    // compare --explicit-flakes --seconds 20, standard errors 0.1-1 %;
    // docs/VALIDATION.md). Without the carbon black it is +3 to +4 %.
    const Recipe pearl = loadRecipeFile(PAINTLAB_DEMO_DIR "/recipes/pearlescent-two-layer.json");
    const FastModelValidity p = fastModelValidity(pearl);
    EXPECT_FALSE(p.within) << p.reason;
    EXPECT_NEAR(p.expected_rel_difference, -0.167, 0.05) << p.reason;
    EXPECT_LT(p.largest_rel_difference, -0.25) << p.reason;
    EXPECT_NE(p.reason.find("darker"), std::string::npos) << p.reason;
    Recipe clear_pearl = pearl;
    auto& base = clear_pearl.layers[1].components;
    base.erase(std::remove_if(base.begin(), base.end(),
                              [](const Component& c) { return std::holds_alternative<Pigment>(c); }),
               base.end());
    const FastModelValidity cp = fastModelValidity(clear_pearl);
    EXPECT_TRUE(cp.within) << cp.reason;
    EXPECT_NEAR(cp.expected_rel_difference, 0.035, 0.03) << cp.reason;  // measured +3 to +4 %

    // A looser tolerance moves the boundary, not the estimate.
    const FastModelValidity loose = fastModelValidity(silver, 1.0);
    EXPECT_TRUE(loose.within);
    EXPECT_EQ(loose.expected_rel_difference, v.expected_rel_difference);
}

TEST(ModelValidity, AbsorptionDarkensOnlyThroughTiltedFlakes) {
    for (const std::string type : {"mirror", "interference"}) {
        // More absorption weights the film's top more, where tilted flakes
        // cannot reach: the expected difference falls with it.
        double previous = fastModelValidity(reportPaint(type, 0.04, 20.0, 10.0)).expected_rel_difference;
        for (double a : {0.02, 0.05, 0.15, 0.5, 1.5}) {
            const double e =
                fastModelValidity(reportPaint(type, 0.04, 20.0, 10.0, a)).expected_rel_difference;
            EXPECT_LT(e, previous) << type << " absorption " << a;
            EXPECT_GT(e, -1.0) << type << " absorption " << a;
            previous = e;
        }
        // Larger flakes reach less far up: what absorption takes off the
        // full model's figure grows with the diameter (the hiding grows too,
        // so the figure itself need not fall).
        previous = 0.0;
        for (double d : {5.0, 10.0, 20.0, 50.0}) {
            const double clear = fastModelValidity(reportPaint(type, 0.04, d, 10.0)).expected_rel_difference;
            const double dark =
                fastModelValidity(reportPaint(type, 0.04, d, 10.0, 0.15)).expected_rel_difference;
            EXPECT_GT(clear - dark, previous) << type << " d " << d;
            previous = clear - dark;
        }
        // Horizontal flakes sit anywhere: absorption changes nothing, only
        // the hiding remains, bounded by its factor of two (model_validity.h).
        const double flat = fastModelValidity(reportPaint(type, 0.3, 50.0, 0.0)).expected_rel_difference;
        EXPECT_EQ(fastModelValidity(reportPaint(type, 0.3, 50.0, 0.0, 0.5)).expected_rel_difference, flat);
        EXPECT_GE(flat, 0.0);
        EXPECT_LE(flat, 1.0);
    }
}

TEST(ModelValidity, ClearFilmsGrowWithCoverage) {
    // Without absorption the hiding dominates: more flakes, more difference.
    for (const std::string type : {"mirror", "interference", "dielectric"}) {
        double previous = 0.0;
        for (double c : {0.001, 0.01, 0.04, 0.12, 0.3}) {
            const double e = fastModelValidity(reportPaint(type, c, 20.0, 10.0)).expected_rel_difference;
            EXPECT_GE(e, previous) << type << " c " << c;
            previous = e;
        }
        EXPECT_LE(previous, 1.0);
    }
}

TEST(ModelValidity, BadInput) {
    const Recipe ok = reportPaint("mirror", 0.04, 20.0, 10.0);
    for (double tol : {0.0, -0.1, 1.5, std::numeric_limits<double>::quiet_NaN()})
        EXPECT_THROW(fastModelValidity(ok, tol), InputError) << tol;
    Recipe bad = ok;
    std::get<MirrorFlake>(bad.layers[0].components[0]).volume_fraction = -0.1;
    EXPECT_THROW(fastModelValidity(bad), InputError);
    Recipe empty;
    EXPECT_THROW(fastModelValidity(empty), InputError);
}

}  // namespace
}  // namespace paintlab
