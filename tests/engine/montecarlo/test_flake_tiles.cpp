// Explicit-flake tiles: overlap rejection (checked by an independent
// intersection test) and error bars that include the randomness of the flake
// arrangement (batches over tile realisations).

#include "flake_tile.h"
#include "mc_random.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/montecarlo/monte_carlo.h"

#include "test_recipes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

namespace paintlab {
namespace {

constexpr double kPi = std::numbers::pi;

mc::Vec3 sub(const mc::Vec3& a, const mc::Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

// Independent of disksIntersect: two non-coplanar disks meet iff the boundary
// circle of one crosses the other disk (the ends of their common chord lie on
// a boundary). The circle is walked as a 4096-gon: each edge that crosses the
// other disk's plane is tested at its crossing point.
bool boundaryCrosses(const mc::PlacedFlake& a, const mc::PlacedFlake& b) {
    const mc::Vec3& n = a.normal;
    const double sign = std::copysign(1.0, n.z);
    const double k = -1.0 / (sign + n.z);
    const double h = n.x * n.y * k;
    const mc::Vec3 b1{1.0 + sign * n.x * n.x * k, sign * h, -sign * n.x};
    const mc::Vec3 b2{h, sign + n.y * n.y * k, -n.y};
    constexpr int kEdges = 4096;
    auto point = [&](int i) {
        const double phi = 2.0 * kPi * i / kEdges;
        const double u = a.radius_um * std::cos(phi);
        const double v = a.radius_um * std::sin(phi);
        return mc::Vec3{a.centre.x + u * b1.x + v * b2.x, a.centre.y + u * b1.y + v * b2.y,
                        a.centre.z + u * b1.z + v * b2.z};
    };
    mc::Vec3 p = point(0);
    double s = mc::dot(sub(p, b.centre), b.normal);
    for (int i = 1; i <= kEdges; ++i) {
        const mc::Vec3 q = point(i);
        const double t = mc::dot(sub(q, b.centre), b.normal);
        if ((s < 0.0) != (t < 0.0)) {
            const double f = s / (s - t);
            const mc::Vec3 x{p.x + f * (q.x - p.x), p.y + f * (q.y - p.y), p.z + f * (q.z - p.z)};
            const mc::Vec3 d = sub(x, b.centre);
            if (mc::dot(d, d) < b.radius_um * b.radius_um) return true;
        }
        p = q;
        s = t;
    }
    return false;
}

bool intersectsIndependently(const mc::PlacedFlake& a, const mc::PlacedFlake& b) {
    return boundaryCrosses(a, b) || boundaryCrosses(b, a);
}

TEST(FlakeOverlap, DiskTestAgreesWithBoundaryWalk) {
    // Random disks around one another (random normals, radii 1-3, centres within 5):
    // the chord test and the boundary walk agree on every pair.
    std::uint64_t state = 12345;
    auto uniform = [&state] { return double(mc::splitMix64(state) >> 11U) * 0x1.0p-53; };
    auto randomNormal = [&] {
        const double z = 2.0 * uniform() - 1.0;
        const double phi = 2.0 * kPi * uniform();
        const double r = std::sqrt(1.0 - z * z);
        return mc::Vec3{r * std::cos(phi), r * std::sin(phi), z};
    };
    int intersecting = 0;
    for (int i = 0; i < 3000; ++i) {
        const mc::PlacedFlake a{{0.0, 0.0, 0.0}, randomNormal(), 1.0 + 2.0 * uniform(), 0};
        const mc::PlacedFlake b{{5.0 * (uniform() - 0.5), 5.0 * (uniform() - 0.5), 5.0 * (uniform() - 0.5)},
                                randomNormal(),
                                1.0 + 2.0 * uniform(),
                                0};
        const bool chord = mc::disksIntersect(a, b);
        EXPECT_EQ(chord, intersectsIndependently(a, b)) << "pair " << i;
        EXPECT_EQ(chord, mc::disksIntersect(b, a)) << "pair " << i;
        intersecting += chord ? 1 : 0;
    }
    // Both outcomes are exercised.
    EXPECT_GT(intersecting, 300);
    EXPECT_LT(intersecting, 2700);
    // Coplanar and parallel cases, which the boundary walk cannot see.
    const mc::Vec3 up{0.0, 0.0, 1.0};
    EXPECT_TRUE(mc::disksIntersect({{0, 0, 0}, up, 1.0, 0}, {{1.5, 0, 0}, up, 1.0, 0}));
    EXPECT_FALSE(mc::disksIntersect({{0, 0, 0}, up, 1.0, 0}, {{2.5, 0, 0}, up, 1.0, 0}));
    EXPECT_FALSE(mc::disksIntersect({{0, 0, 0}, up, 1.0, 0}, {{0.5, 0, 0.1}, up, 1.0, 0}));
}

std::vector<mc::FlakeGeometry> denseFlakes() {
    // 10 µm flakes with a 25 degree spread, 1.5 flake layers of coverage in a 10 µm film
    // (area density x thickness / flake area): crowded enough that random placement overlaps.
    return {{0.15, 10.0, 25.0, nullptr}};
}

// Whether one disk lies wholly on one side of the other's plane (then they
// cannot meet): a cheap exact pre-test that spares the boundary walk most pairs.
bool apart(const mc::PlacedFlake& a, const mc::PlacedFlake& b) {
    const auto side = [](const mc::PlacedFlake& p, const mc::PlacedFlake& q) {
        const double c = mc::dot(p.normal, q.normal);
        return std::abs(mc::dot(sub(p.centre, q.centre), q.normal)) >
               p.radius_um * std::sqrt(std::max(0.0, 1.0 - c * c)) * (1.0 + 1e-9);
    };
    return side(a, b) || side(b, a);
}

// Intersecting pairs of a tile, each pair at its nearest periodic image, by
// the independent test; the candidates are found by lateral cells as wide as
// the largest flake (every pair within reach shares a cell or a neighbouring one).
int overlappingPairs(const mc::FlakeTile& tile) {
    const auto& flakes = tile.flakes();
    const double L = tile.sideUm();
    double r_max = 0.0;
    for (const auto& f : flakes) r_max = std::max(r_max, f.radius_um);
    const int cells = std::max(1, static_cast<int>(L / (2.0 * r_max)));
    const auto cellOf = [&](double c) { return std::clamp(static_cast<int>(c / L * cells), 0, cells - 1); };
    const auto binOf = [cells](int i, int j) {
        return static_cast<std::size_t>(i) * static_cast<std::size_t>(cells) + static_cast<std::size_t>(j);
    };
    std::vector<std::vector<std::size_t>> bins(binOf(cells, 0));
    for (std::size_t i = 0; i < flakes.size(); ++i)
        bins[binOf(cellOf(flakes[i].centre.x), cellOf(flakes[i].centre.y))].push_back(i);
    int pairs = 0;
    for (std::size_t i = 0; i < flakes.size(); ++i) {
        const int ci = cellOf(flakes[i].centre.x);
        const int cj = cellOf(flakes[i].centre.y);
        std::vector<std::size_t> seen;
        for (int di = -1; di <= 1; ++di)
            for (int dj = -1; dj <= 1; ++dj) {
                const int bi = ((ci + di) % cells + cells) % cells;
                const int bj = ((cj + dj) % cells + cells) % cells;
                for (std::size_t j : bins[binOf(bi, bj)]) {
                    if (j <= i || std::find(seen.begin(), seen.end(), j) != seen.end()) continue;
                    seen.push_back(j);
                    mc::PlacedFlake b = flakes[j];
                    b.centre.x -= L * std::round((b.centre.x - flakes[i].centre.x) / L);
                    b.centre.y -= L * std::round((b.centre.y - flakes[i].centre.y) / L);
                    const double dx = b.centre.x - flakes[i].centre.x;
                    const double dy = b.centre.y - flakes[i].centre.y;
                    const double reach = flakes[i].radius_um + b.radius_um;
                    if (dx * dx + dy * dy >= reach * reach || apart(flakes[i], b)) continue;
                    if (intersectsIndependently(flakes[i], b)) ++pairs;
                }
            }
    }
    return pairs;
}

// A tile placed freely and with overlap rejection from the same seed: their
// flake count and intersecting pairs (printed with PAINTLAB_MC_VERBOSE).
struct Overlaps {
    std::size_t flakes = 0;
    int free = 0;
    int rejected = 0;
};
Overlaps overlapsFreeAndRejected(const std::vector<mc::FlakeGeometry>& kinds, double top, double bottom,
                                 std::uint64_t seed, int target_flakes) {
    const mc::FlakeTile free(kinds, top, bottom, seed, target_flakes, 200000, false);
    const mc::FlakeTile rejected(kinds, top, bottom, seed, target_flakes, 200000, true);
    EXPECT_EQ(free.flakes().size(), rejected.flakes().size());
    const Overlaps o{free.flakes().size(), overlappingPairs(free), overlappingPairs(rejected)};
    if (std::getenv("PAINTLAB_MC_VERBOSE") != nullptr)
        std::printf("  %zu flakes: %d intersecting pairs placed freely, %d with rejection\n", o.flakes,
                    o.free, o.rejected);
    return o;
}

TEST(FlakeOverlap, RejectionLeavesNoIntersectingPair) {
    const Overlaps o = overlapsFreeAndRejected(denseFlakes(), 0.0, 10.0, 9, 400);
    EXPECT_GT(o.free, 0);
    EXPECT_EQ(o.rejected, 0);
}

TEST(FlakeOverlap, SilverMetallicPlacesWithoutIntersections) {
    // The silver demo's basecoat (18 µm aluminium at 4 %, 12 degrees, ~2 flake
    // layers in 15 µm) as the engine builds it with reject_overlaps: 20,000
    // flakes, the seed of seed 1's first batch tile (mc_engine.cpp). Its most
    // tilted flakes need up to ~1,800 lateral draws; with the former cap of
    // 1,000 this tile threw InputError at its 19,800th flake.
    const Recipe silver = test::demoRecipe("silver-metallic");
    const auto kinds = mc::layerFlakeGeometries(silver.layers[1]);
    const double top = silver.layers[0].thickness_um;
    const double bottom = top + silver.layers[1].thickness_um;
    const Overlaps o = overlapsFreeAndRejected(kinds, top, bottom, 1U ^ (0x9e3779b97f4a7c15ULL * 2U), 20000);
    // Placed freely, the flakes intersect about once per flake (21,308 pairs):
    // the check sees them, so its 0 below is not for want of looking.
    EXPECT_GT(o.free, 10000);
    EXPECT_EQ(o.rejected, 0);
}

TEST(FlakeOverlap, ImpossibleConcentrationIsAnInputError) {
    // 20 flake layers of coverage in a film thinner than a flake: no room for flat disks.
    const std::vector<mc::FlakeGeometry> packed{{2.0, 10.0, 5.0, nullptr}};
    EXPECT_THROW(mc::FlakeTile(packed, 0.0, 5.0, 1, 200, 100000, true), InputError);
}

// A ray from a point uniform in the film of the tiles below (depth 40-55 µm,
// anywhere over the tile of side L) in a direction uniform on the sphere.
struct Ray {
    mc::Vec3 origin;
    mc::Vec3 dir;
};
Ray rayInTheFilm(mc::PathRng& rng, double L) {
    const double z = 2.0 * rng.uniform() - 1.0;
    const double phi = 2.0 * kPi * rng.uniform();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const mc::Vec3 dir{r * std::cos(phi), r * std::sin(phi), z};
    return {{rng.uniform() * L, rng.uniform() * L, -40.0 - 15.0 * rng.uniform()}, dir};
}

TEST(FlakeTileHits, NameTheirFlakeAndLieOnItsPlaneInALargeTile) {
    // A tile about 1.8 mm across (the pearlescent demo's basecoat: 20,000
    // flakes of 18 µm): Embree's ray is float, so its origin is rounded by up
    // to ~6e-5 µm there and the distance it returns is off by as much. The
    // connections recognise the flake a shadow ray must reach by the index the
    // hit reports, and put vertices at the hit point, so: every hit names a
    // flake (or a periodic copy of it) whose plane holds the hit point to
    // double rounding (1e-9 µm against coordinates of ~1e3 µm: ~1e4 ulps of
    // headroom, and ~1e5 times below the float error it replaces) and whose
    // polygon holds it.
    // Flake area per volume: 6 % by volume of flakes ~0.6 µm thick.
    const std::vector<mc::FlakeGeometry> basecoat{{0.06 / 0.6, 18.0, 10.0, nullptr}};
    const mc::FlakeTile tile(basecoat, 40.0, 55.0, 3, 20000, 1000000);
    const double L = tile.sideUm();
    ASSERT_GT(L, 1000.0);
    mc::PathRng rng(4, 5, 6, 7);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const auto [origin, dir] = rayInTheFilm(rng, L);
        const mc::FlakeHit hit = tile.intersect(origin, dir, 1e-3, 60.0);
        if (hit.kind < 0) continue;
        ++hits;
        ASSERT_GE(hit.flake, 0);
        ASSERT_LT(hit.flake, static_cast<std::int64_t>(tile.flakes().size()));
        const mc::PlacedFlake& f = tile.flakes()[static_cast<std::size_t>(hit.flake)];
        const mc::Vec3 p{origin.x + hit.t * dir.x, origin.y + hit.t * dir.y, origin.z + hit.t * dir.z};
        // The periodic copy nearest the hit point.
        mc::Vec3 rel = sub(p, f.centre);
        rel.x -= L * std::round(rel.x / L);
        rel.y -= L * std::round(rel.y / L);
        EXPECT_LT(std::abs(mc::dot(rel, f.normal)), 1e-9) << "hit " << i;
        EXPECT_TRUE(tile.onFlake(static_cast<std::size_t>(hit.flake), rel)) << "hit " << i;
        EXPECT_GT(std::abs(mc::dot(hit.normal, f.normal)), 1.0 - 1e-12) << "hit " << i;
    }
    EXPECT_GT(hits, 1000);
}

// Embree returns the nearest flake: the same flake and distance as a
// brute-force search over every flake and its eight periodic images (the
// plane crossing, then FlakeTile::onFlake), for rays from random points of
// the film in random directions. Segments are kept inside the tile, where
// every image they can meet is one of Embree's copies. This is what the
// intersection callback's data layout and the primitives' memory order must
// not change (docs/PERFORMANCE.md, "Where the time goes"). Distances agree
// to 1e-9 µm (double rounding on µm-sized segments; the float BVH only culls).
// For the default 16-gons and for exact disks (McSettings::flake_polygon_sides).
void expectNearestOfABruteForceSearch(int sides) {
    const std::vector<mc::FlakeGeometry> basecoat{{0.06 / 0.6, 18.0, 10.0, nullptr}};
    const mc::FlakeTile tile(basecoat, 40.0, 55.0, 11, 1500, 1000000, false, nullptr, sides);
    const double L = tile.sideUm();
    const auto& flakes = tile.flakes();
    mc::PathRng rng(8, 9, 10, 11);
    int hits = 0;
    int rays = 0;
    for (int i = 0; i < 3000; ++i) {
        const auto [origin, dir] = rayInTheFilm(rng, L);
        // Up to 40 µm, and not beyond the tile's sides.
        double t_far = 40.0;
        if (dir.x != 0.0) t_far = std::min(t_far, (dir.x > 0.0 ? L - origin.x : -origin.x) / dir.x);
        if (dir.y != 0.0) t_far = std::min(t_far, (dir.y > 0.0 ? L - origin.y : -origin.y) / dir.y);
        const double t_near = 1e-3;
        if (!(t_far > t_near)) continue;
        ++rays;
        double best_t = t_far;
        std::int64_t best = -1;
        for (std::size_t f = 0; f < flakes.size(); ++f) {
            const double denom = mc::dot(flakes[f].normal, dir);
            if (denom == 0.0) continue;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy) {
                    const mc::Vec3 c{flakes[f].centre.x + dx * L, flakes[f].centre.y + dy * L,
                                     flakes[f].centre.z};
                    const double t = mc::dot(flakes[f].normal, sub(c, origin)) / denom;
                    if (!(t > t_near) || !(t < best_t)) continue;
                    const mc::Vec3 p{origin.x + t * dir.x, origin.y + t * dir.y, origin.z + t * dir.z};
                    if (!tile.onFlake(f, sub(p, c))) continue;
                    best_t = t;
                    best = static_cast<std::int64_t>(f);
                }
        }
        const mc::FlakeHit hit = tile.intersect(origin, dir, t_near, t_far);
        ASSERT_EQ(hit.kind >= 0 ? hit.flake : -1, best) << "ray " << i;
        if (best < 0) continue;
        ++hits;
        EXPECT_NEAR(hit.t, best_t, 1e-9) << "ray " << i;
    }
    std::printf("  nearest hits (%d sides): %d of %d rays hit a flake, every one the brute-force nearest\n",
                sides, hits, rays);
    // ~1.5 flakes per vertical column of the 15 µm film: about half of the
    // segments (up to 40 µm, many leaving the film sooner) cross one (1325
    // of 3000 here); fewer than a third would mean the search finds nothing.
    EXPECT_GT(hits, rays / 3);
}

TEST(FlakeTileHits, AreTheNearestOfABruteForceSearch) {
    expectNearestOfABruteForceSearch(mc::kFlakePolygonSides);
    expectNearestOfABruteForceSearch(0);
}

// The two shapes (McSettings::flake_polygon_sides): both have the disk's area
// (the tile's flake count and the fast model's area density assume it); the
// disk's edge is its radius in every direction, the 16-gon's reaches its
// circumradius only towards a vertex (the apothem is cos(pi/16) = 0.981 of
// it); points drawn on a disk are uniform over its area (E[rho^2] = r^2 / 2;
// 20,000 draws: standard error 0.002 r^2, tolerance 4 of them).
TEST(FlakeTileShapes, DisksAndPolygonsHaveTheDisksAreaAndTheirOwnEdge) {
    const std::vector<mc::FlakeGeometry> kinds{{0.06 / 0.6, 18.0, 10.0, nullptr}};
    const mc::FlakeTile disks(kinds, 40.0, 55.0, 5, 300, 100000, false, nullptr, 0);
    const mc::FlakeTile polygons(kinds, 40.0, 55.0, 5, 300, 100000);
    const double area = 0.25 * kPi * 18.0 * 18.0;
    mc::PathRng rng(12, 13, 14, 15);
    for (std::size_t i = 0; i < 20; ++i) {
        EXPECT_NEAR(disks.flakeAreaUm2(i), area, 1e-9 * area);
        EXPECT_NEAR(polygons.flakeAreaUm2(i), area, 1e-9 * area);
        const mc::PlacedFlake& d = disks.flakes()[i];
        EXPECT_DOUBLE_EQ(d.radius_um, 9.0);
        // In-plane unit vectors of the disk's plane.
        const mc::Vec3 a = std::abs(d.normal.z) < 0.9 ? mc::Vec3{0.0, 0.0, 1.0} : mc::Vec3{1.0, 0.0, 0.0};
        mc::Vec3 e1 = cross(d.normal, a);
        const double n1 = std::sqrt(mc::dot(e1, e1));
        e1 = {e1.x / n1, e1.y / n1, e1.z / n1};
        const mc::Vec3 e2 = cross(d.normal, e1);
        for (int k = 0; k < 50; ++k) {
            const double phi = 2.0 * kPi * rng.uniform();
            const mc::Vec3 e{std::cos(phi) * e1.x + std::sin(phi) * e2.x,
                             std::cos(phi) * e1.y + std::sin(phi) * e2.y,
                             std::cos(phi) * e1.z + std::sin(phi) * e2.z};
            EXPECT_TRUE(disks.onFlake(i, {0.999 * 9.0 * e.x, 0.999 * 9.0 * e.y, 0.999 * 9.0 * e.z}));
            EXPECT_FALSE(disks.onFlake(i, {1.001 * 9.0 * e.x, 1.001 * 9.0 * e.y, 1.001 * 9.0 * e.z}));
        }
        // The polygon: towards a vertex (a point drawn at the fan's outer corner) inside up to
        // the circumradius, towards an edge's middle outside beyond the apothem.
        const mc::PlacedFlake& p = polygons.flakes()[i];
        const mc::Vec3 vertex = sub(polygons.pointOnFlake(i, 0.0, 1.0, 0.0), p.centre);
        const mc::Vec3 next = sub(polygons.pointOnFlake(i, 0.0, 1.0, 1.0), p.centre);
        EXPECT_NEAR(std::sqrt(mc::dot(vertex, vertex)), p.radius_um, 1e-9);
        EXPECT_TRUE(polygons.onFlake(i, {0.999 * vertex.x, 0.999 * vertex.y, 0.999 * vertex.z}));
        const mc::Vec3 mid{0.5 * (vertex.x + next.x), 0.5 * (vertex.y + next.y), 0.5 * (vertex.z + next.z)};
        const double to_mid = std::sqrt(mc::dot(mid, mid));
        EXPECT_NEAR(to_mid, p.radius_um * std::cos(kPi / mc::kFlakePolygonSides), 1e-9);
        const double beyond = 1.01 * p.radius_um * std::cos(kPi / mc::kFlakePolygonSides) / to_mid;
        EXPECT_FALSE(polygons.onFlake(i, {beyond * mid.x, beyond * mid.y, beyond * mid.z}));
    }
    double mean_rho2 = 0.0;
    constexpr int kDraws = 20000;
    for (int k = 0; k < kDraws; ++k) {
        const mc::Vec3 q =
            sub(disks.pointOnFlake(3, rng.uniform(), rng.uniform(), rng.uniform()), disks.flakes()[3].centre);
        ASSERT_LT(std::abs(mc::dot(q, disks.flakes()[3].normal)), 1e-9);
        ASSERT_LE(mc::dot(q, q), 81.0 * (1.0 + 1e-12));
        mean_rho2 += mc::dot(q, q) / 81.0 / kDraws;
    }
    EXPECT_NEAR(mean_rho2, 0.5, 4.0 * 0.002);
    EXPECT_THROW(mc::FlakeTile(kinds, 40.0, 55.0, 5, 300, 100000, false, nullptr, 2), InputError);
}

// Flake sizes (FlakeGeometry::diameter_sd_um): diameters drawn from a
// lognormal of the given mean and sd (cut where 3e-7 of it lies beyond:
// exp(mu + 5 sigma) in log space, 86 µm here), and the flake
// count set by the mean area, so that the projected area per volume (what
// the fast model and the two-stream values use) is the recipe's. Disks
// (diameter = 2 r). Tolerances: ~20,000 flakes of CV 1/3: the mean's standard
// error is 0.04 µm, the sd's ~0.04 µm (lognormal kurtosis included), the total
// area's 0.5 %; 4 of them each (the area also carries the count's rounding).
TEST(FlakeTileShapes, DiametersFollowTheSizeDistributionAndKeepTheAreaDensity) {
    const double density = 0.06 / 0.6;  // area per volume (1/µm)
    const std::vector<mc::FlakeGeometry> kinds{{density, 18.0, 10.0, nullptr, 6.0}};
    const mc::FlakeTile tile(kinds, 40.0, 55.0, 21, 20000, 1000000, false, nullptr, 0);
    const auto& flakes = tile.flakes();
    ASSERT_GT(flakes.size(), 15000U);
    double sum = 0.0;
    double sum2 = 0.0;
    double area = 0.0;
    double largest = 0.0;
    for (std::size_t i = 0; i < flakes.size(); ++i) {
        const double d = 2.0 * flakes[i].radius_um;
        sum += d;
        sum2 += d * d;
        area += tile.flakeAreaUm2(i);
        largest = std::max(largest, d);
    }
    const auto n = static_cast<double>(flakes.size());
    const double mean = sum / n;
    const double sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 18.0, 4.0 * 0.04);
    EXPECT_NEAR(sd, 6.0, 4.0 * 0.04);
    const double log_variance = std::log1p(1.0 / 9.0);
    EXPECT_LE(largest, std::exp(std::log(18.0) - 0.5 * log_variance + 5.0 * std::sqrt(log_variance)));
    const double L = tile.sideUm();
    EXPECT_NEAR(area / (L * L * 15.0), density, 4.0 * 0.005 * density);
    // No spread: every flake the mean size.
    const mc::FlakeTile equal({{density, 18.0, 10.0, nullptr, 0.0}}, 40.0, 55.0, 21, 2000, 1000000, false,
                              nullptr, 0);
    for (const auto& f : equal.flakes()) ASSERT_DOUBLE_EQ(2.0 * f.radius_um, 18.0);
}

