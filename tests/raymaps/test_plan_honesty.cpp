// The effect planner's honesty on ray-map images (issue 7; engine/plan.h):
// for every effect the plan skips or reduces on small ray maps of the demo
// scene (procedural car under the built-in sky and a sun, and the same
// without the sun; 48 x 32 pixels),
// the relight computed anyway (the preset's setting, or the effect on)
// differs from the relight the plan runs by less than the plan claims, as
// CIEDE2000 per paint pixel, 99th percentile. White: the brightest paint
// pixel of the preset's image (the planner's bound holds for pixels no
// brighter than white). The numbers are printed for docs/VALIDATION.md's
// honesty table.

#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/colour/colour.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/model_validity.h"
#include "paintlab/engine/montecarlo/mc_table.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"
#include "paintlab/raymaps/scene.h"
#include "paintlab/raymaps/sparkle_pass.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace paintlab::raymaps {
namespace {

const std::filesystem::path kDemo(PAINTLAB_DEMO_DIR);

const PlanDecision& decision(const EffectPlan& p, const std::string& effect) {
    for (const auto& d : p.decisions)
        if (d.effect == effect) return d;
    throw std::runtime_error("no decision " + effect);
}

struct Relit {
    RgbImage image;
    double model_seconds = 0.0;  // fast model + relight tables (what a recipe change costs)
};

// The maps: 0 the demo scene (sun and sky), 1 the same under the sky alone.
constexpr int kMaps = 2;
const char* const kMapNames[kMaps] = {"demo car, sun + sky", "demo car, sky only"};

// The full model, "computed anyway": the Monte Carlo model with explicit
// flakes tabulated on the fast model's preview grid (mc_table.h), relit on
// the demo map (fullModelAgainstFast below). Budgets are path counts per
// (band, node and incidence), not seconds: with fixed paths and seeds the tables are the
// same on any machine at any load (determinism is tested in
// tests/engine/montecarlo), so the check cannot flip with CI's load; a time
// budget gave half the paths, and a noise above the claim, under ctest -j2.
// The noise falls as 1 / sqrt(paths): for the clear pearl dE00 0.91 with
// ~8 k explicit paths per (band, node and incidence), 0.42 with 80 k. The
// report build of this file (report_raymaps_plan, label `report`, configured
// with -DPAINTLAB_REPORT_TESTS=ON) takes 10x the paths.
#ifdef PAINTLAB_PLAN_HONESTY_REPORT
constexpr double kPathsScale = 10.0;
#else
constexpr double kPathsScale = 1.0;
#endif

struct FullModelImages {
    double measured_de = 0.0;              // 99th percentile dE00, explicit flakes against the continuum
    double noise_de = 0.0;                 // of that difference, from the seeds
    double tabulation_de = 0.0;            // the continuum Monte Carlo's table against the fast model
    double median_luminance_change = 0.0;  // Y explicit / continuum - 1 over the paint pixels
};

class PlanHonesty : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_dir = new test::TempDir();
        for (int m = 0; m < kMaps; ++m) {
            Scene scene = loadSceneFile(kDemo / "scenes" / "car_body_sky.json");
            scene.camera.width = 48;
            scene.camera.height = 32;
            if (m == 1) scene.lights.clear();
            RayMapSettings s;
            s.aa_samples = 1;
            s.light_rays = 16;
            s.bake_paths = 1;
            s.sun_shadow_rays = 2;
            const auto path = s_dir->path() / ("demo" + std::to_string(m) + ".prm");
            buildRayMap(scene, s, path);
            s_maps[m] = RayMap::open(path).release();
            s_inputs[m] = new RelightInput(*s_maps[m]);
        }
        use(0);
    }
    static void TearDownTestSuite() {
        for (int m = 0; m < kMaps; ++m) {
            delete s_inputs[m];
            delete s_maps[m];
        }
        delete s_dir;
    }
    // The map the helpers below work on.
    static void use(int m) {
        s_map = s_maps[m];
        s_input = s_inputs[m];
    }

    static Relit relit(const Recipe& r, const FastModelSettings& settings) {
        const auto start = std::chrono::steady_clock::now();
        const LayeredBrdf brdf = computeLayeredBrdf(r, settings);
        const RelightTables tables(brdf, s_map->header().cells, s_map->header().orders);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return {relight(*s_input, tables), seconds};
    }

    static double luminanceOf(const RgbImage& image, std::uint32_t pixel) {
        const float* p = image.rgb.data() + 3 * static_cast<std::size_t>(pixel);
        return linearSrgbToXyz(
                   {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])})
            .Y;
    }

    // The brightest paint pixel of `image` (the white of the comparison).
    static double whiteOf(const RgbImage& image) {
        double y = 0.0;
        for (std::size_t i = 0; i < s_input->paintPixels(); ++i)
            y = std::max(y, luminanceOf(image, s_input->pixel(i)));
        return y;
    }

    // 99th percentile over the paint pixels of Delta E_00 between two images,
    // XYZ relative to y_white (D65 white).
    static double percentile99DeltaE(const RgbImage& a, const RgbImage& b, double y_white) {
        const Xyz white = linearSrgbToXyz({1.0, 1.0, 1.0});
        const auto lab = [&](const RgbImage& image, std::uint32_t pixel) {
            const float* p = image.rgb.data() + 3 * static_cast<std::size_t>(pixel);
            const Xyz x =
                linearSrgbToXyz({static_cast<double>(p[0]) / y_white, static_cast<double>(p[1]) / y_white,
                                 static_cast<double>(p[2]) / y_white});
            return xyzToLab(x, white);
        };
        std::vector<double> de;
        for (std::size_t i = 0; i < s_input->paintPixels(); ++i) {
            const std::uint32_t pixel = s_input->pixel(i);
            de.push_back(ciede2000(lab(a, pixel), lab(b, pixel)));
        }
        if (de.empty() || !(y_white > 0.0)) {
            ADD_FAILURE() << "no paint pixels, or a black white point";
            return std::numeric_limits<double>::infinity();
        }
        std::sort(de.begin(), de.end());
        return de[static_cast<std::size_t>(0.99 * static_cast<double>(de.size() - 1))];
    }

    static Recipe demoRecipe(const char* name) { return loadRecipeFile(kDemo / "recipes" / name); }

    // The full model's relit image (the Monte Carlo with explicit flakes,
    // tabulated on the preview grid, mean of two seeds) against the same
    // Monte Carlo with the flakes as a continuum (the control: what the fast
    // model solves, through the same tabulation, so the table's cell
    // averages and the grid's interpolation cancel), and the control against
    // the fast model (that tabulation bias, for the record).
    static FullModelImages fullModelAgainstFast(const Recipe& r, const char* what,
                                                std::int64_t explicit_paths, std::int64_t continuum_paths) {
        const RelightInput& input = *s_input;
        const RayMap& map = *s_map;
        const FastModelSettings grid = presetSettings(Preset::Preview);
        mc::McSettings s;
        s.histogram_cone_deg = 5.0;
        struct MeanImage {
            RgbImage image;   // of two independent tables
            double noise_de;  // of that mean: half the two tables' difference (each has half its variance)
        };
        const RgbImage fast = relit(r, grid).image;
        const double white = whiteOf(fast);
        const auto relitMean = [&](bool explicit_flakes, const char* model) {
            s.explicit_flakes = explicit_flakes;
            s.max_paths = static_cast<std::int64_t>(
                kPathsScale * static_cast<double>(explicit_flakes ? explicit_paths : continuum_paths));
            RgbImage one[2];
            for (int k = 0; k < 2; ++k) {
                s.seed = static_cast<std::uint64_t>(k + 1);
                const mc::McTable t = mc::tabulateMonteCarlo(r, grid, s);
                std::printf("  %s: %s table, seed %d: %lld paths in %.1f s\n", what, model, k + 1,
                            static_cast<long long>(t.total_paths), t.seconds);
                one[k] = relight(input, RelightTables(t.brdf, map.header().cells, map.header().orders));
            }
            MeanImage m{one[0], 0.5 * percentile99DeltaE(one[0], one[1], white)};
            for (std::size_t i = 0; i < m.image.rgb.size(); ++i)
                m.image.rgb[i] = 0.5F * (one[0].rgb[i] + one[1].rgb[i]);
            return m;
        };
        const MeanImage full = relitMean(true, "explicit flakes");
        const MeanImage control = relitMean(false, "continuum");
        FullModelImages out;
        out.measured_de = percentile99DeltaE(control.image, full.image, white);
        out.noise_de = std::hypot(full.noise_de, control.noise_de);
        out.tabulation_de = percentile99DeltaE(fast, control.image, white);
        std::vector<double> ratio;
        for (std::size_t i = 0; i < input.paintPixels(); ++i) {
            const double y_control = luminanceOf(control.image, input.pixel(i));
            if (y_control > 0.0) ratio.push_back(luminanceOf(full.image, input.pixel(i)) / y_control - 1.0);
        }
        if (ratio.empty()) {
            ADD_FAILURE() << what << ": no lit paint pixels";
            return out;
        }
        std::sort(ratio.begin(), ratio.end());
        out.median_luminance_change = ratio[ratio.size() / 2];
        std::printf(
            "  %s: explicit flakes against the continuum, dE00 %.3g (99th percentile), Monte Carlo noise "
            "%.3g; the continuum against the fast model %.3g; Y explicit / continuum - 1 per pixel: 10th "
            "percentile %+.3f, median %+.3f, 90th %+.3f\n",
            what, out.measured_de, out.noise_de, out.tabulation_de, ratio[ratio.size() / 10],
            out.median_luminance_change, ratio[ratio.size() * 9 / 10]);
        return out;
    }

    static test::TempDir* s_dir;
    static RayMap* s_maps[kMaps];
    static RelightInput* s_inputs[kMaps];
    static RayMap* s_map;
    static RelightInput* s_input;
};

