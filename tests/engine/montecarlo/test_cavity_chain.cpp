// The cavity connections' geometry (cavity_chain.h): the normals that send a
// flight through j + 1 round trips between two flakes into a given
// direction, their Jacobian, and which change histories end a cavity chain
// (the walk's side of the split). The connections' mean against the walks
// they replace is checked in test_mc_connections.cpp.

#include "cavity_chain.h"
#include "mc_random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace paintlab {
namespace {

constexpr double kPi = std::numbers::pi;

mc::Vec3 unitAt(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

TEST(CavityChain, NormalsSendTheFlightToTheTarget) {
    // Random flights, tilted flakes and targets: every normal returned must
    // map the flight onto the target (the mirrors composed directly), lie
    // in the upper hemisphere, and one round trip has its textbook Jacobian
    // 4 |d.h| (the half vector's).
    mc::PathRng rng(7, 1, 2, 3);
    int solved = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const mc::Vec3 d = unitAt(kPi * rng.uniform(), 2.0 * kPi * rng.uniform());
        const mc::Vec3 n = unitAt(0.6 * rng.uniform(), 2.0 * kPi * rng.uniform());
        const mc::Vec3 target = unitAt(0.5 * kPi * rng.uniform(), 2.0 * kPi * rng.uniform());
        for (int k = 1; k <= mc::kMaxCavityRoundTrips + 1; ++k) {
            mc::CavityNormals normals;
            const int count = mc::cavityNormals(d, n, target, k, normals);
            ASSERT_LE(count, k);
            for (int i = 0; i < count; ++i) {
                const mc::CavityNormal& c = normals[static_cast<std::size_t>(i)];
                const mc::Vec3 exit = mc::cavityExit(d, n, c.h, k);
                // Rounding of a few mirrors and trigonometric functions: ~1e-15.
                EXPECT_NEAR(exit.x, target.x, 1e-9);
                EXPECT_NEAR(exit.y, target.y, 1e-9);
                EXPECT_NEAR(exit.z, target.z, 1e-9);
                EXPECT_GE(c.h.z, 0.0);
                if (k == 1) {
                    EXPECT_NEAR(c.jacobian, 4.0 * std::abs(mc::dot(d, c.h)), 1e-12);
                }
                ++solved;
            }
        }
    }
    EXPECT_GT(solved, 3000);  // one normal per trial at k = 1, up to two at k = 2
}

TEST(CavityChain, JacobianAndNormalsChangeVariablesExactly) {
    // Change of variables: for a weight g of the normal h on the upper
    // hemisphere and the map h -> exit (k round trips), the integral over
    // exits of the sum, over the normals returned for each exit, of
    // g(h) / J(h) is the integral of g over the upper hemisphere (every h
    // has one exit). A missed normal (a wrong turn's sense or range) or a
    // wrong J moves it. g = exp(kappa (h.n - 1)), kappa 10 (normals within
    // ~25 degrees of n, like a flake law); the expected value by a
    // quadrature grid. 400k exits uniform on the sphere: the tolerance is 4
    // standard errors (printed) plus 1e-3 (the grid, and the finite
    // differences of J, ~1e-6 relative).
    mc::PathRng rng(11, 5, 6, 7);
    const mc::Vec3 d = unitAt(2.6, 0.4);  // a flight going down at 31 degrees from the nadir
    const mc::Vec3 n = unitAt(0.2, 1.1);
    constexpr double kappa = 10.0;
    const auto g = [&](const mc::Vec3& h) {
        const double mu = mc::dot(h, n);
        return mu > 0.0 ? std::exp(kappa * (mu - 1.0)) : 0.0;
    };
    for (int k = 1; k <= mc::kMaxCavityRoundTrips + 1; ++k) {
        constexpr int kSamples = 400000;
        double sum = 0.0;
        double sum2 = 0.0;
        for (int s = 0; s < kSamples; ++s) {
            const double z = 1.0 - 2.0 * rng.uniform();
            const mc::Vec3 target = unitAt(std::acos(z), 2.0 * kPi * rng.uniform());
            mc::CavityNormals normals;
            const int count = mc::cavityNormals(d, n, target, k, normals);
            double value = 0.0;
            for (int i = 0; i < count; ++i) {
                const mc::CavityNormal& c = normals[static_cast<std::size_t>(i)];
                value += g(c.h) / c.jacobian;
            }
            value *= 4.0 * kPi;
            sum += value;
            sum2 += value * value;
        }
        // The normals within 90 degrees of n, in the upper hemisphere: g's integral there.
        double expected = 0.0;
        {
            constexpr int kGrid = 800;
            for (int a = 0; a < kGrid; ++a)
                for (int b = 0; b < 2 * kGrid; ++b) {
                    const double theta = (a + 0.5) * 0.5 * kPi / kGrid;
                    const double phi = (b + 0.5) * kPi / kGrid;
                    const mc::Vec3 h = unitAt(theta, phi);
                    expected += g(h) * std::sin(theta) * (0.5 * kPi / kGrid) * (kPi / kGrid);
                }
        }
        const double mean = sum / kSamples;
        const double error = std::sqrt(std::max(0.0, sum2 / kSamples - mean * mean) / kSamples);
        std::printf("k = %d: %.5f +- %.5f, expected %.5f\n", k, mean, error, expected);
        EXPECT_NEAR(mean, expected, 4.0 * error + 1e-3 * expected) << "k = " << k;
    }
}

std::vector<mc::ChainChange> history(std::initializer_list<mc::ChainChange> in_time_order) {
    std::vector<mc::ChainChange> latest_first(in_time_order);
    std::reverse(latest_first.begin(), latest_first.end());
    return latest_first;
}

TEST(CavityChain, WhichEscapesEndACavityChain) {
    // Flakes of layer 1 (id = flake * 64 + layer), met before (false) or for
    // the first time (true); -1 another change (the top's internal reflection).
    const mc::ChainChange a{1 * 64 + 1, true};
    const mc::ChainChange b{2 * 64 + 1, true};
    const mc::ChainChange c{3 * 64 + 1, true};
    const auto again = [](mc::ChainChange x) { return mc::ChainChange{x.flake_id, false}; };
    const mc::ChainChange top{-1, false};
    const auto layer = [](const std::vector<mc::ChainChange>& h) { return mc::cavityChainLayer(h); };
    // x c x (j 0, m 1); x2 x1 c x1 x2 (j 0, m 2); x c x c x (j 1, m 1).
    EXPECT_EQ(layer(history({a, b, again(a)})), 1);
    EXPECT_EQ(layer(history({a, b, c, again(b), again(a)})), 1);
    EXPECT_EQ(layer(history({a, b, again(a), again(b), again(a)})), 1);
    EXPECT_EQ(layer(history({top, a, b, again(a)})), 1);
    // Not cavity chains: ends at c; a top reflection after c; another flake
    // after x; the last change a first meeting (the last-flake
    // connections'); no flake before c; two round trips (j = 2, beyond the bound
    // kMaxCavityRoundTrips = 1).
    EXPECT_EQ(layer(history({a, b, again(a), again(b)})), -1);
    EXPECT_EQ(layer(history({a, b, top, again(a)})), -1);
    EXPECT_EQ(layer(history({a, b, again(a), top})), -1);
    EXPECT_EQ(layer(history({a, b, c, again(a)})), -1);
    EXPECT_EQ(layer(history({a, b})), -1);
    EXPECT_EQ(layer(history({top, b, again(a)})), -1);
    EXPECT_EQ(layer(history({a, b, again(a), again(b), again(a), again(b), again(a)})), -1);
    // The flake before c in another layer.
    const mc::ChainChange other{4 * 64 + 2, true};
    EXPECT_EQ(layer(history({other, b, again(other)})), -1);
}

}  // namespace
}  // namespace paintlab
