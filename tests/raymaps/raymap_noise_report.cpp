// Report tool (not a test): the precompute's per-pixel noise on the paint
// (issue 26, part 4). For each demo scene and each demo recipe, two ray maps
// traced with different seeds (the recipe's colour as the paint stand-in, as
// `paintlab-cli render` builds them), relit with the same recipe; the RMS
// relative difference over the interior paint pixels per channel
// (paint_comparison.h, seedNoise), printed as one map's noise (/ sqrt 2),
// with the precompute time. --passes N: each map is the average of N passes
// (ProgressiveRayMap), the two maps' seeds disjoint. Figures for docs/PERFORMANCE.md and
// docs/VALIDATION.md:
//   build/release/tests/raymaps/raymap_noise_report [--width W] [--aa N]
//       [--light-rays N] [--bake-paths N] [--env-points N] [--env-rays N] [--passes N] [--preset P]
//       [--scene NAME]...
//       [--recipe NAME]...

#include "paint_comparison.h"
#include "temp_dir.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/paint_proxy.h"
#include "paintlab/raymaps/scene.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace {

struct Options {
    int width = 0;  // 0: the scene's
    paintlab::raymaps::RayMapSettings settings;
    std::string preset = "standard";
    std::vector<std::string> scenes;
    std::vector<std::string> recipes;
};

int intArgument(const char* value, const char* name, long low = 1) {
    char* end = nullptr;
    const long v = std::strtol(value, &end, 10);
    if (end == value || *end != '\0' || v < low || v > 1000000) {
        std::fprintf(stderr, "%s: '%s' is not an integer in range\n", name, value);
        std::exit(2);  // NOLINT(concurrency-mt-unsafe)
    }
    return static_cast<int>(v);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) {
            std::fprintf(stderr, "%s needs a value\n", a.c_str());
            std::exit(2);  // NOLINT(concurrency-mt-unsafe)
        }
        const char* v = argv[++i];
        if (a == "--width")
            o.width = intArgument(v, "--width");
        else if (a == "--aa")
            o.settings.aa_samples = intArgument(v, "--aa");
        else if (a == "--light-rays")
            o.settings.light_rays = intArgument(v, "--light-rays");
        else if (a == "--bake-paths")
            o.settings.bake_paths = intArgument(v, "--bake-paths");
        else if (a == "--env-points")
            o.settings.environment_points = intArgument(v, "--env-points", 0);
        else if (a == "--env-rays")
            o.settings.environment_rays = intArgument(v, "--env-rays", 0);
        else if (a == "--passes")
            o.settings.passes = intArgument(v, "--passes");
        else if (a == "--preset")
            o.preset = v;
        else if (a == "--scene")
            o.scenes.emplace_back(v);
        else if (a == "--recipe")
            o.recipes.emplace_back(v);
        else {
            std::fprintf(stderr, "unknown option %s\n", a.c_str());
            std::exit(2);  // NOLINT(concurrency-mt-unsafe)
        }
    }
    if (o.scenes.empty()) o.scenes = {"car_body_sky", "car_body_courtyard"};
    if (o.recipes.empty())
        o.recipes = {"pearlescent-two-layer", "raw-medium-slab", "silver-metallic", "solid-red",
                     "three-layer"};
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace paintlab;
    using namespace paintlab::raymaps;
    const Options o = parse(argc, argv);
    const std::filesystem::path demo(PAINTLAB_DEMO_DIR);
    const test::TempDir dir;
    std::printf(
        "| scene | recipe | paint pixels (all / no glint) | noise R / G / B per pixel, all | per pixel, no "
        "glint | of the mean, no glint | precompute s (wall / CPU) |\n|---|---|---|---|---|---|---|\n");
    double worst = 0.0;
    for (const std::string& name : o.scenes) {
        Scene scene = loadSceneFile(demo / "scenes" / (name + ".json"));
        if (o.width > 0) {
            scene.camera.height = scene.camera.height * o.width / scene.camera.width;
            scene.camera.width = o.width;
        }
        for (const std::string& recipe_name : o.recipes) {
            const LayeredBrdf brdf =
                computeLayeredBrdf(loadRecipeFile(demo / "recipes" / (recipe_name + ".json")),
                                   presetSettings(presetFromName(o.preset)));
            RayMapSettings s = o.settings;
            s.paint_proxy_albedo = paintProxyAlbedo(brdf);
            s.seed = 1;
            const std::clock_t cpu = std::clock();  // all threads of the process
            const RayMapHeader ha = buildRayMap(scene, s, dir / "a.prm");
            s.seed = 1 + static_cast<std::uint64_t>(s.passes);  // seeds 1..N and N+1..2N
            const RayMapHeader hb = buildRayMap(scene, s, dir / "b.prm");
            const double cpu_s = 0.5 * static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
            const auto map = RayMap::open(dir / "a.prm");
            const RelightTables tables(brdf, map->header().cells, map->header().orders);
            const RgbImage a = relight(*map, tables);
            const RgbImage b = relight(*RayMap::open(dir / "b.prm"), tables);
            // Sun glints (coat mirror directions within 10 degrees of a sun or
            // an HDR hotspot) apart: a subpixel image of the disk, sampled by
            // the camera samples' jitter, like sparkle no part of smooth shading.
            const compare::SeedNoise all = compare::seedNoise(a, b, compare::interiorPaintMask(*map));
            const compare::SeedNoise n =
                compare::seedNoise(a, b, compare::interiorPaintMask(*map, compare::notSunGlint(*map, 10.0)));
            const auto pct = [](double difference) { return 100.0 * compare::SeedNoise::perMap(difference); };
            std::printf(
                "| %s | %s | %d / %d | %.2f / %.2f / %.2f %% | %.2f / %.2f / %.2f %% | %.2f / %.2f / %.2f %% "
                "| %.1f / %.1f |\n",
                name.c_str(), recipe_name.c_str(), all.pixels, n.pixels, pct(all.relative[0]),
                pct(all.relative[1]), pct(all.relative[2]), pct(n.relative[0]), pct(n.relative[1]),
                pct(n.relative[2]), pct(n.of_mean[0]), pct(n.of_mean[1]), pct(n.of_mean[2]),
                0.5 * (ha.seconds + hb.seconds), cpu_s);
            std::fflush(stdout);
            worst = std::max(worst, pct(n.relative.maxCoeff()));
        }
    }
    std::printf("worst channel, one map's per-pixel noise away from sun glints: %.2f %%\n", worst);
    return 0;
}
