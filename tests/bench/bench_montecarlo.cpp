// The full model's cost (issue 4, "Speed"): the two-layer pearlescent demo to
// 1 % relative standard error at the six multi-angle geometries; Embree ray
// throughput in a flake tile; how the time grows with the tile's flake count
// and with the number of layers; the tabulated BRDF on the preview grid.
// Figures for docs/PERFORMANCE.md come from running bench_montecarlo
// directly; the smoke test runs only the cheap cases.
#include "flake_tile.h"
#include "mc_connection.h"
#include "mc_engine.h"
#include "mc_glints.h"
#include "mc_random.h"
#include "mc_reflected_beams.h"

#include "paintlab/engine/montecarlo/mc_table.h"
#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/spectrum.h"

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace paintlab;

const std::filesystem::path kDemo = std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes";

Recipe pearlescent() { return loadRecipeFile(kDemo / "pearlescent-two-layer.json"); }

// The demo recipes of BM_McDemoOnePercent, by its argument.
constexpr const char* kDemoPaints[] = {"pearlescent-two-layer", "silver-metallic", "three-layer", "solid-red",
                                       "raw-medium-slab"};

// The recipe of the error-budget runs: PAINTLAB_BENCH_RECIPE (a demo recipe's
// name, e.g. silver-metallic, or the path of a recipe file ending in .json,
// e.g. a grid point of tools/compare_report) if set, else the pearlescent demo.
Recipe budgetRecipe() {
    const char* name = std::getenv("PAINTLAB_BENCH_RECIPE");
    if (name == nullptr) return pearlescent();
    const std::string text(name);
    if (text.size() > 5 && text.ends_with(".json")) return loadRecipeFile(text);
    return loadRecipeFile(kDemo / (text + ".json"));
}

// Incidence 45 degrees with the six multi-angle detectors (the `mc` command's
// oblique request), or the first `count` of them (4: 45as-15 to 45as45, near
// the specular direction).
std::vector<mc::IncidenceRequest> multiAngleRequest(std::size_t count = 6) {
    mc::IncidenceRequest oblique{multiAngleGeometry(kAspecularAnglesDeg[0]).wi, {}};
    for (double as : kAspecularAnglesDeg)
        if (oblique.wo.size() < count) oblique.wo.push_back(multiAngleGeometry(as).wo);
    return {oblique};
}

void reportPaths(benchmark::State& state, std::int64_t paths) {
    state.counters["paths"] =
        benchmark::Counter(static_cast<double>(paths), benchmark::Counter::kAvgIterations);
    state.counters["paths_per_s"] =
        benchmark::Counter(static_cast<double>(paths), benchmark::Counter::kIsRate);
}

// CPU seconds of the whole process (every thread): on a loaded machine the
// wall time of a 2-thread run overstates what two idle cores would take.
double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The runs' seed: PAINTLAB_BENCH_SEED if set (the spread of a stop-rule time
// between seeds is part of the figure), else 1.
std::uint64_t benchSeed() {
    const char* text = std::getenv("PAINTLAB_BENCH_SEED");
    return text != nullptr ? std::strtoull(text, nullptr, 10) : 1U;
}

// PAINTLAB_BENCH_OVERLAPS=reject or =allow sets McSettings::reject_overlaps
// of the error-budget runs (unset: the default), so that every part of the
// account can be measured with and without intersecting flakes.
void applyBenchOverlaps(mc::McSettings& s) {
    const char* text = std::getenv("PAINTLAB_BENCH_OVERLAPS");
    if (text == nullptr) return;
    const std::string value(text);
    if (value == "reject")
        s.reject_overlaps = true;
    else if (value == "allow")
        s.reject_overlaps = false;
    else
        throw std::invalid_argument("PAINTLAB_BENCH_OVERLAPS: 'reject' or 'allow', got '" + value + "'");
}

