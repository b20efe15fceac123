// Recipe I/O and recipe-to-optics costs: what every recompute pays before
// the fast model starts.
#include "paintlab/engine/layer_optics.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/spectrum.h"

#include <benchmark/benchmark.h>

#include <filesystem>

namespace {

const std::filesystem::path kDemo = std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes";

void BM_LoadDemoRecipe(benchmark::State& state) {
    for (auto _ : state)
        benchmark::DoNotOptimize(paintlab::loadRecipeFile(kDemo / "pearlescent-two-layer.json"));
}
BENCHMARK(BM_LoadDemoRecipe)->Unit(benchmark::kMicrosecond);

// All layers of the pearlescent demo at `bands` wavelengths.
void BM_SlabOpticsAllBands(benchmark::State& state) {
    const auto recipe = paintlab::loadRecipeFile(kDemo / "pearlescent-two-layer.json");
    const auto bands = paintlab::visibleBands(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state)
        for (const auto& layer : recipe.layers)
            for (double nm : bands) benchmark::DoNotOptimize(paintlab::slabOptics(layer, nm));
}
BENCHMARK(BM_SlabOpticsAllBands)->Arg(8)->Arg(41)->Unit(benchmark::kMicrosecond);

}  // namespace
