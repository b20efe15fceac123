// The sparkle pass on a ray map (raymaps/sparkle_pass.h): a sun-lit flake
// panel seen from 10 cm at ~50 µm per pixel. Energy (the pass adds zero
// mean over the paint pixels: z-test), determinism, stability under recipe
// changes, and bad input.

#include "temp_dir.h"
#include "test_recipes.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/scene.h"
#include "paintlab/raymaps/sparkle_pass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace paintlab::raymaps {
namespace {

Recipe flakePaint(double volume_fraction) {
    Recipe r = test::oneLayerRecipe(1.5, 20.0, LambertianSubstrate{Spectrum(0.3)});
    r.layers[0].components.push_back(test::mirrorFlake(volume_fraction, 15.0, 0.6));
    return r;
}

// Camera 0.1 m from a panel; pixel angle 2 tan(0.46 deg) / 32 = 5.0e-4 rad:
// 50 µm per pixel; the sun 6 deg off the mirror direction of the view.
class SparklePass : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string text = R"({"schema_version": 1,
          "camera": {"position": [0, 0.06, 0.08], "look_at": [0, 0, 0], "vertical_fov_deg": 0.917, "width": 32, "height": 32},
          "environment": {"intensity": 0.2},
          "lights": [{"type": "sun", "direction": [0.1, 0.6, -0.8], "irradiance": [3, 3, 3]}],
          "materials": [{"name": "paint", "kind": "paint"}],
          "objects": [{"name": "panel", "plane": {"size": 1}, "material": "paint"}]})";
        m_scene = parseSceneJson(text, "panel.json");
        RayMapSettings s;
        s.aa_samples = 1;
        s.light_rays = 16;
        s.bake_paths = 1;
        s.sun_shadow_rays = 2;
        m_path = m_dir.path() / "panel.prm";
        buildRayMap(m_scene, s, m_path);
        m_map = RayMap::open(m_path);
        m_settings.pixel_angle_rad = 2.0 * std::tan(0.5 * 0.917 * 3.14159265358979 / 180.0) / 32.0;
    }

    RgbImage relit(const Recipe& r) const {
        const LayeredBrdf brdf = computeLayeredBrdf(r, presetSettings(Preset::Preview));
        return relight(*m_map, RelightTables(brdf, m_map->header().cells, m_map->header().orders));
    }

    test::TempDir m_dir;
    Scene m_scene;
    std::filesystem::path m_path;
    std::unique_ptr<RayMap> m_map;
    SparklePassSettings m_settings;
};

TEST_F(SparklePass, AddsZeroMeanGlintsDeterministically) {
    const Recipe r = flakePaint(0.01);
    const RgbImage base = relit(r);
    RgbImage a = base;
    RgbImage b = base;
    const SparkleModel model(r, {.bands = 4});
    const SparklePassStats stats = addSparkle(*m_map, model, a, m_settings);
    addSparkle(*m_map, model, b, m_settings);
    EXPECT_EQ(a.rgb, b.rgb);  // deterministic (and thread-count independent: keys, not threads)
    EXPECT_EQ(stats.pixels, m_map->header().paint_pixels);
    EXPECT_GT(stats.glint_pixels, 0U);
    EXPECT_LT(stats.glint_pixels, stats.pixels);  // ~50 µm footprints resolve the 15 µm flakes
    // Energy: the mean added radiance over the paint pixels is 0 (z-test,
    // |z| < 3: two-sided 0.27 %), while single pixels change a lot.
    double sum = 0.0;
    double sum_sq = 0.0;
    double base_sum = 0.0;
    const std::size_t pixels = base.rgb.size() / 3;
    const auto n = static_cast<double>(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        const double d = static_cast<double>(a.rgb[3 * i + 1]) - static_cast<double>(base.rgb[3 * i + 1]);
        sum += d;
        sum_sq += d * d;
        base_sum += static_cast<double>(base.rgb[3 * i + 1]);
    }
    const double mean = sum / n;
    const double se = std::sqrt((sum_sq / n - mean * mean) / n);
    ASSERT_GT(se, 0.0);
    EXPECT_LT(std::abs(mean) / se, 3.0);
    EXPECT_GT(std::sqrt(sum_sq / n), 0.05 * base_sum / n);
}

// A denser paint keeps the keys: a pixel that glints at c glints at 2c
// (Poisson inversion is monotone in the mean for the same random number).
// Glints are rare here (Lambda << 1 per pixel), so a glint makes X >> 1 at
// both concentrations: the bright pixels (added radiance > 0) of the thin
// paint are bright in the thick one, all but those whose draw changed with
// the extinction (which is 2 x larger): at least 80 %.
TEST_F(SparklePass, DenserPaintKeepsTheGlints) {
    const Recipe thin = flakePaint(0.005);
    const Recipe thick = flakePaint(0.01);
    RgbImage zero_thin{32, 32, std::vector<float>(32 * 32 * 3, 0.0F)};
    RgbImage zero_thick = zero_thin;
    addSparkle(*m_map, SparkleModel(thin, {.bands = 1}), zero_thin, m_settings);
    addSparkle(*m_map, SparkleModel(thick, {.bands = 1}), zero_thick, m_settings);
    int glints = 0;
    int kept = 0;
    for (std::size_t i = 0; i < zero_thin.rgb.size(); i += 3) {
        if (zero_thin.rgb[i] > 0.0F) {
            ++glints;
            if (zero_thick.rgb[i] > 0.0F) ++kept;
        }
    }
    EXPECT_GT(glints, 0);
    EXPECT_GE(kept, 0.8 * glints);
}

TEST_F(SparklePass, BadInputIsRefused) {
    const SparkleModel model(flakePaint(0.01), {.bands = 1});
    RgbImage wrong{8, 8, std::vector<float>(8 * 8 * 3, 0.0F)};
    EXPECT_THROW(addSparkle(*m_map, model, wrong, m_settings), InputError);
    RgbImage image{32, 32, std::vector<float>(32 * 32 * 3, 0.0F)};
    SparklePassSettings bad = m_settings;
    bad.scene_unit_m = 0.0;
    EXPECT_THROW(addSparkle(*m_map, model, image, bad), InputError);
}

// The planner's view of this scene: one sun, 50 µm footprints: sparkle on.
TEST_F(SparklePass, PlannerSeesTheSceneAndTurnsSparkleOn) {
    const PlanScene s = summariseScene(m_scene);
    ASSERT_EQ(s.lights.size(), 1U);
    EXPECT_NEAR(s.lights[0].irradiance_w_m2, 3.0, 1e-9);
    EXPECT_NEAR(s.footprint_min_um, 50.0, 5.0);
    const PlanScene from_map = summariseRayMap(*m_map);
    EXPECT_NEAR(from_map.footprint_min_um, 50.0, 5.0);
    EXPECT_TRUE(plan(flakePaint(0.01), m_scene, Preset::Standard).sparkle);
}

}  // namespace
}  // namespace paintlab::raymaps