test::TempDir* PlanHonesty::s_dir = nullptr;
RayMap* PlanHonesty::s_maps[kMaps] = {};
RelightInput* PlanHonesty::s_inputs[kMaps] = {};
RayMap* PlanHonesty::s_map = nullptr;
RelightInput* PlanHonesty::s_input = nullptr;

// Fewer Fourier orders and fewer bands, one at a time and together: the
// relight at the preset's settings against the plan's.
TEST_F(PlanHonesty, ReducedOrdersAndBandsChangeTheRelitImageLessThanClaimed) {
    int reductions = 0;
    for (int m = 0; m < kMaps; ++m) {
        use(m);
        const PlanScene summary = summariseRayMap(*s_map);
        for (const char* name : {"silver-metallic.json", "solid-red.json", "pearlescent-two-layer.json"}) {
            const Recipe r = demoRecipe(name);
            const EffectPlan p = plan(r, summary, Preset::Standard);
            const FastModelSettings preset = presetSettings(Preset::Standard);
            FastModelSettings orders_only = preset;
            orders_only.orders = p.fast.orders;
            const FastModelSettings planned = applyPlan(p, preset);
            EXPECT_EQ(planned.orders, p.fast.orders);
            EXPECT_EQ(planned.bands, p.fast.bands);
            const Relit full = relit(r, preset);
            const Relit fewer_orders = relit(r, orders_only);
            const Relit as_planned = relit(r, planned);
            const double white = whiteOf(full.image);
            ASSERT_GT(white, 0.0) << name;
            const double claimed_orders = decision(p, "angular").accepted_error_de;
            const double claimed_bands = decision(p, "bands").accepted_error_de;
            const double measured_orders = percentile99DeltaE(full.image, fewer_orders.image, white);
            const double measured_bands = percentile99DeltaE(fewer_orders.image, as_planned.image, white);
            const double measured_both = percentile99DeltaE(full.image, as_planned.image, white);
            std::printf(
                "honesty %s, %s: orders %d -> %d claimed dE %.3g measured %.3g; bands %d -> %d "
                "claimed %.3g measured %.3g; both measured %.3g; fast model + tables %.0f -> %.0f ms\n",
                name, kMapNames[m], preset.orders, planned.orders, claimed_orders, measured_orders,
                preset.bands, planned.bands, claimed_bands, measured_bands, measured_both,
                1e3 * full.model_seconds, 1e3 * as_planned.model_seconds);
            if (planned.orders < preset.orders) {
                ++reductions;
                EXPECT_LE(measured_orders, std::max(claimed_orders, 1e-3)) << name;
            } else {
                EXPECT_EQ(measured_orders, 0.0) << name;
            }
            if (planned.bands < preset.bands) {
                ++reductions;
                EXPECT_LE(measured_bands, std::max(claimed_bands, 1e-3)) << name;
            }
            // Two accepted errors together stay within the sum of the claims (and the tolerance).
            EXPECT_LE(measured_both, std::max(claimed_orders + claimed_bands, 1e-3)) << name;
            EXPECT_LE(measured_both, p.tolerance_de) << name;
        }
    }
    EXPECT_GT(reductions, 0);  // the map's sun and smooth spectra let the plan reduce something
}