// Where a run's time went: paths and wall seconds per band (stderr, so that
// the benchmark's own table stays parseable).
void printBandTimes(const mc::McResult& r) {
    for (std::size_t b = 0; b < r.bands.size(); ++b)
        std::fprintf(stderr, "  band %3.0f nm: %9lld paths %6.2f s\n", r.wavelengths_nm[b],
                     static_cast<long long>(r.bands[b][0].paths), r.bands[b][0].seconds);
}

// One run with its process CPU time (added to `cpu`) and its band times printed.
mc::McResult timedRun(const Recipe& recipe, std::span<const double> wavelengths,
                      std::span<const mc::IncidenceRequest> requests, const mc::McSettings& s, double& cpu) {
    const double cpu_start = processCpuSeconds();
    mc::McResult r = mc::runMonteCarlo(recipe, wavelengths, requests, s);
    cpu += processCpuSeconds() - cpu_start;
    printBandTimes(r);
    return r;
}

// Explicit-flake estimators of the benchmarks below: the default, or that of 2026-12-01.
void estimatorOf20261201(mc::McSettings& s) {
    s.glint_azimuths = false;
    s.adaptive_fractions = false;
    s.split_branches = false;
}

// Arguments: bands; estimator: 0 continuum flakes + next-event, 1 explicit
// flakes with a 5 degree cone and the default connections (mc_connection.h),
// 2 explicit flakes, the histogram alone and one view per tile (the estimator
// before 2026-12), 3 explicit flakes, the connections of 2026-12-01 (per-view
// glint lists, one fraction for all cones, no split branches), 4 the default
// with the first-flake walks (McSettings::first_flake_walks), 5 the default
// without the delta walks' roulette by promise (McSettings::chain_promise,
// the estimator before 2026-12-04, tenth session); geometries: the
// six multi-angle ones or the four near the specular direction (45as-15 to
// 45as45). Stops every band at 1 % relative standard error of the albedo and
// every f; 2 threads. Explicit flakes run for at most 60 s and report the time
// 1 % would take from the worst error reached (error ~ 1 / sqrt(time)), over
// the requested geometries and over the four near the specular direction,
// both in wall time and in the process's CPU time (cpu_*: all threads).
void BM_McPearlescentOnePercent(benchmark::State& state) {
    const Recipe recipe = pearlescent();
    const auto wavelengths = visibleBands(static_cast<std::size_t>(state.range(0)));
    const auto request = multiAngleRequest(static_cast<std::size_t>(state.range(2)));
    mc::McSettings s;
    s.threads = 2;
    s.max_paths = 100000000;
    s.target_rel_error = 0.01;
    s.explicit_flakes = state.range(1) != 0;
    s.histogram_cone_deg = s.explicit_flakes ? 5.0 : 0.0;
    if (state.range(1) == 2) {
        s.connections = false;
        s.tile_views = 1;
        s.split_branches = false;
    }
    if (state.range(1) == 3) estimatorOf20261201(s);
    if (state.range(1) == 4) s.first_flake_walks = true;
    if (s.explicit_flakes) s.max_seconds = 60.0;
    if (state.range(1) == 5) s.chain_promise = false;
    s.seed = benchSeed();
    std::int64_t paths = 0;
    double worst = 0.0;
    double worst_near = 0.0;
    double seconds = 0.0;
    double cpu = 0.0;
    for (auto _ : state) {
        const mc::McResult r = timedRun(recipe, wavelengths, request, s, cpu);
        paths += r.total_paths;
        seconds += r.seconds;
        for (const auto& band : r.bands)
            for (std::size_t k = 0; k < band[0].brdf_per_sr.size(); ++k) {
                worst = std::max(worst, band[0].brdf_per_sr[k].relError());
                if (k < 4) worst_near = std::max(worst_near, band[0].brdf_per_sr[k].relError());
            }
    }
    reportPaths(state, paths);
    const double to_1pct = std::pow(std::max(worst, 0.01) / 0.01, 2.0);
    const double to_1pct_near = std::pow(std::max(worst_near, 0.01) / 0.01, 2.0);
    state.counters["worst_rel_error"] = worst;
    state.counters["seconds_to_1pct"] = seconds * to_1pct;
    state.counters["worst_rel_error_near"] = worst_near;
    state.counters["seconds_to_1pct_near"] = seconds * to_1pct_near;
    state.counters["cpu_seconds"] = cpu;
    state.counters["cpu_seconds_to_1pct"] = cpu * to_1pct;
    state.counters["cpu_seconds_to_1pct_near"] = cpu * to_1pct_near;
    static const char* const kLabels[] = {"continuum flakes, next-event",
                                          "explicit flakes, connections",
                                          "explicit flakes, histogram only",
                                          "explicit flakes, connections of 2026-12-01",
                                          "explicit flakes, connections with first-flake walks",
                                          "explicit flakes, connections without the roulette by promise"};
    state.SetLabel(std::string(kLabels[state.range(1)]) + ", " + std::to_string(state.range(2)) +
                   " geometries");
}
BENCHMARK(BM_McPearlescentOnePercent)
    ->Args({8, 0, 6})
    ->Args({16, 0, 6})
    ->Args({8, 1, 6})
    ->Args({8, 1, 4})
    ->Args({8, 4, 6})
    ->Args({8, 5, 6})
    ->Args({8, 3, 6})
    ->Args({8, 3, 4})
    ->Args({8, 2, 6})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Issue 30: each demo recipe (kDemoPaints[argument 0]) to 1 % relative
