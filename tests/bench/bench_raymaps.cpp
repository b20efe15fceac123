// Ray maps (issue 6, "Speed"): the relight kernel at three resolutions of
// the demo scene, the relight tables per recipe change, slider-to-image
// latency (preview fast model + tables + kernel), and the kernel's
// independence of the geometry (a sphere of 16x more triangles, same image).
// Issue 7: the effect plan's saving per recipe change in the relight path,
// and the sparkle pass.
// Figures for docs/PERFORMANCE.md come from running bench_raymaps directly;
// the smoke test runs the smallest size only.
//
// The maps are built once per process with the cheapest precompute settings:
// the kernel's work depends on the number of paint pixels, J, M_L and K, not
// on how many rays estimated the stored values.
#include "temp_dir.h"
#include "test_scenes.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/plan/plan.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/raymaps/plan_scene.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"
#include "paintlab/raymaps/scene.h"
#include "paintlab/raymaps/sparkle_pass.h"

#include <benchmark/benchmark.h>

#include <array>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace {

using namespace paintlab;
using namespace paintlab::raymaps;

const std::filesystem::path kDemo = std::filesystem::path(PAINTLAB_DEMO_DIR);

Recipe pearlescent() { return loadRecipeFile(kDemo / "recipes" / "pearlescent-two-layer.json"); }

// Maps (loaded) and their decoded input by key, built on first use and kept for the process.
struct CachedMap {
    std::unique_ptr<RayMap> map;
    std::unique_ptr<RelightInput> input;
};

const CachedMap& cachedMap(const std::string& key, const Scene& scene) {
    static const paintlab::test::TempDir dir;
    static std::map<std::string, CachedMap> maps;
    auto& slot = maps[key];
    if (!slot.map) {
        const auto path = dir / (key + ".prm");
        buildRayMap(scene, paintlab::test::cheapRayMapSettings(), path);
        slot.map = RayMap::open(path);
        slot.map->loadAll();
        slot.input = std::make_unique<RelightInput>(*slot.map);
    }
    return slot;
}

const RelightInput& cachedInput(const std::string& key, const Scene& scene) {
    return *cachedMap(key, scene).input;
}

const CachedMap& demoMap(int width) {
    Scene scene = loadSceneFile(kDemo / "scenes" / "car_body_sky.json");
    scene.camera.width = width;
    scene.camera.height = width * 9 / 16;
    return cachedMap("demo" + std::to_string(width), scene);
}

const RelightInput& demoInput(int width) { return *demoMap(width).input; }

// Process CPU time (all threads) per iteration, next to the wall time: on a
// shared machine CPU time / cores is what idle cores would take.
class CpuClock {
public:
    CpuClock() : m_start(std::clock()) {}
    double msPerIteration(benchmark::IterationCount n) const {
        return 1e3 * static_cast<double>(std::clock() - m_start) / CLOCKS_PER_SEC / static_cast<double>(n);
    }

private:
    std::clock_t m_start;
};

// Argument: image width (16:9).
void BM_RelightKernel(benchmark::State& state) {
    const RelightInput& input = demoInput(static_cast<int>(state.range(0)));
    const LayeredBrdf brdf = computeLayeredBrdf(pearlescent(), presetSettings(Preset::Preview));
    const RelightTables tables(brdf, input.cells(), input.orders());
    const CpuClock cpu;
    for (auto _ : state) benchmark::DoNotOptimize(relight(input, tables));
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
    state.counters["paint_pixels"] = static_cast<double>(input.paintPixels());
}
BENCHMARK(BM_RelightKernel)->Arg(480)->Arg(960)->Arg(1920)->Unit(benchmark::kMillisecond)->UseRealTime();

// Decoding a map into the kernel's arrays: once per map, not per recipe.
void BM_RelightDecode(benchmark::State& state) {
    Scene scene = loadSceneFile(kDemo / "scenes" / "car_body_sky.json");
    scene.camera.width = static_cast<int>(state.range(0));
    scene.camera.height = scene.camera.width * 9 / 16;
    const paintlab::test::TempDir dir;
    buildRayMap(scene, paintlab::test::cheapRayMapSettings(), dir / "map.prm");
    const auto map = RayMap::open(dir / "map.prm");
    map->loadAll();
    for (auto _ : state) benchmark::DoNotOptimize(RelightInput(*map));
}
BENCHMARK(BM_RelightDecode)->Arg(480)->Arg(1920)->Unit(benchmark::kMillisecond)->UseRealTime();

// Per recipe change: the relight tables of a computed BRDF. Argument: preset.
void BM_RelightTables(benchmark::State& state) {
    const auto preset = static_cast<Preset>(state.range(0));
    const LayeredBrdf brdf = computeLayeredBrdf(pearlescent(), presetSettings(preset));
    state.SetLabel(std::string(presetName(preset)));
    const CpuClock cpu;
    for (auto _ : state) benchmark::DoNotOptimize(RelightTables(brdf, 4, 4));
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
}
BENCHMARK(BM_RelightTables)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The preview fast model of the pearlescent demo, for the slider breakdown.
void BM_PreviewFastModel(benchmark::State& state) {
    const Recipe recipe = pearlescent();
    const CpuClock cpu;
    for (auto _ : state)
        benchmark::DoNotOptimize(computeLayeredBrdf(recipe, presetSettings(Preset::Preview)));
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
}
BENCHMARK(BM_PreviewFastModel)->Unit(benchmark::kMillisecond)->UseRealTime();