// Sparkle skipped where the plan finds the glints averaged out (the demo
// map's ~10 cm pixels): the sparkle pass run anyway changes the relit image
// by less than claimed.
TEST_F(PlanHonesty, SkippedSparkleChangesTheRelitImageLessThanClaimed) {
    int skipped = 0;
    for (int m = 0; m < kMaps; ++m) {
        use(m);
        const PlanScene summary = summariseRayMap(*s_map);
        for (const char* name : {"silver-metallic.json", "pearlescent-two-layer.json"}) {
            const Recipe r = demoRecipe(name);
            const EffectPlan p = plan(r, summary, Preset::Standard);
            const PlanDecision& d = decision(p, "sparkle");
            const Relit base = relit(r, applyPlan(p, presetSettings(Preset::Standard)));
            RgbImage with = base.image;
            const SparkleModel model(r);
            const SparklePassStats stats = addSparkle(*s_map, model, with);
            const double measured = percentile99DeltaE(base.image, with, whiteOf(base.image));
            std::printf("honesty sparkle %s, %s (footprints %.3g-%.3g um): plan %s, claimed dE %.3g, "
                        "measured %.3g, sparkle pass %.1f ms for %llu paint pixels\n",
                        name, kMapNames[m], summary.footprint_min_um, summary.footprint_max_um,
                        p.sparkle ? "on" : "skipped", d.accepted_error_de, measured, 1e3 * stats.seconds,
                        static_cast<unsigned long long>(stats.pixels));
            if (p.sparkle) continue;
            ++skipped;
            EXPECT_LE(measured, std::max(d.accepted_error_de, 1e-3)) << name;
        }
    }
    EXPECT_GT(skipped, 0);
}

