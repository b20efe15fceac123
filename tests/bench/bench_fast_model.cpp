// The fast model's cost: every preset on every demo recipe, and how the time
// grows with nodes, Fourier orders, bands and layers, and the cost of one doubling
// step per node count (issue 3, "Speed"). Figures for docs/PERFORMANCE.md come
// from running bench_engine directly; the smoke test only checks they run.
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/layered/layer_operator.h"
#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/layered/quadrature.h"
#include "paintlab/engine/recipe_json.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

const std::filesystem::path kDemo = std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes";
constexpr std::array<const char*, 3> kRecipes{"pearlescent-two-layer", "silver-metallic", "solid-red"};

paintlab::Recipe demo(int index) {
    return paintlab::loadRecipeFile(kDemo /
                                    (std::string(kRecipes[static_cast<std::size_t>(index)]) + ".json"));
}

// Arguments: recipe index, preset (0 preview, 1 standard, 2 reference).
void BM_FastModelPreset(benchmark::State& state) {
    const auto recipe = demo(static_cast<int>(state.range(0)));
    const auto preset = static_cast<paintlab::Preset>(state.range(1));
    const auto settings = paintlab::presetSettings(preset);
    state.SetLabel(std::string(kRecipes[static_cast<std::size_t>(state.range(0))]) + "/" +
                   std::string(paintlab::presetName(preset)));
    for (auto _ : state) benchmark::DoNotOptimize(paintlab::computeLayeredBrdf(recipe, settings));
}
BENCHMARK(BM_FastModelPreset)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FastModelPreset)
    ->ArgsProduct({{0, 1, 2}, {2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

// A filler of large particles (g = 0.9) in a 20 µm coat over a white base:
// what computing its single scattering exactly and refining the grid for its
// sharp lobe cost (arguments: preset 1 standard / 2 reference; cures 0 off /
// 1 on), and per eval() call (BM_EvalSharpLobe, the same arguments).
paintlab::Recipe sharpLobeRecipe() {
    paintlab::Recipe r;
    r.name = "filler g 0.9";
    paintlab::Layer coat;
    coat.name = "coat";
    coat.thickness_um = 20.0;
    coat.binder.refractive_index = paintlab::Spectrum(1.5);
    paintlab::Pigment filler;
    filler.name = "filler";
    filler.volume_fraction = 0.1;
    filler.sigma_a_per_um = paintlab::Spectrum(0.02);
    filler.sigma_s_per_um = paintlab::Spectrum(1.0);
    filler.hg_g = 0.9;
    coat.components = {filler};
    r.layers = {coat};
    r.substrate = paintlab::LambertianSubstrate{paintlab::Spectrum(0.8)};
    return r;
}

paintlab::FastModelSettings sharpLobeSettings(const benchmark::State& state) {
    auto settings = paintlab::presetSettings(static_cast<paintlab::Preset>(state.range(0)));
    if (state.range(1) == 0) {
        settings.exact_single_scattering = false;
        settings.sharp_nodes = settings.sharp_orders = 0;
        settings.sharp_max_start_tau = 1.0;
    }
    return settings;
}

void BM_FastModelSharpLobe(benchmark::State& state) {
    const auto recipe = sharpLobeRecipe();
    const auto settings = sharpLobeSettings(state);
    for (auto _ : state) benchmark::DoNotOptimize(paintlab::computeLayeredBrdf(recipe, settings));
}
BENCHMARK(BM_FastModelSharpLobe)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EvalSharpLobe(benchmark::State& state) {
    const auto brdf = paintlab::computeLayeredBrdf(sharpLobeRecipe(), sharpLobeSettings(state));
    std::vector<double> out(brdf.wavelengthsNm().size());
    const auto wi = paintlab::directionFromAnglesDeg(45.0, 0.0);
    const auto wo = paintlab::directionFromAnglesDeg(30.0, 150.0);
    for (auto _ : state) {
        brdf.eval(wi, wo, out);
        benchmark::DoNotOptimize(out.data());
    }
}
BENCHMARK(BM_EvalSharpLobe)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMicrosecond);

// Scaling on the pearlescent demo around the standard preset: one knob at a time.
enum Knob { kNodes, kOrders, kBands };

void BM_FastModelScaling(benchmark::State& state) {
    const auto recipe = demo(0);
    auto settings = paintlab::presetSettings(paintlab::Preset::Standard);
    const auto value = static_cast<int>(state.range(1));
    switch (static_cast<Knob>(state.range(0))) {
    case kNodes:
        settings.nodes = value;
        state.SetLabel("nodes " + std::to_string(value));
        break;
    case kOrders:
        settings.orders = value;
        settings.order_tolerance = 0.0;  // every order computed
        state.SetLabel("orders " + std::to_string(value));
        break;
    case kBands:
        settings.bands = value;
        state.SetLabel("bands " + std::to_string(value));
        break;
    }
    for (auto _ : state) benchmark::DoNotOptimize(paintlab::computeLayeredBrdf(recipe, settings));
}
BENCHMARK(BM_FastModelScaling)
    ->ArgsProduct({{kNodes}, {12, 16, 24, 32, 48}})
    ->ArgsProduct({{kOrders}, {4, 8, 16, 32}})
    ->ArgsProduct({{kBands}, {4, 8, 16, 32}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Scaling with the number of layers at the standard preset: the pearlescent
// demo's basecoat (15 µm, pearl flakes + carbon black) alone for 1 layer, and
// under the demo's 40 µm clear coat repeated, as L - 1 basecoats, for L >= 2.
void BM_FastModelLayers(benchmark::State& state) {
    const auto demo_recipe = demo(0);
    const auto layers = static_cast<std::size_t>(state.range(0));
    auto recipe = demo_recipe;
    recipe.layers.clear();
    if (layers == 1) {
        recipe.layers.push_back(demo_recipe.layers[1]);
    } else {
        recipe.layers.push_back(demo_recipe.layers[0]);
        for (std::size_t i = 1; i < layers; ++i) recipe.layers.push_back(demo_recipe.layers[1]);
    }
    const auto settings = paintlab::presetSettings(paintlab::Preset::Standard);
    state.SetLabel("layers " + std::to_string(layers));
    for (auto _ : state) benchmark::DoNotOptimize(paintlab::computeLayeredBrdf(recipe, settings));
}
BENCHMARK(BM_FastModelLayers)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Arg(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One doubling step (LU of I - R R and three products) of an n-node slab:
// 16 doublings of a g = 0.75 slab divided by 16.
void BM_DoublingStep(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const auto q = paintlab::layered::makeQuadrature(n, 1.5);
    const auto phase = paintlab::layered::henyeyGreensteinDeltaM(0.75, n);
    const auto h = paintlab::layered::phaseMatrices(q.mu, phase.chi, 0);
    paintlab::layered::DoublingOptions options;
    options.max_start_tau = 1.0 / 1024.0;
    for (auto _ : state)
        benchmark::DoNotOptimize(paintlab::layered::homogeneousSlab(q, h, 0.9, 64.0, 0, options));
    state.counters["s_per_doubling"] =
        benchmark::Counter(16.0 * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DoublingStep)
    ->Arg(8)
    ->Arg(16)
    ->Arg(24)
    ->Arg(32)
    ->Arg(48)
    ->Arg(64)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
