// The last-flake connections' flake law (last_flake.h): the surface density
// of a virtual flake drawn through a point (rho, relative to the layer's mean
// area density A) must be the tile's own, per depth and tilt: near the
// layer's top and bottom a tilted flake is kept inside the film (flake_tile.h),
// so its surface is thinner there and denser inside. A wrong rho is a bias of
// the connections that only a long run would show (test_mc_connections.cpp);
// this checks the law alone against a built tile, fast.

#include "flake_tile.h"
#include "last_flake.h"
#include "mc_random.h"

#include "paintlab/engine/optics/flake_orientation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace paintlab {
namespace {

TEST(LastFlakeLaw, VirtualFlakeDensityIsTheTilesPerDepthAndTilt) {
    // Large, strongly tilted flakes in a thin layer (8 µm across, spread 25
    // deg, 12 µm of film at 10-22 µm): a tilted flake's half height r sin(tilt)
    // is up to ~3.5 µm, so the edge effect spans half the film. A size spread
    // checks the size bias (rho carries A(d) / E[A]).
    const double top = 10.0;
    const double bottom = 22.0;
    const std::vector<mc::FlakeGeometry> kinds{{0.24, 8.0, 25.0, nullptr, 2.0}};
    const mc::FlakeTile tile(kinds, top, bottom, 3, 100000, 1000000);
    const mc::LastFlakeLaw law = mc::lastFlakeLaw(kinds, top, bottom, tile.polygonSides());
    const double L = tile.sideUm();
    constexpr std::size_t kDepthBins = 6;
    constexpr std::size_t kTiltBins = 3;
    const std::array<double, kTiltBins> tilt_edges{0.2, 0.45, 10.0};  // radians
    const auto tiltBin = [&](double nz) {
        const double tilt = std::acos(std::clamp(std::abs(nz), 0.0, 1.0));
        return static_cast<std::size_t>(std::upper_bound(tilt_edges.begin(), tilt_edges.end(), tilt) -
                                        tilt_edges.begin());
    };
    const double dz = (bottom - top) / static_cast<double>(kDepthBins);
    const auto depthBin = [&](double depth) {
        return static_cast<std::size_t>(
            std::clamp((depth - top) / dz, 0.0, static_cast<double>(kDepthBins) - 0.5));
    };
    // The tile: each flake's area spread over depth by points uniform on its polygon.
    std::vector<double> tile_density(kDepthBins * kTiltBins, 0.0);
    constexpr int kPointsPerFlake = 16;
    mc::PathRng rng(5, 0, 0, 0);
    const auto& flakes = tile.flakes();
    for (std::size_t i = 0; i < flakes.size(); ++i) {
        const std::size_t t = tiltBin(flakes[i].normal.z);
        const double share = tile.flakeAreaUm2(i) / kPointsPerFlake / (L * L * dz);
        for (int p = 0; p < kPointsPerFlake; ++p) {
            const mc::Vec3 point = tile.pointOnFlake(i, rng.uniform(), rng.uniform(), rng.uniform());
            tile_density[depthBin(-point.z) * kTiltBins + t] += share;
        }
    }
    // The law: A E_D[rho 1(tilt bin)] at a depth uniform in the bin.
    const FlakeOrientation orientation(25.0);
    std::vector<double> law_density(kDepthBins * kTiltBins, 0.0);
    constexpr int kDraws = 400000;
    for (std::size_t d = 0; d < kDepthBins; ++d)
        for (int k = 0; k < kDraws; ++k) {
            const FlakeNormal n = orientation.sample(rng.uniform(), rng.uniform());
            const double depth = top + (static_cast<double>(d) + rng.uniform()) * dz;
            const mc::VirtualFlake flake = mc::drawVirtualFlake(law, 0, {n.x, n.y, n.z}, depth, rng);
            law_density[d * kTiltBins + tiltBin(n.z)] += kinds[0].area_density_per_um * flake.rho / kDraws;
        }
    // Tolerance: the sparsest cell (the least tilted third at an edge) holds
    // the area of ~1,200 of the tile's 100,000 flakes, so the tile's own count
    // scatters by ~3 % (Poisson, 1 / sqrt(n), a little more with the sizes'
    // spread); 12 % is 4 of those. The law's mean is exact to ~0.5 % (400,000
    // draws per depth bin). Without the edge effect (rho = 1) the most tilted
    // third's edge cells would be 4-6 times the tile's.
    for (std::size_t d = 0; d < kDepthBins; ++d)
        for (std::size_t t = 0; t < kTiltBins; ++t) {
            const std::size_t c = d * kTiltBins + t;
            std::printf("depth bin %zu tilt bin %zu: tile %.5f law %.5f\n", d, t, tile_density[c],
                        law_density[c]);
            EXPECT_NEAR(law_density[c], tile_density[c], 0.12 * tile_density[c])
                << "depth " << d << " tilt " << t;
        }
}

}  // namespace
}  // namespace paintlab
