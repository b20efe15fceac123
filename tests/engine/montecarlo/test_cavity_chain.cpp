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

// dOmega_exit / dOmega_h by central differences of the composed mirrors on
// h's tangent plane: the parallelogram of the two exit differences over the
// square of the steps (eps 1e-5 rad: truncation ~eps^2 = 1e-10 relative,
// rounding ~1e-16 / eps = 1e-11 relative).
double finiteDifferenceJacobian(const mc::Vec3& d, const mc::Vec3& n, const mc::Vec3& h, int k) {
    constexpr double eps = 1e-5;
    mc::Vec3 t1;
    mc::Vec3 t2;
    mc::orthonormalBasis(h, t1, t2);
    const auto exitAt = [&](double a, double b) {
        mc::Vec3 m{h.x + a * t1.x + b * t2.x, h.y + a * t1.y + b * t2.y, h.z + a * t1.z + b * t2.z};
        const double len = std::sqrt(mc::dot(m, m));
        return mc::cavityExit(d, n, {m.x / len, m.y / len, m.z / len}, k);
    };
    const mc::Vec3 pa = exitAt(eps, 0.0);
    const mc::Vec3 ma = exitAt(-eps, 0.0);
    const mc::Vec3 pb = exitAt(0.0, eps);
    const mc::Vec3 mb = exitAt(0.0, -eps);
    const mc::Vec3 area =
        mc::cross({pa.x - ma.x, pa.y - ma.y, pa.z - ma.z}, {pb.x - mb.x, pb.y - mb.y, pb.z - mb.z});
    return std::sqrt(mc::dot(area, area)) / (4.0 * eps * eps);
}

TEST(CavityChain, NormalsSendTheFlightToTheTarget) {
    // Random flights, tilted flakes and targets: every normal returned must
    // map the flight onto the target (the mirrors composed directly), lie
    // in the upper hemisphere, and carry the Jacobian of those mirrors'
    // central differences (its closed form, SO(3)'s left Jacobian); one round
    // trip has its textbook 4 |d.h| (the half vector's), and oneTripNormal
    // finds it without the turn (rounding: 1e-12). Jacobian tolerance
    // 1e-4 relative: the differences' error is ~1e-10; a J off by a power of
    // k or the sin/theta stretch is off by 10 % or more at these angles.
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
                    // The walker's shortcut for one pass (no turn): the same normal and J.
                    mc::CavityNormal direct;
                    ASSERT_TRUE(mc::oneTripNormal(d, n, target, direct));
                    EXPECT_NEAR(direct.h.x, c.h.x, 1e-12);
                    EXPECT_NEAR(direct.h.y, c.h.y, 1e-12);
                    EXPECT_NEAR(direct.h.z, c.h.z, 1e-12);
                    EXPECT_NEAR(direct.jacobian, c.jacobian, 1e-12);
                }
                const double reference = finiteDifferenceJacobian(d, n, c.h, k);
                EXPECT_NEAR(c.jacobian, reference, 1e-4 * reference) << "k = " << k;
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
    // standard errors (printed) plus 1e-3 (the grid).
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
    const auto layer = [](const std::vector<mc::ChainChange>& h) { return mc::cavityChainForm(h).layer; };
    // x c x (j 0, m 1); x2 x1 c x1 x2 (j 0, m 2); x c x c x (j 1, m 1).
    EXPECT_EQ(layer(history({a, b, again(a)})), 1);
    EXPECT_EQ(layer(history({a, b, c, again(b), again(a)})), 1);
    EXPECT_EQ(layer(history({a, b, again(a), again(b), again(a)})), 1);
    EXPECT_EQ(layer(history({top, a, b, again(a)})), 1);
    // Back over three flakes (j 0, m 3): x3 x2 x1 c x1 x2 x3.
    const mc::ChainChange d{5 * 64 + 1, true};
    EXPECT_EQ(layer(history({a, b, c, d, again(c), again(b), again(a)})), 1);
    // Ending at c (m 0): x c x c (j 1), x c x c x c x c (j 3); three round
    // trips then back over x_2 (j 3, m 2).
    EXPECT_EQ(layer(history({a, b, again(a), again(b)})), 1);
    EXPECT_EQ(layer(history({a, b, again(a), again(b), again(a), again(b), again(a), again(b)})), 1);
    EXPECT_EQ(layer(history(
                  {a, b, c, again(b), again(c), again(b), again(c), again(b), again(c), again(b), again(a)})),
              1);
    // Not cavity chains: a top reflection after c; another flake after x;
    // the last change a first meeting (the last-flake connections'); no
    // flake before c; four round trips (j = 4, beyond kMaxCavityRoundTrips =
    // 3), at c or back at x; back at x_1 after ending at c's round trips
    // without x_1 between (x c x c c is no mirror chain: c twice in a row).
    EXPECT_EQ(layer(history({a, b, top, again(a)})), -1);
    EXPECT_EQ(layer(history({a, b, again(a), top})), -1);
    EXPECT_EQ(layer(history({a, b, c, again(a)})), -1);
    EXPECT_EQ(layer(history({a, b})), -1);
    EXPECT_EQ(layer(history({top, b, again(a)})), -1);
    EXPECT_EQ(layer(history(
                  {a, b, again(a), again(b), again(a), again(b), again(a), again(b), again(a), again(b)})),
              -1);
    EXPECT_EQ(layer(history({a, b, again(a), again(b), again(a), again(b), again(a), again(b), again(a),
                             again(b), again(a)})),
              -1);
    EXPECT_EQ(layer(history({a, b, again(a), again(b), again(b)})), -1);
    // x c x c then another flake met before (not x_2): j 1 would go back over x_2.
    EXPECT_EQ(layer(history({a, b, c, again(b), again(c), again(a)})), -1);
    // The flake before c in another layer.
    const mc::ChainChange other{4 * 64 + 2, true};
    EXPECT_EQ(layer(history({other, b, again(other)})), -1);
}

}  // namespace
}  // namespace paintlab