// standard error of both albedos and f at the six multi-angle geometries,
// 8 bands, explicit flakes (as `mc --explicit-flakes --rel-error 0.01`),
// 2 threads, at most argument 1 seconds, the default estimator (argument 2 =
// 0) or the one before issue 30 (1: no roulette of the connections by
// transmittance, McSettings::connection_roulette); reports the time and the process's
// CPU time (all threads; load-independent up to the machine's speed) and,
// when the cap stopped the run, the time 1 % would take from the worst error
// reached (error ~ 1 / sqrt(time)).
void BM_McDemoOnePercent(benchmark::State& state) {
    const auto paint = static_cast<std::size_t>(state.range(0));
    const Recipe recipe = loadRecipeFile(kDemo / (std::string(kDemoPaints[paint]) + ".json"));
    const auto wavelengths = visibleBands(8);
    mc::IncidenceRequest normal{directionFromAnglesDeg(0.0, 0.0), {}};
    const std::vector<mc::IncidenceRequest> requests{normal, multiAngleRequest()[0]};
    mc::McSettings s;
    s.threads = 2;
    s.max_paths = 1000000000;
    s.target_rel_error = 0.01;
    s.explicit_flakes = true;
    s.histogram_cone_deg = 5.0;
    s.max_seconds = static_cast<double>(state.range(1));
    s.connection_roulette = state.range(2) == 0;
    applyBenchOverlaps(s);
    s.seed = benchSeed();
    double worst = 0.0;
    double seconds = 0.0;
    double cpu = 0.0;
    std::int64_t paths = 0;
    for (auto _ : state) {
        const mc::McResult r = timedRun(recipe, wavelengths, requests, s, cpu);
        seconds += r.seconds;
        paths += r.total_paths;
        for (const auto& band : r.bands)
            for (const auto& inc : band) {
                worst = std::max(worst, inc.albedo.relError());
                for (const auto& e : inc.brdf_per_sr) worst = std::max(worst, e.relError());
            }
    }
    reportPaths(state, paths);
    const double to_1pct = std::pow(std::max(worst, 0.01) / 0.01, 2.0);
    state.counters["worst_rel_error"] = worst;
    state.counters["seconds_to_1pct"] = seconds * to_1pct;
    state.counters["cpu_seconds"] = cpu;
    state.counters["cpu_seconds_to_1pct"] = cpu * to_1pct;
    state.SetLabel(std::string(kDemoPaints[paint]) + (state.range(2) == 0 ? "" : ", before issue 30"));
}
BENCHMARK(BM_McDemoOnePercent)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {30, 60}, {0, 1}})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Error budget of the explicit-flake estimate (docs/PERFORMANCE.md, "Full
// model"): the pearlescent demo, 8 bands, 45 degree incidence, the six
// multi-angle geometries, 5 degree cone, a fixed number of paths per band
// (argument 1, thousands); argument 2: one path in this many runs the
// connections (McSettings::connection_fraction; with adaptive fractions, the
// first round's). "Default tiles": the default batches, each its own tile
// (64 of 5,000 flakes since 2026-12-07; 16 of 20,000 before, and 8 before
// 2026-12-03, which the figures of those times used). Argument 0 picks the estimator:
//   0 histogram only (split branches, as every config but 7, 8, 12, 13), default tiles
//     (error over the batches: path + tile spread)
//   1 histogram only, 1 tile (error over paths only)
//   2 / 3 / 4 histogram only, default tiles, scoring only the path class
//     BeamFlake / Smooth / Other (mc_connection.h): each class's share
//   5 connections (the default), default tiles;  6 connections, 1 tile
//   7 the connections of 2026-12-01, default tiles;  8 the default without split
//     branches;  9 the default with one fraction for every cone
//   10 / 11 histogram only, default tiles, class Other only: its chains of delta
//     events from the beam / its delta events after a smooth vertex
//   12 / 13 as 10 / 11 with split branches off
//   14 / 15 as 11, only the paths whose first direction change was a delta /
//     a smooth vertex (the reverse walks' part, McSettings::reverse_walks)
//   16 the default without reverse walks (the estimator before 2026-12-02, third session)
//   17 the default with the first-flake walks (McSettings::first_flake_walks)
//   18 the default without the delta walks' roulette by promise (McSettings::chain_promise)
//   19-24 the default scoring one part alone (issue 30's account per walk kind):
//     19 next-event into the cones, 20 glints, 21 reverse walks, 22 delta-chain
//     walks, 23 forward flake images, 24 the histogram's remainder
//   25 the default without the connections' roulette by transmittance
//     (McSettings::connection_roulette, the estimator before issue 30)
//   26 / 27 the default / the delta-chain walks alone (22) with the
//     last-flake connections on every flake layer (McSettings::last_flake_connections)
//   28 the default walking the flake-free bottom instead of its reflection
//     operator (McSettings::bottom_operator off, the estimator before it)
//   29 / 30 the default / the delta-chain walks alone (22) without the
//     chain connections (McSettings::mirror_chain_connections and
//     interference_chain_connections, the estimator before them)
//   33 the histogram's remainder in the default alone (class Beam and part
//     delta_first of class Other: what no walk or connection takes)
//   34 the drawn cavity chains on (McSettings::cavity_forms: beyond j <= 1,
//     m <= 2, one drawn per flight; the default since 2026-12-06, so 34 is
//     the default now) / 39 off (the default before)
//   40 the default with every flight of the delta walks running the drawn
//     cavity chain (McSettings::adapt_drawn_chain_rate off at rate 1, the
//     estimator before the drawn chains' rate)
//   41 the default with the last-flake connections' cone drawn uniformly
//     (McSettings::kernel_chain_cones off, the estimator before 2026-12-06's
//     kernel-weighted draw)
//   42 the default with every flight of the delta walks running its
//     last-flake connection (McSettings::adapt_chain_length off at L = 0,
//     the estimator before the rate by flight length)
//   35 the default without the chain connections on interference-flake
//     layers (McSettings::interference_chain_connections, before 2026-12-05)
//   36 the default without the forward walk's chain connections
//     (ConnectionParts::forward_chains)
//   37 / 38 the delta-chain walks (22) split in two: their escapes that no
//     chain connection takes, the walks running none (ConnectionParts::
//     delta_chains off) / the chain connections alone (CavityForms::
//     WalkScores::None)
// The figures quoted in docs/PERFORMANCE.md: see there (each row names its
// arguments). Prints f, its standard error and the relative error per band
// and geometry (stdout) and reports the worst relative error, the time 1 %
// would take (wall and process CPU) and the mean square relative error.
void BM_McExplicitBudget(benchmark::State& state) {
    const Recipe recipe = budgetRecipe();
    const auto wavelengths = visibleBands(8);
    const int config = static_cast<int>(state.range(0));
    mc::McSettings s;
    s.threads = 2;
    s.max_paths = state.range(1) * 1000;
    s.explicit_flakes = true;
    s.histogram_cone_deg = 5.0;
    s.connections = (config >= 5 && config <= 9) || config >= 16;
    if (config == 1 || config == 6) s.batches = 1;  // else the default
    if (config >= 2 && config <= 4) {
        s.histogram_classes = mc::HistogramClasses::none();
        s.histogram_classes.beam_flake = config == 2;
        s.histogram_classes.smooth = config == 3;
        s.histogram_classes.other = config == 4;
    }
    if (config >= 10 && config <= 15) {
        s.histogram_classes = mc::HistogramClasses::none();
        s.histogram_classes.other = true;
        // 14: delta_first; 15: smooth_first; else even: delta_chains, odd: delta_first and smooth_first.
        s.histogram_other = mc::HistogramOtherParts::none();
        s.histogram_other.delta_chains = config <= 13 && config % 2 == 0;
        s.histogram_other.delta_first = config == 14 || (config <= 13 && config % 2 == 1);
        s.histogram_other.smooth_first = config == 15 || (config <= 13 && config % 2 == 1);
        s.split_branches = config <= 11 || config >= 14;
    }
    if (config == 16) s.reverse_walks = false;
    if (config == 7) estimatorOf20261201(s);
    if (config == 8) s.split_branches = false;
    if (config == 9) s.adaptive_fractions = false;
    if (state.range(2) > 0) s.connection_fraction = 1.0 / static_cast<double>(state.range(2));
    if (config == 17) s.first_flake_walks = true;
    if (config == 18) s.chain_promise = false;
    if (config >= 19 && config <= 24) {
        s.connection_parts = mc::ConnectionParts::none();
        s.connection_parts.cone_direct = config == 19;
        s.connection_parts.glints = config == 20;
        s.connection_parts.reverse_walks = config == 21;
        s.connection_parts.delta_walks = config == 22;
        s.connection_parts.flake_images = config == 23;
        s.connection_parts.forward_chains = false;
        if (config != 24) s.histogram_classes = mc::HistogramClasses::none();
    }
    if (config == 25) s.connection_roulette = false;
    if (config == 27 || config == 30 || config == 37 || config == 38) {
        s.connection_parts = mc::ConnectionParts::none();
        s.connection_parts.delta_walks = true;
        s.histogram_classes = mc::HistogramClasses::none();
    }
    if (config == 26 || config == 27) s.last_flake_connections = true;
    if (config == 29 || config == 30) s.mirror_chain_connections = s.interference_chain_connections = false;
    if (config == 33) {
        // The histogram's remainder in the default: class Beam and the part of
        // class Other that no walk or connection takes (delta_first).
        s.connection_parts = mc::ConnectionParts::none();
        s.histogram_classes = mc::HistogramClasses::none();
        s.histogram_classes.beam = true;
        s.histogram_classes.other = true;
        s.histogram_other = mc::HistogramOtherParts::none();
        s.histogram_other.delta_first = true;
    }
    if (config == 34 || config == 39) s.cavity_forms.drawn = config == 34;
    if (config == 40)
        s.adapt_drawn_chain_rate = false;            // every flight runs the drawn chain (before 2026-12-06)
    if (config == 41) s.kernel_chain_cones = false;  // the uniform cone draw (before 2026-12-06)
    if (config == 42) s.adapt_chain_length = false;  // every flight connects (before 2026-12-06)
    if (config == 35) s.interference_chain_connections = false;  // before 2026-12-05 (nineteenth session)
    if (config == 36) s.connection_parts.forward_chains = false;
    if (config == 37) s.connection_parts.delta_chains = false;
    if (config == 38) s.cavity_forms.walk_scores = mc::CavityForms::WalkScores::None;
    if (config == 28) s.bottom_operator = false;  // the walk through the flake-free bottom (issue 30)
    applyBenchOverlaps(s);
    s.seed = benchSeed();
    double worst = 0.0;
    double seconds = 0.0;
    double cpu = 0.0;
    double mean_square = 0.0;
    double per_band_to_1pct = 0.0;  // sum over bands of its time x (its worst error / 1 %)^2
    int count = 0;
    std::vector<double> worst_of(std::size(kAspecularAnglesDeg), 0.0);  // per geometry, over the bands
    std::int64_t paths = 0;
    for (auto _ : state) {
        const double cpu_start = processCpuSeconds();
        const mc::McResult r = mc::runMonteCarlo(recipe, wavelengths, multiAngleRequest(), s);
        cpu += processCpuSeconds() - cpu_start;
        seconds += r.seconds;
        paths += r.total_paths;
        for (std::size_t b = 0; b < r.bands.size(); ++b) {
            const auto& inc = r.bands[b][0];
            std::printf("budget config %d  %5.1f nm  %.3f s ", config, r.wavelengths_nm[b], inc.seconds);
            double band_worst = 0.0;
            for (std::size_t k = 0; k < inc.brdf_per_sr.size(); ++k) {
                const auto& e = inc.brdf_per_sr[k];
                std::printf(" %9.4g +- %8.2g (%5.1f %%)", e.mean, e.std_error, 100.0 * e.relError());
                worst = std::max(worst, e.relError());
                band_worst = std::max(band_worst, e.relError());
                worst_of[k] = std::max(worst_of[k], e.relError());
                mean_square += e.relError() * e.relError();
                ++count;
            }
            std::printf("\n");
            per_band_to_1pct += inc.seconds * std::pow(band_worst / 0.01, 2.0);
        }
    }
    reportPaths(state, paths);
    const double to_1pct = std::pow(std::max(worst, 0.01) / 0.01, 2.0);
    state.counters["worst_rel_error"] = worst;
    state.counters["seconds_to_1pct"] = seconds * to_1pct;
    // Each band run to 1 % at its worst geometry alone (what the stop rule does,
    // from fixed-path errors: no stop on a low draw of the error estimate).
    state.counters["seconds_to_1pct_per_band"] = per_band_to_1pct;
    state.counters["cpu_seconds"] = cpu;
    state.counters["cpu_seconds_to_1pct"] = cpu * to_1pct;
    state.counters["rms_rel_error"] = std::sqrt(mean_square / std::max(1, count));
    // Per geometry: the CPU time its worst band would need for 1 % (this run's fractions).
    for (std::size_t k = 0; k < worst_of.size(); ++k)
        state.counters["cpu_to_1pct_45as" + std::to_string(static_cast<int>(kAspecularAnglesDeg[k]))] =
            cpu * std::pow(std::max(worst_of[k], 0.01) / 0.01, 2.0);
}
BENCHMARK(BM_McExplicitBudget)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6}, {100}, {1}})
    ->Args({5, 100, 8})
    ->Args({5, 800, 8})
    ->Args({6, 800, 8})
    ->Args({3, 800, 1})
    ->ArgsProduct({{5, 7, 8, 9}, {150}, {8}})
    ->ArgsProduct({{5, 7, 17, 18}, {1500}, {8}})
    ->ArgsProduct({{10, 11, 12, 13, 14, 15}, {1000}, {1}})
    ->ArgsProduct({{5, 16}, {1500}, {8}})
    ->ArgsProduct({{5, 19, 20, 21, 22, 23, 24}, {20, 200}, {8}})
    ->Args({5, 4, 8})  // with 25: /5/20/8 and /5/200/8 are registered once, above
    ->ArgsProduct({{25}, {4, 20, 200}, {8}})
    ->ArgsProduct({{26, 27}, {20, 100, 200}, {8}})
    // Silver (issue 30): one tile, the first-flake walks, no roulette by promise.
    ->ArgsProduct({{6, 17, 18}, {200}, {8}})
    // Three-layer (issue 30): the bottom operator off, against /5/4/8 and /5/20/8.
    ->ArgsProduct({{28}, {4}, {8}})
    // Silver (issue 30): without the chain connections; the histogram's remainder; the delta walks' escapes
    // and connections apart.
    ->ArgsProduct({{29, 30, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42}, {20, 100, 200}, {8}})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Embree: random rays through the pearlescent basecoat's tile (all of its
