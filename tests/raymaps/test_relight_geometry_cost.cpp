// Issue 6: relighting a scene with many more triangles does the same work at
// the same resolution. The relight reads the ray map only: per paint pixel a
// record of a fixed size, whatever the geometry that produced it, and the
// kernel's work is fixed per paint pixel for a given record layout
// (relight.cpp, shadeRows). So the test checks the layout and the number of
// paint pixels, which do not depend on the machine's load; the time
// itself is BM_RelightGeometry's (tests/bench/bench_raymaps.cpp,
// docs/PERFORMANCE.md).

#include "temp_dir.h"
#include "test_scenes.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/raymaps/raymap.h"
#include "paintlab/raymaps/relight.h"
#include "paintlab/raymaps/relight_input.h"
#include "paintlab/raymaps/scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

namespace paintlab::raymaps {
namespace {

TEST(RelightGeometryCost, SixteenTimesTheTrianglesRelightWithTheSameWork) {
    const test::TempDir dir;
    // The cheapest precompute: the relight's work does not depend on it.
    const RayMapSettings s = test::cheapRayMapSettings();
    buildRayMap(test::paintSphereOnFloor(640, 360, 3), s, dir / "coarse.prm");  // 1,280 sphere triangles
    buildRayMap(test::paintSphereOnFloor(640, 360, 5), s, dir / "fine.prm");    // 20,480: 16x
    const auto coarse_map = RayMap::open(dir / "coarse.prm");
    const auto fine_map = RayMap::open(dir / "fine.prm");
    const RelightInput coarse(*coarse_map);
    const RelightInput fine(*fine_map);

    // The records: the same size and layout (J, M_L, lights), whatever the triangles.
    EXPECT_EQ(coarse_map->recordBytes(), fine_map->recordBytes());
    EXPECT_EQ(coarse.cells(), fine.cells());
    EXPECT_EQ(coarse.orders(), fine.orders());
    EXPECT_EQ(coarse.lights(), fine.lights());
    // Up to the silhouette's pixels the same number of paint pixels (the
    // finer sphere is rounder by < 1 %): with the same layout, the same work within 1 %.
    const auto a = static_cast<double>(coarse.paintPixels());
    const auto b = static_cast<double>(fine.paintPixels());
    ASSERT_GT(a, 20000.0);
    EXPECT_NEAR(b / a, 1.0, 0.01);
    std::printf("relight 640 x 360: %.0f / %.0f paint pixels (1,280 / 20,480 triangles)\n", a, b);

    // Both relight to a full image with the same tables (J, M_L of either map).
    const RelightTables tables(computeLayeredBrdf(loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) /
                                                                 "recipes" / "pearlescent-two-layer.json"),
                                                  presetSettings(Preset::Preview)),
                               coarse.cells(), coarse.orders());
    EXPECT_EQ(relight(coarse, tables).rgb.size(), relight(fine, tables).rgb.size());
}

}  // namespace
}  // namespace paintlab::raymaps