// The spread of independent runs (different seeds: different tiles and paths)
// against their error bars: chi^2 = sum (x_s - mean)^2 / se_s^2 over S runs
// follows chi^2 with S - 1 degrees of freedom if the error bars are right.
double chiSquare(const std::vector<mc::Estimate>& runs) {
    double w = 0.0;
    double mean = 0.0;
    for (const auto& e : runs) {
        w += 1.0 / (e.std_error * e.std_error);
        mean += e.mean / (e.std_error * e.std_error);
    }
    mean /= w;
    double chi2 = 0.0;
    for (const auto& e : runs) chi2 += (e.mean - mean) * (e.mean - mean) / (e.std_error * e.std_error);
    return chi2;
}

TEST(TileVariance, ErrorBarsCoverTheSpreadBetweenTileSeeds) {
    // A small tile (300 flakes of 15 µm, 10 degrees spread) whose arrangement
    // moves f near the specular direction by far more than the path error.
    Recipe r;
    Layer layer;
    layer.name = "basecoat";
    layer.thickness_um = 15.0;
    layer.binder.refractive_index = Spectrum(1.0);
    MirrorFlake flake;
    flake.name = "mirror";
    flake.volume_fraction = 0.02;
    flake.thickness_um = 0.5;
    flake.diameter_um = 15.0;
    flake.orientation_spread_deg = 10.0;
    flake.reflectance = Spectrum(0.9);
    layer.components = {flake};
    r.layers = {layer};
    r.substrate = BlackSubstrate{};
    const std::vector<mc::IncidenceRequest> req{
        {directionFromAnglesDeg(45.0, 0.0), {directionFromAnglesDeg(35.0, 180.0)}}};
    constexpr int kSeeds = 8;
    // chi^2 with 7 degrees of freedom: 0.999 quantile (tables, e.g. NIST/SEMATECH e-Handbook 1.3.6.7.4).
    constexpr double kChi2_7_999 = 24.32;
    std::vector<mc::Estimate> batched;
    std::vector<mc::Estimate> one_tile;
    for (int s = 1; s <= kSeeds; ++s) {
        mc::McSettings ms;
        ms.seed = std::uint64_t(s);
        ms.max_paths = 16000;
        ms.explicit_flakes = true;
        ms.histogram_cone_deg = 10.0;
        ms.tile_flakes = 300;
        ms.batches = 16;  // 16 tiles; the error bar has 15 degrees of freedom
        batched.push_back(
            mc::runMonteCarlo(r, std::vector<double>{550.0}, req, ms).bands[0][0].brdf_per_sr[0]);
        ms.batches = 1;     // one tile; the error bar is over paths only
        ms.tile_views = 1;  // ...and seen in its own frame only (views would average part of its arrangement,
        ms.glint_azimuths = false;  // and so would the glint connection over all its azimuths)
        one_tile.push_back(
            mc::runMonteCarlo(r, std::vector<double>{550.0}, req, ms).bands[0][0].brdf_per_sr[0]);
    }
    const double chi2_batched = chiSquare(batched);
    const double chi2_one_tile = chiSquare(one_tile);
    if (std::getenv("PAINTLAB_MC_VERBOSE") != nullptr) {
        for (std::size_t s = 0; s < batched.size(); ++s)
            std::printf("  seed %zu: 16 tiles %.5g +- %.2g, one tile %.5g +- %.2g\n", s + 1, batched[s].mean,
                        batched[s].std_error, one_tile[s].mean, one_tile[s].std_error);
        std::printf("  chi2 (7 dof): 16 tiles %.2f, one tile %.2f\n", chi2_batched, chi2_one_tile);
    }
    // The error bars over tiles cover the spread between seeds at the 0.1 % level...
    EXPECT_LT(chi2_batched, kChi2_7_999);
    // ...and the path-only error bars of one tile do not (the test can fail).
    EXPECT_GT(chi2_one_tile, kChi2_7_999);
}

}  // namespace
}  // namespace paintlab