// Slider to image: what one recipe change costs with the map decoded (the
// recipe parsed once; the fast model at the preview preset, the tables, the
// kernel). Argument: image width.
void BM_SliderToImage(benchmark::State& state) {
    const RelightInput& input = demoInput(static_cast<int>(state.range(0)));
    const Recipe recipe = pearlescent();
    const CpuClock cpu;
    for (auto _ : state) {
        const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(Preset::Preview));
        const RelightTables tables(brdf, input.cells(), input.orders());
        benchmark::DoNotOptimize(relight(input, tables));
    }
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
}
BENCHMARK(BM_SliderToImage)->Arg(480)->Arg(1920)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same image of a paint sphere on a floor, tessellated with 20 x 4^s
// triangles: s = 4 (5,120) and s = 6 (81,920, 16x). The kernel's time must
// not follow the triangle count; the test (test_relight_geometry_cost.cpp)
// checks the counted work, this measures the time (wall and CPU). Argument: s.
void BM_RelightGeometry(benchmark::State& state) {
    const auto s = static_cast<int>(state.range(0));
    const RelightInput& input =
        cachedInput("sphere" + std::to_string(s), paintlab::test::paintSphereOnFloor(960, 540, s));
    const LayeredBrdf brdf = computeLayeredBrdf(pearlescent(), presetSettings(Preset::Preview));
    const RelightTables tables(brdf, input.cells(), input.orders());
    state.SetLabel(std::to_string(20 << (2 * s)) + " sphere triangles");
    const CpuClock cpu;
    for (auto _ : state) benchmark::DoNotOptimize(relight(input, tables));
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
    state.counters["paint_pixels"] = static_cast<double>(input.paintPixels());
}
BENCHMARK(BM_RelightGeometry)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond)->UseRealTime();

// Issue 7: one recipe change in the relight path of the demo map (standard
// preset) with every effect computed (the preset's fast model, the sparkle
// model and pass) against the effect plan (the plan itself, from the map's
// summary, then the fast model at the plan's settings and sparkle only if
// the plan keeps it). Args: image width (48: ~9 cm pixels, where the plan
// skips sparkle; 480: ~2 cm, where it keeps it), recipe (0 silver, 1 solid
// red, 2 pearlescent), 0 = everything / 1 = the plan.
const std::array<const char*, 3> kPlanRecipes{"silver-metallic.json", "solid-red.json",
                                              "pearlescent-two-layer.json"};

void BM_RecipeChangePresetVsPlan(benchmark::State& state) {
    const CachedMap& demo = demoMap(static_cast<int>(state.range(0)));
    const auto name = kPlanRecipes[static_cast<std::size_t>(state.range(1))];
    const Recipe recipe = loadRecipeFile(kDemo / "recipes" / name);
    const bool use_plan = state.range(2) == 1;
    const PlanScene summary = summariseRayMap(*demo.map);  // once per map
    const CpuClock cpu;
    bool sparkle = true;
    FastModelSettings settings = presetSettings(Preset::Standard);
    for (auto _ : state) {
        if (use_plan) {
            const EffectPlan p = plan(recipe, summary, Preset::Standard);
            settings = applyPlan(p, presetSettings(Preset::Standard));
            sparkle = p.sparkle;
        }
        const LayeredBrdf brdf = computeLayeredBrdf(recipe, settings);
        const RelightTables tables(brdf, demo.input->cells(), demo.input->orders());
        RgbImage image = relight(*demo.input, tables);
        if (sparkle) addSparkle(*demo.map, SparkleModel(recipe), image);
        benchmark::DoNotOptimize(image);
    }
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
    state.SetLabel(std::string(name) + (use_plan ? " plan" : " everything") + ": orders " +
                   std::to_string(settings.orders) + ", bands " + std::to_string(settings.bands) +
                   (sparkle ? ", sparkle" : ", no sparkle"));
}
BENCHMARK(BM_RecipeChangePresetVsPlan)
    ->ArgsProduct({{48, 480}, {0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The sparkle pass alone on the demo map (the sparkle model built once).
// Args: image width, recipe.
void BM_SparklePass(benchmark::State& state) {
    const CachedMap& demo = demoMap(static_cast<int>(state.range(0)));
    const Recipe recipe =
        loadRecipeFile(kDemo / "recipes" / kPlanRecipes[static_cast<std::size_t>(state.range(1))]);
    const SparkleModel model(recipe);
    RgbImage image{demo.input->width(), demo.input->height(),
                   std::vector<float>(static_cast<std::size_t>(demo.input->width()) *
                                          static_cast<std::size_t>(demo.input->height()) * 3,
                                      0.0F)};
    const CpuClock cpu;
    for (auto _ : state) benchmark::DoNotOptimize(addSparkle(*demo.map, model, image));
    state.counters["cpu_ms"] = cpu.msPerIteration(state.iterations());
    state.counters["paint_pixels"] = static_cast<double>(demo.input->paintPixels());
}
BENCHMARK(BM_SparklePass)->Args({480, 0})->Args({480, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
