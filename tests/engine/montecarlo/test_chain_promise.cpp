// The delta walks' promise tables (chain_promise.h). The roulette they steer
// is unbiased for any promise (test_mc_connections.cpp checks the mean), so
// what can go wrong here is only a promise that misses the chains it is
// meant to keep: a wrong half-vector, a wrong frame, or a cone weight that
// does not act. Each is checked against the closed form it tabulates.

#include "chain_promise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace paintlab {
namespace {

constexpr double kPi = std::numbers::pi;

mc::Vec3 unit(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// The direction at the centre of the table's cell (ix, iy) in the beam's
// frame (lateral components), upward or downward; inside the unit disk.
mc::Vec3 cellCentre(int ix, int iy, bool up) {
    const int bins = up ? mc::ChainPromise::kUpBins : mc::ChainPromise::kDownBins;
    const double x = -1.0 + (ix + 0.5) * 2.0 / bins;
    const double y = -1.0 + (iy + 0.5) * 2.0 / bins;
    const double z = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
    return {x, y, up ? z : -z};
}

// D(h) / D(1) = exp(-kappa (1 - h_z)) at the half-vector mirroring `down` into `up`.
double expectedDown(const mc::Vec3& down, const mc::Vec3& up, double kappa) {
    const mc::Vec3 h{up.x - down.x, up.y - down.y, up.z - down.z};
    return std::exp(-kappa * (1.0 - h.z / std::sqrt(mc::dot(h, h))));
}

TEST(ChainPromise, DownwardPromiseIsTheOrientationLawAtTheHalfVector) {
    // Two cones (the flop on the beam's side and the normal); weights 1 and
    // 0.25; kappa of a 10 degree spread. At cell centres the table is exact
    // (float rounding: 1e-6 relative).
    const double kappa = 32.4;
    const std::vector<mc::Vec3> cones{unit(37.0 * kPi / 180.0, kPi), {0.0, 0.0, 1.0}};
    mc::ChainPromise promise(cones, kappa, 0.3);
    EXPECT_FALSE(promise.ready());
    promise.setConeWeights(std::vector<double>{1.0, 0.25});
    ASSERT_TRUE(promise.ready());
    int checked = 0;
    for (int ix = 0; ix < mc::ChainPromise::kDownBins; ix += 3)
        for (int iy = 0; iy < mc::ChainPromise::kDownBins; iy += 5) {
            const mc::Vec3 d = cellCentre(ix, iy, false);
            if (!(d.z < -0.05)) continue;  // the rim's cells hold their nearest point on it
            const double expected =
                expectedDown(d, cones[0], kappa) + 0.25 * expectedDown(d, cones[1], kappa);
            EXPECT_NEAR(promise.at(d, 1.0, 0.0), expected, 1e-6 * (1.0 + expected)) << ix << " " << iy;
            ++checked;
        }
    EXPECT_GT(checked, 200);
    // The mirror image of the flop cone in a horizontal flake (h = z, D at
    // its peak) lies within half a cell of its table cell's centre.
    const mc::Vec3 mirror{cones[0].x, cones[0].y, -cones[0].z};
    EXPECT_GT(promise.at(mirror, 1.0, 0.0), 0.5);
}

TEST(ChainPromise, DirectionsAreReadInTheBeamsFrame) {
    // Turning the direction and the beam together about the normal leaves the
    // promise unchanged (the views turn both; chunkDelta passes the view's beam).
    // A table read in the tile's frame instead would find the mirror image
    // of the cone (promise near 1) at a turned azimuth with a promise near 0.
    const mc::Vec3 cone = unit(37.0 * kPi / 180.0, kPi);
    mc::ChainPromise promise(std::vector<mc::Vec3>{cone}, 32.4, 0.3);
    promise.setConeWeights(std::vector<double>{1.0});
    const mc::Vec3 d{cone.x, cone.y, -cone.z};
    const double unturned = promise.at(d, 1.0, 0.0);
    EXPECT_GT(unturned, 0.5);
    for (double psi : {1.2, 2.5, 4.0}) {  // turns large enough to leave the peak of D
        const double c = std::cos(psi);
        const double s = std::sin(psi);
        const mc::Vec3 turned{c * d.x - s * d.y, s * d.x + c * d.y, d.z};
        EXPECT_NEAR(promise.at(turned, c, s), unturned, 0.05 * unturned) << psi;
        EXPECT_LT(promise.at(turned, 1.0, 0.0), 0.1 * unturned) << psi;
    }
}

TEST(ChainPromise, UpwardPromiseAveragesTheNextFlakeAndIsBoundedByR) {
    // Upward: R E_B[D(h(reflect(d, n_B)))] / D(1), so within [0, R]; for a
    // nearly vertical ray a horizontal flake's underside sends it straight
    // down, which mirrors into a vertical cone through h = z: close to R x the
    // mean of exp(-kappa (1 - h_z)) over the tilts, well above a cone the
    // chain cannot reach in two reflections. A cone weight of 0 silences its cone.
    const double R = 0.3;
    const std::vector<mc::Vec3> cones{{0.0, 0.0, 1.0}, unit(80.0 * kPi / 180.0, 0.0)};
    mc::ChainPromise promise(cones, 32.4, R);
    const mc::Vec3 up = cellCentre(mc::ChainPromise::kUpBins / 2, mc::ChainPromise::kUpBins / 2, true);
    promise.setConeWeights(std::vector<double>{1.0, 0.0});
    const double vertical = promise.at(up, 1.0, 0.0);
    promise.setConeWeights(std::vector<double>{0.0, 1.0});
    const double grazing = promise.at(up, 1.0, 0.0);
    EXPECT_GT(vertical, 0.1 * R);
    EXPECT_LE(vertical, R);
    EXPECT_GE(grazing, 0.0);
    EXPECT_LT(grazing, 0.01 * vertical);
}

}  // namespace
}  // namespace paintlab
