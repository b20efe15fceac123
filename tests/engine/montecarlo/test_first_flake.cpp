// The first-flake walks' draw (first_flake.h): the probability a draw reports
// is the one it was drawn with, and a drawn flake lies in the group its key
// names. The walks' weight divides by that probability, so an error here is a
// bias that the histogram comparison (test_mc_connections.cpp) sees only
// through a whole run; this checks the draw alone, fast.

#include "first_flake.h"
#include "flake_tile.h"
#include "mc_random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace paintlab {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

TEST(FirstFlakeDraw, DrawsEachGroupWithTheProbabilityItReportsAndFromThatGroup) {
    // The demo's basecoat flakes (6 %, 18 µm, 10 deg) in a 15 µm layer at 40-55 µm, a small tile;
    // layer 0 has no tile, so the entries of layer 1 must be found past it.
    const std::vector<mc::FlakeGeometry> kinds{{0.06 / 0.6, 18.0, 10.0, nullptr}};
    const mc::FlakeTile tile(kinds, 40.0, 55.0, 5, 2000, 100000);
    const mc::TiltIndex tilts = mc::tiltIndex(tile);
    const mc::FlakeGroups groups = mc::flakeGroups(tile, tilts, 40.0, 55.0);
    const std::vector<mc::LayerFlakes> layers{mc::LayerFlakes{}, mc::LayerFlakes{&tile, {}, &tilts, &groups}};
    // An uneven learned part (a fixed generator), half of P_G then far from area-proportional.
    mc::FirstFlakeProposal proposal;
    mc::PathRng weights(7, 0, 0, 0);
    for (int k = 0; k < 2 * mc::FlakeGroups::kGroups; ++k)
        proposal.h.push_back(4.0 * weights.uniform() * weights.uniform());
    const double beam_azimuth = 2.0;  // radians: not a multiple of the bin width
    const mc::Vec3 v{0.45 * std::cos(beam_azimuth), 0.45 * std::sin(beam_azimuth),
                     -std::sqrt(1.0 - 0.45 * 0.45)};
    const mc::FirstFlakeTable table = mc::firstFlakeTable(layers, v, proposal);
    ASSERT_EQ(table.cumulative.size(), static_cast<std::size_t>(mc::FlakeGroups::kGroups));
    EXPECT_NEAR(table.cumulative.back(), 1.0, 1e-12);

    constexpr int kDraws = 400000;
    std::vector<double> counts(table.cumulative.size(), 0.0);
    mc::PathRng rng(11, 0, 0, 0);
    const double bin = kTwoPi / mc::FlakeGroups::kAzimuthBins;
    int misplaced = 0;
    int wrong_probability = 0;
    for (int i = 0; i < kDraws; ++i) {
        const double u_group = rng.uniform();
        const double u_flake = rng.uniform();
        const double u1 = rng.uniform();
        const double u2 = rng.uniform();
        const double u3 = rng.uniform();
        const mc::FirstFlakeDraw d = mc::drawFirstFlake(layers, table, u_group, u_flake, u1, u2, u3);
        ASSERT_EQ(d.layer, 1);
        // The entry the key names (keys of layer 1 start at kGroups).
        const int relative_group = d.key - mc::FlakeGroups::kGroups;
        std::size_t e = 0;
        while (e < table.key.size() && table.key[e] != d.key) ++e;
        ASSERT_LT(e, table.key.size());
        counts[e] += 1.0;
        const double p = table.cumulative[e] - (e > 0 ? table.cumulative[e - 1] : 0.0);
        if (std::abs(d.probability - p) > 1e-12 * p) ++wrong_probability;
        // The flake lies in the key's group: its tilt quantile (the edges from the
        // tile's sorted tilts), its depth third, and the azimuth bin of its upward
        // normal, counted from the beam's azimuth rounded to a whole bin.
        const mc::PlacedFlake& f = tile.flakes()[d.flake];
        const int depth_third = relative_group % mc::FlakeGroups::kDepthBins;
        const int azimuth_bin =
            (relative_group / mc::FlakeGroups::kDepthBins) % mc::FlakeGroups::kAzimuthBins;
        const int tilt_bin = relative_group / (mc::FlakeGroups::kDepthBins * mc::FlakeGroups::kAzimuthBins);
        const double depth = -f.centre.z;
        const bool depth_ok =
            depth >= 40.0 + 5.0 * depth_third - 1e-9 && depth <= 45.0 + 5.0 * depth_third + 1e-9;
        const double up = f.normal.z < 0.0 ? -1.0 : 1.0;
        const double tilt = std::acos(std::min(1.0, std::abs(f.normal.z)));
        const auto edge = [&](int q) {
            return tilts.tilt[tilts.tilt.size() * static_cast<std::size_t>(q) / mc::FlakeGroups::kTiltBins];
        };
        const bool tilt_ok = (tilt_bin == 0 || tilt >= edge(tilt_bin)) &&
                             (tilt_bin == mc::FlakeGroups::kTiltBins - 1 || tilt < edge(tilt_bin + 1));
        double phi = std::atan2(up * f.normal.y, up * f.normal.x);
        phi -= kTwoPi * std::floor(phi / kTwoPi);
        const int shift =
            static_cast<int>(std::floor(beam_azimuth / bin + 0.5)) % mc::FlakeGroups::kAzimuthBins;
        const int tile_bin = std::min(static_cast<int>(phi / bin), mc::FlakeGroups::kAzimuthBins - 1);
        const bool azimuth_ok = tile_bin == (azimuth_bin + shift) % mc::FlakeGroups::kAzimuthBins;
        if (!depth_ok || !azimuth_ok || !tilt_ok) ++misplaced;
        // The point is on the drawn flake's plane (pointOnFlake works in double:
        // 1e-9 µm is rounding at the tile's ~100 µm coordinates).
        const mc::Vec3 r{d.point.x - f.centre.x, d.point.y - f.centre.y, d.point.z - f.centre.z};
        EXPECT_NEAR(mc::dot(r, f.normal), 0.0, 1e-9);
    }
    EXPECT_EQ(wrong_probability, 0);
    EXPECT_EQ(misplaced, 0);
    // Counts against N P_G: chi-square over the entries expected at least 20
    // times, as a z-score of its (dof, 2 dof) normal approximation; |z| < 4
    // (two-sided significance ~6e-5): a draw off by a factor in one group of
    // ~1 % probability moves chi-square by ~N p = 4000.
    double chi2 = 0.0;
    int dof = -1;
    for (std::size_t e = 0; e < counts.size(); ++e) {
        const double expected = kDraws * (table.cumulative[e] - (e > 0 ? table.cumulative[e - 1] : 0.0));
        if (expected < 20.0) continue;
        chi2 += (counts[e] - expected) * (counts[e] - expected) / expected;
        ++dof;
    }
    ASSERT_GT(dof, 50);
    const double z = (chi2 - dof) / std::sqrt(2.0 * dof);
    std::printf("chi-square %.1f for %d degrees of freedom, z = %.2f\n", chi2, dof, z);
    EXPECT_LT(std::abs(z), 4.0);
}

}  // namespace
}  // namespace paintlab