// depth, random directions, nearest hit), one thread. Argument: flakes per tile.
void BM_FlakeTileRays(benchmark::State& state) {
    const Recipe recipe = pearlescent();
    const Layer& basecoat = recipe.layers[1];
    const mc::FlakeTile tile(mc::layerFlakeGeometries(basecoat), 0.0, basecoat.thickness_um, 1,
                             static_cast<int>(state.range(0)), 1000000);
    mc::PathRng rng(1, 2, 3, 4);
    const double L = tile.sideUm();
    std::int64_t rays = 0;
    std::int64_t hits = 0;
    for (auto _ : state) {
        for (int i = 0; i < 1024; ++i) {
            const double z = 2.0 * rng.uniform() - 1.0;
            const double phi = 2.0 * std::numbers::pi * rng.uniform();
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            const mc::Vec3 origin{rng.uniform() * L, rng.uniform() * L,
                                  -rng.uniform() * basecoat.thickness_um};
            const mc::FlakeHit hit = tile.intersect(origin, {r * std::cos(phi), r * std::sin(phi), z}, 1e-3,
                                                    4.0 * basecoat.thickness_um);
            hits += hit.kind >= 0 ? 1 : 0;
        }
        rays += 1024;
    }
    state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
    state.counters["hit_fraction"] =
        static_cast<double>(hits) / static_cast<double>(std::max<std::int64_t>(1, rays));
    state.counters["flakes"] = static_cast<double>(tile.flakeCount());
}
BENCHMARK(BM_FlakeTileRays)->Arg(2000)->Arg(20000)->Arg(200000)->Unit(benchmark::kMicrosecond);

