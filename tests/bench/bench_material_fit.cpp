// The glTF approximation's fit (engine approx/material_fit.h, issue 29): one
// fitGltfMaterial per demo recipe (argument: its index in kRecipes) on the
// fast model's BRDF at the standard preset, computed once outside the loop.
// Counters: the starts tried, the largest ΔE00 left at the six geometries.
#include "paintlab/engine/approx/material_fit.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe_json.h"

#include <benchmark/benchmark.h>

#include <array>
#include <filesystem>

namespace {

using namespace paintlab;

constexpr std::array<const char*, 5> kRecipes{"pearlescent-two-layer", "raw-medium-slab", "silver-metallic",
                                              "solid-red", "three-layer"};

void BM_GltfFit(benchmark::State& state) {
    const char* name = kRecipes[static_cast<std::size_t>(state.range(0))];
    const Recipe recipe =
        loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes" / (std::string(name) + ".json"));
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(Preset::Standard));
    approx::MaterialFit fit;
    for (auto _ : state) {
        fit = approx::fitGltfMaterial(recipe, brdf);
        benchmark::DoNotOptimize(fit.max_delta_e00);
    }
    state.SetLabel(name);
    state.counters["starts"] = fit.starts;
    state.counters["max_dE00"] = fit.max_delta_e00;
}
BENCHMARK(BM_GltfFit)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

}  // namespace