// Depth slices: a profiled flake layer at the preset's slices and at 16
// (near the exact profile) against the plan's count. The claim is the
// relative concentration error of the slice means, which bounds the change
// of the light the layer scatters. The silver demo's basecoat is clear
// binder: there, where the flakes sit in depth does not change the light at
// all (radiative transfer in a non-absorbing binder depends on the flakes'
// optical depth only; the multi-angle colour of the silver with its flakes
// at the top, at the bottom or uniform is the same to 0.01), so the
// basecoat here also holds 1 % of the red demo's hematite, uniformly: a
// red metallic, whose colour depends on how deep the flakes lie.
TEST_F(PlanHonesty, FewerDepthSlicesChangeTheRelitImageLessThanClaimed) {
    use(0);
    const PlanScene summary = summariseRayMap(*s_map);
    Pigment hematite = std::get<Pigment>(demoRecipe("solid-red.json").layers[1].components[0]);
    hematite.volume_fraction = 0.01;
    struct Case {
        const char* what;
        std::vector<double> weight;  // top to bottom
    };
    for (const Case& c : {Case{"gentle gradient 1.05 -> 0.95", {1.05, 0.95}},
                          Case{"flakes settled to the top 1 -> 0", {1.0, 0.0}}}) {
        Recipe r = demoRecipe("silver-metallic.json");
        std::get<MirrorFlake>(r.layers[1].components[0]).depth_profile = DepthProfile{{0.0, 1.0}, c.weight};
        r.layers[1].components.emplace_back(hematite);
        const EffectPlan p = plan(r, summary, Preset::Standard);
        const PlanDecision& d = decision(p, "slices");
        ASSERT_TRUE(d.simulate) << c.what;
        const FastModelSettings planned = applyPlan(p, presetSettings(Preset::Standard));
        FastModelSettings preset = planned;
        preset.slices = presetSettings(Preset::Standard).slices;
        FastModelSettings fine = planned;
        fine.slices = 16;
        const Relit at_plan = relit(r, planned);
        const Relit at_preset = relit(r, preset);
        const Relit at_fine = relit(r, fine);
        const double white = whiteOf(at_fine.image);
        const double against_preset = percentile99DeltaE(at_preset.image, at_plan.image, white);
        const double against_fine = percentile99DeltaE(at_fine.image, at_plan.image, white);
        std::printf(
            "honesty slices red metallic, %s: slices %d (preset %d), claimed dE %.3g, measured %.3g against "
            "the preset's, %.3g against 16 slices; fast model + tables %.0f (preset) -> %.0f ms\n",
            c.what, planned.slices, preset.slices, d.accepted_error_de, against_preset, against_fine,
            1e3 * at_preset.model_seconds, 1e3 * at_plan.model_seconds);
        EXPECT_LE(against_fine, d.accepted_error_de) << c.what;
        if (planned.slices < preset.slices) {
            EXPECT_LE(against_preset, d.accepted_error_de) << c.what;
        }
    }
}

