// Report tool (not a test): bytes per paint pixel against relight error as
// J (cells in mu_i) and M_L (azimuthal orders) change, on the demo scene.
// One brute-force reference (its noise estimated per pixel), one ray map
// per (J, M_L) and a second of another seed (the precompute's noise), the
// comparison of paint_comparison.h. Figures for docs/RAYMAPS.md:
//   build/release/tests/raymaps/raymap_tradeoff_report [width] [spp]

#include "paint_comparison.h"
#include "temp_dir.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/scene.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

int main(int argc, char** argv) {
    using namespace paintlab;
    using namespace paintlab::raymaps;
    const std::filesystem::path demo(PAINTLAB_DEMO_DIR);
    const int width = argc > 1 ? std::atoi(argv[1]) : 96;
    const int spp = argc > 2 ? std::atoi(argv[2]) : 1024;
    Scene scene = loadSceneFile(demo / "scenes" / "car_body_sky.json");
    scene.camera.width = width;
    scene.camera.height = width * 9 / 16;
    const LayeredBrdf brdf = computeLayeredBrdf(
        loadRecipeFile(demo / "recipes" / "pearlescent-two-layer.json"), presetSettings(Preset::Preview));
    ReferenceSettings rs;
    rs.samples_per_pixel = spp;
    const ReferenceImage reference = renderReference(scene, RelightTables(brdf, 4, 4), rs);
    const test::TempDir dir;
    std::printf(
        "| J | M_L | bytes per paint pixel | mean bias R / G / B | systematic RMSE (3-sigma bound) |\n");
    std::printf("|---|---|---|---|---|\n");
    constexpr std::array<std::pair<int, int>, 7> kGrid{
        {{1, 1}, {2, 2}, {4, 2}, {2, 4}, {4, 4}, {8, 4}, {4, 8}}};
    compare::PaintComparison last;
    for (const auto& [cells, orders] : kGrid) {
        RayMapSettings s;
        s.aa_samples = 16;
        s.light_rays = 256;
        s.cells = cells;
        s.orders = orders;
        const RayMapHeader h = buildRayMap(scene, s, dir / "a.prm");
        s.seed = 2;
        buildRayMap(scene, s, dir / "b.prm");
        const auto map = RayMap::open(dir / "a.prm");
        const RelightTables tables(brdf, cells, orders);
        const RgbImage a = relight(*map, tables);
        const RgbImage b = relight(*RayMap::open(dir / "b.prm"), tables);
        const auto c = compare::comparePaint(
            a, reference, compare::interiorPaintMask(*map, compare::notSunGlint(*map, 10.0)), b);
        last = c;
        std::printf("| %d | %d | %zu | %+.2f / %+.2f / %+.2f %% | %.2f %% (%.2f %%) |\n", cells, orders,
                    recordBytes(cells, orders, static_cast<int>(h.lights.size())), 100 * c.bias[0],
                    100 * c.bias[1], 100 * c.bias[2], 100 * c.systematic,
                    100 * std::sqrt(c.systematic * c.systematic + 3.0 * c.systematic2_sigma));
        std::fflush(stdout);
    }
    std::printf("%d paint pixels compared; reference %d spp, its noise %.2f %% per pixel\n", last.pixels, spp,
                100 * last.noise);
    return 0;
}
