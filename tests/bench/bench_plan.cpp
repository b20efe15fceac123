// The effect planner's time saving (issue 7): the fast model at the preset's
// settings against the plan's, for the demo recipes in a sunny and an
// overcast scene summary; the plan's own cost; the sparkle statistics per
// pixel (what the sparkle pass pays per paint pixel and light).
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/engine/sparkle/sparkle_texture.h"

#include <benchmark/benchmark.h>

#include <array>
#include <filesystem>
#include <string>

namespace {

using namespace paintlab;

const std::filesystem::path kDemo = std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes";
const std::array<const char*, 3> kRecipes{"silver-metallic.json", "solid-red.json",
                                          "pearlescent-two-layer.json"};

// 0: the demo car scene's sun and sky (1 cm pixels); 1: an overcast sky (no
// compact light, features 90 deg wide).
PlanScene scene(int which) {
    PlanScene s;
    s.source = which == 0 ? "sunny" : "overcast";
    if (which == 0) s.lights.push_back({"sun", 2.9, 6.8e-5});
    s.environment_radiance = which == 0 ? 0.6 : 1.0;
    s.environment_sharpness_deg = which == 0 ? 40.0 : 90.0;
    s.footprint_min_um = 9500.0;
    s.footprint_max_um = 20000.0;
    s.viewing_distance_m = 5.0;
    return s;
}

// Args: recipe, scene, 0 = the preset's settings / 1 = the plan's.
void BM_FastModelPresetVsPlan(benchmark::State& state) {
    const Recipe r = loadRecipeFile(kDemo / kRecipes[static_cast<std::size_t>(state.range(0))]);
    const EffectPlan p = plan(r, scene(static_cast<int>(state.range(1))), Preset::Standard);
    const FastModelSettings s = state.range(2) == 0 ? presetSettings(Preset::Standard) : p.fast;
    for (auto _ : state) benchmark::DoNotOptimize(computeLayeredBrdf(r, s));
    state.SetLabel(std::string(kRecipes[static_cast<std::size_t>(state.range(0))]) + " " +
                   scene(static_cast<int>(state.range(1))).source +
                   (state.range(2) == 0 ? " preset" : " plan") + " orders " + std::to_string(s.orders) +
                   " bands " + std::to_string(s.bands));
}
BENCHMARK(BM_FastModelPresetVsPlan)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_Plan(benchmark::State& state) {
    const Recipe r = loadRecipeFile(kDemo / kRecipes[static_cast<std::size_t>(state.range(0))]);
    for (auto _ : state) benchmark::DoNotOptimize(plan(r, scene(0), Preset::Standard));
}
BENCHMARK(BM_Plan)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// The sparkle model of a recipe (per recipe change, before the sparkle pass):
// per band the paint stack and the exit chains on the polar grid.
void BM_SparkleModel(benchmark::State& state) {
    const Recipe r = loadRecipeFile(kDemo / kRecipes[static_cast<std::size_t>(state.range(0))]);
    for (auto _ : state) benchmark::DoNotOptimize(SparkleModel(r));
}
BENCHMARK(BM_SparkleModel)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

// One paint pixel and light: statistics and draw (16 bands).
void BM_SparklePixel(benchmark::State& state) {
    const SparkleModel model(loadRecipeFile(kDemo / kRecipes[static_cast<std::size_t>(state.range(0))]));
    SparkleGeometry g;
    g.wi = directionFromAnglesDeg(45.0, 0.0);
    g.wo = directionFromAnglesDeg(30.0, 170.0);
    g.element_area_um2 = 1e8;
    g.light_solid_angle_sr = 6.8e-5;
    g.view_solid_angle_sr = viewApertureSr(5.0);
    std::uint64_t key = 1;
    for (auto _ : state) {
        const SparkleStats s = model.evaluate(g);
        benchmark::DoNotOptimize(sparkleBrdfModulation(s, ++key));
    }
}
BENCHMARK(BM_SparklePixel)->Arg(0)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