// Skipped: the demo pearl without its carbon black (clear basecoat), where
// the flakes' hiding is the only difference (fastModelValidity: a few %).
// The claim is checked only where the noise is below it, and the model's
// difference may exceed the claim by at most that noise. 25 k explicit
// paths per (band, node and incidence), 6.15 M per table, and 80 k for the
// continuum give noise 0.52 against the claim 0.89 (measured 1.22); twice
// the paths gave 0.37 and 1.08 at twice the CPU (the tables are the same
// on any machine: fixed paths and seeds). ~90 s on two idle cores.
TEST_F(PlanHonesty, SkippedFullModelChangesTheRelitImageLessThanClaimed) {
    use(0);
    Recipe r = demoRecipe("pearlescent-two-layer.json");
    auto& base = r.layers[1].components;
    base.erase(std::remove_if(base.begin(), base.end(),
                              [](const Component& c) { return std::holds_alternative<Pigment>(c); }),
               base.end());
    const EffectPlan p = plan(r, summariseRayMap(*s_map), Preset::Standard);
    const PlanDecision& d = decision(p, "full_model");
    ASSERT_FALSE(d.simulate) << d.reason;
    const FullModelImages m = fullModelAgainstFast(r, "clear pearl (skipped)", 25000, 80000);
    std::printf("full model skipped, clear pearl, demo car (sun + sky): claimed dE00 %.3g, measured %.3g, "
                "noise %.3g\n",
                d.accepted_error_de, m.measured_de, m.noise_de);
    ASSERT_LT(m.noise_de, d.accepted_error_de) << "the full model's tables are too noisy to check the claim";
    EXPECT_LE(m.measured_de, d.accepted_error_de + m.noise_de);
}

// Advised: the pearlescent demo itself (1 % carbon black in the basecoat),
// which the plan sends to the full model because its tilted flakes cannot
// reach the absorbing film's top (the full model darker by ~15 %,
// fastModelValidity). Computing it must matter at the plan's own tolerance,
// and the darkening must be the one predicted: the median paint pixel's
// luminance change within 6 points of the expected signal-weighted
// difference (the rule's residual on the report's absorbing-film series is
// up to ~5 points, plus the image's mix of geometries).
TEST_F(PlanHonesty, AdvisedFullModelChangesTheRelitImageAsPredicted) {
    use(0);
    const Recipe r = demoRecipe("pearlescent-two-layer.json");
    const EffectPlan p = plan(r, summariseRayMap(*s_map), Preset::Standard);
    const PlanDecision& d = decision(p, "full_model");
    ASSERT_TRUE(d.simulate) << d.reason;
    const FastModelValidity v = fastModelValidity(r);
    const FullModelImages m = fullModelAgainstFast(r, "pearlescent (advised)", 30000, 30000);
    std::printf(
        "full model advised, pearlescent, demo car (sun + sky): expected %+.1f %% (largest %+.1f %% at "
        "45as%.0f), measured median luminance change %+.1f %%, dE00 %.3g, noise %.3g, plan tolerance "
        "dE00 %.3g\n",
        100.0 * v.expected_rel_difference, 100.0 * v.largest_rel_difference, v.largest_at_aspecular_deg,
        100.0 * m.median_luminance_change, m.measured_de, m.noise_de, p.tolerance_de);
    EXPECT_GT(m.measured_de - m.noise_de, p.tolerance_de) << "the advice was not needed";
    EXPECT_NEAR(m.median_luminance_change, v.expected_rel_difference, 0.06);
}
}  // namespace
}  // namespace paintlab::raymaps