// Building one tile of the basecoat against the flake count.
// reflectedBeams (the flake-image connections of the reverse walks and the
// forward flake images): the pearlescent demo's basecoat tile (20,000 flakes),
// the 45 degree beam at 450 nm, points uniform in the basecoat. Argument: 0
// the images off one flake, 1 those off a flake and then the top. Reports the
// candidate flakes tested per call (in the cost model's units: 64 per unit).
void BM_ReflectedBeams(benchmark::State& state) {
    mc::McSettings settings;
    settings.explicit_flakes = true;
    settings.histogram_cone_deg = 5.0;
    settings.batches = 1;
    const Recipe recipe = pearlescent();  // the engine keeps a reference
    const mc::McEngine engine(recipe, settings);
    const mc::McEngine::Band band = engine.band(450.0);
    const mc::PaintStack& stack = band.stack;
    const std::span<const mc::LayerFlakes> tiles = band.explicit_flakes[0];
    const mc::Slice& base = stack.slices.back();
    const double L = tiles[static_cast<std::size_t>(base.layer)].tile->sideUm();
    const Direction wi = multiAngleGeometry(kAspecularAnglesDeg[0]).wi;
    const double ratio = stack.ambient_n / stack.slices.front().n;
    const mc::Vec3 beam_top{-wi.x * ratio, -wi.y * ratio,
                            -std::sqrt(1.0 - (wi.x * wi.x + wi.y * wi.y) * ratio * ratio)};
    const mc::BeamImages images{state.range(0) == 0, state.range(0) == 1};
    mc::PathRng rng(5, 6, 7, 8);
    std::int64_t units = 0;
    std::int64_t calls = 0;
    double sum = 0.0;
    for (auto _ : state) {
        const double depth = base.top_um + rng.uniform() * base.thicknessUm();
        sum += mc::reflectedBeams(stack, tiles, stack.slices.size() - 1, depth, rng.uniform() * L,
                                  rng.uniform() * L, {0.0, 0.0, -1.0}, beam_top, images, &units);
        ++calls;
    }
    benchmark::DoNotOptimize(sum);
    state.counters["units_per_call"] =
        static_cast<double>(units) / static_cast<double>(std::max<std::int64_t>(1, calls));
    state.SetLabel(state.range(0) == 0 ? "off one flake" : "off a flake, then the top");
}
BENCHMARK(BM_ReflectedBeams)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_FlakeTileBuild(benchmark::State& state) {
    const Recipe recipe = pearlescent();
    const Layer& basecoat = recipe.layers[1];
    for (auto _ : state)
        benchmark::DoNotOptimize(mc::FlakeTile(mc::layerFlakeGeometries(basecoat), 0.0, basecoat.thickness_um,
                                               1, static_cast<int>(state.range(0)), 1000000));
}
BENCHMARK(BM_FlakeTileBuild)
    ->Arg(2000)
    ->Arg(20000)
    ->Arg(200000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Explicit flakes: 16384 paths at 550 nm and the six geometries against the
// flakes per tile (tile build for 8 batches included), 2 threads.
void BM_McTileFlakes(benchmark::State& state) {
    const Recipe recipe = pearlescent();
    mc::McSettings s;
    s.threads = 2;
    s.max_paths = 16384;
    s.explicit_flakes = true;
    s.histogram_cone_deg = 5.0;
    s.tile_flakes = static_cast<int>(state.range(0));
    std::int64_t paths = 0;
    for (auto _ : state)
        paths += mc::runMonteCarlo(recipe, std::vector<double>{550.0}, multiAngleRequest(), s).total_paths;
    reportPaths(state, paths);
}
BENCHMARK(BM_McTileFlakes)
    ->Arg(500)
    ->Arg(2000)
    ->Arg(20000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The pearlescent basecoat repeated `layers` times under the clear coat
// (each 15 µm with its flakes and carbon black), 16384 paths at 550 nm,
// continuum (0) or explicit (1) flakes, 2 threads.
void BM_McLayers(benchmark::State& state) {
    Recipe recipe = pearlescent();
    const Layer basecoat = recipe.layers[1];
    recipe.layers.resize(1);
    for (int l = 0; l < state.range(0); ++l) {
        recipe.layers.push_back(basecoat);
        recipe.layers.back().name = "basecoat " + std::to_string(l + 1);
    }
    mc::McSettings s;
    s.threads = 2;
    s.max_paths = 16384;
    s.explicit_flakes = state.range(1) != 0;
    s.histogram_cone_deg = s.explicit_flakes ? 5.0 : 0.0;
    std::int64_t paths = 0;
    for (auto _ : state)
        paths += mc::runMonteCarlo(recipe, std::vector<double>{550.0}, multiAngleRequest(), s).total_paths;
    reportPaths(state, paths);
}
BENCHMARK(BM_McLayers)->ArgsProduct({{1, 2, 4, 8}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The tabulated BRDF (mc_table.h) on the preview grid, 4096 paths per node, 2 threads.
void BM_McTablePreview(benchmark::State& state) {
    const Recipe recipe = pearlescent();
    mc::McSettings s;
    s.threads = 2;
    s.max_paths = 4096;
    std::int64_t paths = 0;
    for (auto _ : state)
        paths += mc::tabulateMonteCarlo(recipe, presetSettings(Preset::Preview), s).total_paths;
    reportPaths(state, paths);
}
BENCHMARK(BM_McTablePreview)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
