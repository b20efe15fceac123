// The beam's single flake reflections averaged over every azimuth of a tile
// (mc_connection.h, azimuthGlintSets / azimuthGlintSample) against the
// per-view glint lists they replace (glintSets / scoreGlints).
//
// Unbiasedness rests on two facts checked here: every flake that glints into a
// cone at some view is listed with that view's azimuth inside its interval
// (exact, no tolerance), and the sample's mean is the average over views of
// the per-view estimate (z-test, z = 4: two-sided significance ~6e-5 per
// comparison, four comparisons).

#include "mc_connection.h"
#include "mc_engine.h"
#include "mc_glints.h"
#include "mc_random.h"
#include "mc_reflected_beams.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/optics/fresnel.h"

#include "test_recipes.h"
#include "z_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

namespace paintlab {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The small pearlescent (test_recipes.h) with an absorbing, weakly scattering
// black over a 0.3 grey base; ~1500 flakes per tile.
Recipe pearlescent() {
    Pigment black = test::pigment(0.01, 10.0, 0.5, 0.0);
    black.name = "black";
    return test::smallPearlescent(black, 0.3);
}

struct Fixture {
    Recipe recipe = pearlescent();
    mc::McSettings settings;
    std::unique_ptr<mc::McEngine> engine;
    mc::McEngine::Band band;
    mc::Vec3 v_in;  // the beam refracted into the top slice
    std::vector<mc::HistogramBin> bins;

    explicit Fixture(double cone_deg) {
        settings.explicit_flakes = true;
        settings.histogram_cone_deg = cone_deg;
        settings.batches = 1;
        settings.tile_flakes = 1500;
        engine = std::make_unique<mc::McEngine>(recipe, settings);
        band = engine->band(450.0);
        const Direction wi = directionFromAnglesDeg(45.0, 0.0);
        const double ratio = band.stack.ambient_n / band.stack.slices.front().n;
        v_in = {-wi.x * ratio, -wi.y * ratio, 0.0};
        v_in.z = -std::sqrt(1.0 - v_in.x * v_in.x - v_in.y * v_in.y);
        const double alpha = cone_deg * std::numbers::pi / 180.0;
        // Near the specular direction, across it, at the flop, and a cone that crosses the horizon.
        for (const Direction& wo : {directionFromAnglesDeg(45.0, 180.0), directionFromAnglesDeg(25.0, 180.0),
                                    directionFromAnglesDeg(20.0, 0.0), directionFromAnglesDeg(60.0, 150.0),
                                    directionFromAnglesDeg(88.0, 180.0)})
            bins.push_back({{wo.x, wo.y, wo.z},
                            std::cos(alpha),
                            std::numbers::pi * std::sin(alpha) * std::sin(alpha) * std::max(wo.z, 1e-9),
                            kTwoPi * (1.0 - std::cos(alpha))});
    }
    std::span<const mc::LayerFlakes> tiles() const { return band.explicit_flakes[0]; }
};

mc::Vec3 turned(const mc::Vec3& a, double psi) {
    return {std::cos(psi) * a.x - std::sin(psi) * a.y, std::sin(psi) * a.x + std::cos(psi) * a.y, a.z};
}

// One glint sample's uniforms, each independent (GlintUniforms; not moved).
mc::GlintUniforms randomGlintUniforms(mc::PathRng& rng) {
    mc::GlintUniforms u;
    u.pick = rng.uniform();
    u.psi = rng.uniform();
    u.choose = rng.uniform();
    u.u1 = rng.uniform();
    u.u2 = rng.uniform();
    u.u3 = rng.uniform();
    return u;
}

TEST(GlintAzimuths, EighthOfAnAngleFromItsCosineMatchesTheTrigonometry) {
    // Closed form: cos and sin of delta / 8. Three half-angle steps of square
    // roots lose at most a few ulps of cos delta; near delta = 0 the
    // cancellation in 1 - cos delta costs ~1e-16 / delta^2 relative in sin,
    // hence the tolerance of 1e-12 on sin at delta >= 1e-2 and 1e-14 on cos.
    for (int i = 0; i <= 1000; ++i) {
        const double delta = std::numbers::pi * (1e-2 + (1.0 - 1e-2) * i / 1000.0);
        const mc::CosSin e = mc::eighthOfAngle(std::cos(delta));
        EXPECT_NEAR(e.c, std::cos(delta / 8.0), 1e-14) << delta;
        EXPECT_NEAR(e.s, std::sin(delta / 8.0), 1e-12) << delta;
    }
    EXPECT_NEAR(mc::eighthOfAngle(-1.0).c, std::cos(std::numbers::pi / 8.0), 1e-15);
    EXPECT_EQ(mc::eighthOfAngle(1.0).s, 0.0);
    EXPECT_EQ(mc::eighthOfAngle(1.0).c, 1.0);
}

TEST(GlintAzimuths, EveryGlintingFlakeIsListedAtItsAzimuth) {
    const Fixture fx(5.0);
    const auto sets = mc::azimuthGlintSets(fx.band.stack, fx.tiles(), fx.v_in, fx.bins);
    mc::PathRng rng(1, 2, 3, 4);
    std::vector<int> glints(fx.bins.size(), 0);
    std::vector<int> missing(fx.bins.size(), 0);
    for (int view = 0; view < 400; ++view) {
        const double psi = kTwoPi * rng.uniform();
        std::vector<mc::HistogramBin> bins = fx.bins;
        for (auto& bin : bins) bin.wo = turned(bin.wo, psi);
        // The per-view lists: the flakes that glint into each cone at this view.
        const auto lists = mc::glintSets(fx.band.stack, fx.tiles(), turned(fx.v_in, psi), bins);
        for (std::size_t k = 0; k < bins.size(); ++k)
            for (const auto& g : lists[k].flakes) {
                ++glints[k];
                bool listed = false;
                for (const auto& a : sets[k].flakes) {
                    if (a.layer != g.layer || a.flake != g.flake) continue;
                    const double offset = std::fmod(std::fmod(psi - a.psi_lo, kTwoPi) + kTwoPi, kTwoPi);
                    listed = listed || offset <= a.psi_width + 1e-12;
                }
                if (!listed) ++missing[k];
            }
    }
    for (std::size_t k = 0; k < fx.bins.size(); ++k) {
        EXPECT_EQ(missing[k], 0) << "cone " << k << ": " << missing[k] << " of " << glints[k]
                                 << " glints unlisted";
        if (k < 4) {
            EXPECT_GT(glints[k], 20) << "cone " << k << " (the test needs glints)";
        }
    }
}

TEST(GlintAzimuths, SampleMeanIsTheAverageOverViews) {
    const Fixture fx(5.0);
    const auto sets = mc::azimuthGlintSets(fx.band.stack, fx.tiles(), fx.v_in, fx.bins);
    mc::PathRng rng(5, 6, 7, 8);
    // Reference: views on a randomly shifted grid of azimuths (stratified, unbiased for the
    // average over all azimuths), 40 per-view glint samples each; its error from the
    // spread of the views' means (an upper bound for the stratified grid).
    constexpr int kViews = 720;
    constexpr int kPerView = 40;
    const double shift = rng.uniform();
    std::vector<std::vector<double>> per_view(fx.bins.size(), std::vector<double>(kViews, 0.0));
    for (int m = 0; m < kViews; ++m) {
        const double psi = kTwoPi * (m + shift) / kViews;
        std::vector<mc::HistogramBin> bins = fx.bins;
        for (auto& bin : bins) bin.wo = turned(bin.wo, psi);
        const auto lists = mc::glintSets(fx.band.stack, fx.tiles(), turned(fx.v_in, psi), bins);
        std::vector<double> f(bins.size(), 0.0);
        for (int i = 0; i < kPerView; ++i)
            mc::scoreGlints(fx.band.stack, fx.tiles(), lists, bins, 1.0 / kPerView, rng, f);
        for (std::size_t k = 0; k < bins.size(); ++k) per_view[k][static_cast<std::size_t>(m)] = f[k];
    }
    for (std::size_t k = 0; k < 4; ++k) {
        double mean = 0.0;
        for (double x : per_view[k]) mean += x / kViews;
        double var = 0.0;
        for (double x : per_view[k]) var += (x - mean) * (x - mean) / (kViews - 1);
        constexpr int kSamples = 40000;
        double s1 = 0.0;
        double s2 = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            mc::GlintUniforms u = randomGlintUniforms(rng);
            const double x = mc::azimuthGlintSample(fx.band.stack, fx.tiles(), sets[k], fx.bins[k], u);
            s1 += x;
            s2 += x * x;
        }
        const double sample_mean = s1 / kSamples;
        const double sample_se =
            std::sqrt(std::max(0.0, s2 / kSamples - sample_mean * sample_mean) / kSamples);
        ASSERT_GT(mean, 0.0) << "cone " << k;
        test::expectClose(sample_mean, sample_se, mean, std::sqrt(var / kViews),
                          "glint f, cone " + std::to_string(k));
    }
}

// A flake moved to its own place (McSettings::move_glint_flakes with a shift
// of zero) glints exactly as it does in place: the trace that leaves it out of
// the tile finds the same shadows, as a flat flake never shades itself.
TEST(GlintAzimuths, AFlakeMovedToItsOwnPlaceGlintsAsInPlace) {
    const Fixture fx(5.0);
    const auto sets = mc::azimuthGlintSets(fx.band.stack, fx.tiles(), fx.v_in, fx.bins);
    mc::PathRng rng(9, 10, 11, 12);
    int glinting = 0;
    for (std::size_t k = 0; k < 4; ++k)
        for (int i = 0; i < 2000; ++i) {
            mc::GlintUniforms u = randomGlintUniforms(rng);
            const double in_place = mc::azimuthGlintSample(fx.band.stack, fx.tiles(), sets[k], fx.bins[k], u);
            u.moved = true;
            const double moved = mc::azimuthGlintSample(fx.band.stack, fx.tiles(), sets[k], fx.bins[k], u);
            ASSERT_EQ(moved, in_place) << "cone " << k << ", sample " << i;
            if (in_place > 0.0) ++glinting;
        }
    EXPECT_GT(glinting, 1000) << "the test needs glints";
}

// Moving the glinting flake to a uniform place keeps the glints' mean over
// tiles: the tiles place flakes independently and uniformly, so a flake's
// place is independent of its normal, its depth and the other flakes. Per
// tile the two estimates differ (each tile's own shadows against shadows
// averaged over its places); over 48 tiles their mean difference D is zero
// within its standard error from the tiles' spread of D (z = 4, four cones).
TEST(GlintAzimuths, MovedFlakesKeepTheMeanOverTiles) {
    constexpr int kTiles = 48;
    constexpr int kSamples = 3000;  // per tile, cone and estimate
    Recipe recipe = pearlescent();
    mc::McSettings settings;
    settings.explicit_flakes = true;
    settings.histogram_cone_deg = 5.0;
    settings.batches = kTiles;
    settings.tile_flakes = 1500;
    const Fixture fx(5.0);  // its cones and beam
    const mc::McEngine engine(recipe, settings);
    const mc::McEngine::Band band = engine.band(450.0);
    mc::PathRng rng(13, 14, 15, 16);
    for (std::size_t k = 0; k < 4; ++k) {
        std::vector<double> d(kTiles, 0.0);
        double moved_mean = 0.0;
        for (int t = 0; t < kTiles; ++t) {
            const auto tiles =
                std::span<const mc::LayerFlakes>(band.explicit_flakes[static_cast<std::size_t>(t)]);
            const auto sets = mc::azimuthGlintSets(band.stack, tiles, fx.v_in, fx.bins);
            double in_place = 0.0;
            double moved = 0.0;
            for (int i = 0; i < kSamples; ++i) {
                mc::GlintUniforms u = randomGlintUniforms(rng);
                u.pick = (i + rng.uniform()) / kSamples;  // stratified, as chunkGlints picks
                in_place += mc::azimuthGlintSample(band.stack, tiles, sets[k], fx.bins[k], u) / kSamples;
                u = randomGlintUniforms(rng);
                u.pick = (i + rng.uniform()) / kSamples;
                u.moved = true;
                u.move_x = rng.uniform();
                u.move_y = rng.uniform();
                moved += mc::azimuthGlintSample(band.stack, tiles, sets[k], fx.bins[k], u) / kSamples;
            }
            d[static_cast<std::size_t>(t)] = moved - in_place;
            moved_mean += moved / kTiles;
        }
        double mean = 0.0;
        for (double x : d) mean += x / kTiles;
        double var = 0.0;
        for (double x : d) var += (x - mean) * (x - mean) / (kTiles - 1);
        ASSERT_GT(moved_mean, 0.0) << "cone " << k;
        test::expectClose(mean, std::sqrt(var / kTiles), 0.0, 0.0,
                          "moved - in place, cone " + std::to_string(k) + " (f " +
                              std::to_string(moved_mean) + ")");
    }
}

// The beam traced straight down from a uniform entry point over the tile
// (the top's and the coat's 1 - F, the pigments' extinction, T of each
// interference flake passed), and at every flake it meets, its reflection
// followed through the flake layer: returns the sum over those reflected rays
// of their weight times the length they travel in the layer, each metre of
// it weighted by the transmittance so far (the track-length estimate of the
// integral of the reflected light's flux density over the layer, per unit
// of the beam's power per unit area times the tile's area).
double reflectedTrackLength(const mc::PaintStack& stack, std::span<const mc::LayerFlakes> tiles,
                            const mc::Vec3& v_top, double x, double y) {
    const double n_top = stack.slices.front().n;
    // The entry: 1 - F at the ambient's cosine of the beam (Snell back out of the top slice).
    const double sin2_ambient =
        (1.0 - v_top.z * v_top.z) * (n_top / stack.ambient_n) * (n_top / stack.ambient_n);
    double weight =
        1.0 - fresnelDielectric(std::sqrt(std::max(0.0, 1.0 - sin2_ambient)), n_top / stack.ambient_n);
    mc::Vec3 v = v_top;
    double track = 0.0;
    for (std::size_t j = 0; j < stack.slices.size() && weight > 0.0; ++j) {
        const mc::Slice& s = stack.slices[j];
        if (j > 0) {
            const double n_from = stack.slices[j - 1].n;
            weight *= 1.0 - fresnelDielectric(std::abs(v.z), s.n / n_from);
            mc::Vec3 refracted;
            if (!mc::refractPlanar(v, n_from, s.n, refracted)) return track;
            v = refracted;
        }
        const double sigma = s.sigma_a_per_um + s.sigma_s_per_um;
        const auto layer = static_cast<std::size_t>(s.layer);
        if (layer >= tiles.size() || tiles[layer].tile == nullptr) {
            weight *= std::exp(-sigma * s.thicknessUm() / std::abs(v.z));
            continue;
        }
        const mc::LayerFlakes& lf = tiles[layer];
        const double L = lf.tile->sideUm();
        double depth = s.top_um;
        const auto wrap = [L](double& a) { a -= L * std::floor(a / L); };
        // A straight flight through the tile from (x, y, depth) along u until the
        // slice's boundary; at each flake hit, on_hit(weight there, point, normal, kind)
        // returns the factor to go on with (0: stop).
        const auto fly = [&](double fx, double fy, double fdepth, const mc::Vec3& u, double w,
                             const auto& on_hit, double* integral) {
            double t_near = mc::kTileEpsilonUm;
            for (int step = 0; step < 100000 && w > 0.0; ++step) {
                if (fx < 0.0 || fx > L) wrap(fx);
                if (fy < 0.0 || fy > L) wrap(fy);
                const double to_boundary =
                    (u.z < 0.0 ? s.bottom_um - fdepth : fdepth - s.top_um) / std::abs(u.z);
                const double inf = std::numeric_limits<double>::infinity();
                const double tx = u.x > 0.0 ? (L - fx) / u.x : (u.x < 0.0 ? -fx / u.x : inf);
                const double ty = u.y > 0.0 ? (L - fy) / u.y : (u.y < 0.0 ? -fy / u.y : inf);
                const double t_far = std::min({to_boundary, tx, ty});
                const mc::FlakeHit hit = lf.tile->intersect({fx, fy, -fdepth}, u, t_near, t_far);
                const double t = hit.kind >= 0 ? hit.t : t_far;
                if (integral != nullptr) *integral += w * (1.0 - std::exp(-sigma * t)) / sigma;
                w *= std::exp(-sigma * t);
                fx += u.x * t;
                fy += u.y * t;
                fdepth = std::clamp(fdepth - u.z * t, s.top_um, s.bottom_um);
                t_near = mc::kTileEpsilonUm;
                if (hit.kind >= 0) {
                    w *= on_hit(w, mc::Vec3{fx, fy, -fdepth}, hit.normal, hit.kind);
                    continue;
                }
                if (t >= to_boundary) break;
                // Across a side: in again from the opposite one.
                if (tx <= ty)
                    fx = u.x > 0.0 ? 0.0 : L;
                else
                    fy = u.y > 0.0 ? 0.0 : L;
                t_near = 0.0;
            }
            return w;
        };
        const auto reflect = [&](double w, const mc::Vec3& p, const mc::Vec3& n, int kind) {
            const mc::FlakeKind& f = lf.kinds[static_cast<std::size_t>(kind)];
            const double vn = mc::dot(v, n);
            const mc::Vec3 r{v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
            double integral = 0.0;
            const auto pass = [&](double /*w*/, const mc::Vec3& /*p*/, const mc::Vec3& m, int k) {
                return lf.kinds[static_cast<std::size_t>(k)].T(std::abs(mc::dot(r, m)));
            };
            fly(p.x, p.y, -p.z, r, w * f.R(std::abs(vn)), pass, &integral);
            track += integral;
            return f.T(std::abs(vn));
        };
        weight = fly(x, y, depth, v, weight, reflect, nullptr);
        depth = s.bottom_um;
    }
    return track;
}

TEST(ReflectedBeams, PointSumMatchesATrackLengthCountOfTheReflectedLight) {
    // reflectedBeams(z) sums, over the flakes whose mirror column of the beam
    // holds the point z, R times the beam's transmittance down to the flake
    // and the column's from the flake to z (times the pigment kernel, constant
    // for this isotropic black); divided by the kernel and |beam_z| it is the
    // reflected light's flux density at z. Its mean over points uniform in the
    // flake layer equals the reflected rays' track length per volume, counted
    // by tracing the beam forward from uniform entry points (a different
    // algorithm: no columns, no periodic images, the flakes found by Embree
    // only). Both sides are Monte Carlo means with their standard errors,
    // compared at kZ = 4. A connection dropped as blocked (the float-distance
    // test fixed on 2026-12-03 lost ~8 % of them here) or a periodic image
    // missed would show.
    Fixture fx(5.0);
    const mc::PaintStack& stack = fx.band.stack;
    const auto tiles = fx.tiles();
    const mc::Slice& base = stack.slices.back();
    ASSERT_NE(tiles[static_cast<std::size_t>(base.layer)].tile, nullptr);
    const double L = tiles[static_cast<std::size_t>(base.layer)].tile->sideUm();
    mc::Vec3 beam;  // in the flake layer
    ASSERT_TRUE(mc::refractPlanar(fx.v_in, stack.slices.front().n, base.n, beam));
    const mc::Vec3 any{0.0, 0.0, 1.0};
    const double kernel = base.kernel(any, any);  // isotropic: the same for every pair
    ASSERT_GT(kernel, 0.0);
    mc::PathRng rng(11, 12, 13, 14);
    constexpr int kRays = 200000;
    double t1 = 0.0;
    double t2 = 0.0;
    for (int i = 0; i < kRays; ++i) {
        const double x = reflectedTrackLength(stack, tiles, fx.v_in, rng.uniform() * L, rng.uniform() * L) /
                         base.thicknessUm();
        t1 += x;
        t2 += x * x;
    }
    constexpr int kPoints = 16000;  // ~1.5 % error: an 8 % loss is z > 5
    double p1 = 0.0;
    double p2 = 0.0;
    for (int i = 0; i < kPoints; ++i) {
        const double depth = base.top_um + rng.uniform() * base.thicknessUm();
        const double x = mc::reflectedBeams(stack, tiles, stack.slices.size() - 1, depth, rng.uniform() * L,
                                            rng.uniform() * L, any, fx.v_in, {true, false}) /
                         (kernel * std::abs(beam.z));
        p1 += x;
        p2 += x * x;
    }
    const double track_mean = t1 / kRays;
    const double point_mean = p1 / kPoints;
    const double track_se = std::sqrt(std::max(0.0, t2 / kRays - track_mean * track_mean) / kRays);
    const double point_se = std::sqrt(std::max(0.0, p2 / kPoints - point_mean * point_mean) / kPoints);
    std::printf("reflected flux density: points %.5g +- %.2g, tracks %.5g +- %.2g\n", point_mean, point_se,
                track_mean, track_se);
    ASSERT_GT(track_mean, 20.0 * track_se);
    test::expectClose(point_mean, point_se, track_mean, track_se, "reflected flux density");
}

TEST(ReflectedBeams, CandidateGridLeavesNoColumnOut) {
    // reflectedBeams tests only the flakes a column could reach the point from
    // (TiltIndex's lateral grid and tilt cut); without the index it tests every
    // flake. Both sums must agree to rounding (1e-12 relative: the same terms,
    // added in another order) at random points, for beams from near the
    // normal to grazing and with the top images, where the reach is longest.
    Fixture fx(5.0);
    const mc::PaintStack& stack = fx.band.stack;
    const auto tiles = fx.tiles();
    std::vector<mc::LayerFlakes> exhaustive(tiles.begin(), tiles.end());
    for (auto& lf : exhaustive) lf.tilts = nullptr;
    const mc::Slice& base = stack.slices.back();
    const mc::FlakeTile& tile = *tiles[static_cast<std::size_t>(base.layer)].tile;
    mc::PathRng rng(21, 22, 23, 24);
    int nonzero = 0;
    for (const double theta_deg : {5.0, 30.0, 55.0, 80.0}) {
        const Direction w = directionFromAnglesDeg(theta_deg, 37.0);
        const double ratio = stack.ambient_n / stack.slices.front().n;
        const mc::Vec3 beam_top{-w.x * ratio, -w.y * ratio,
                                -std::sqrt(1.0 - (w.x * w.x + w.y * w.y) * ratio * ratio)};
        for (int i = 0; i < 1000; ++i) {
            const double depth = base.top_um + rng.uniform() * base.thicknessUm();
            const double x = rng.uniform() * tile.sideUm();
            const double y = rng.uniform() * tile.sideUm();
            const mc::Vec3 v{0.0, 0.0, -1.0};
            for (const mc::BeamImages images : {mc::BeamImages{true, false}, mc::BeamImages{false, true}}) {
                const double culled = mc::reflectedBeams(stack, tiles, stack.slices.size() - 1, depth, x, y,
                                                         v, beam_top, images);
                const double all = mc::reflectedBeams(stack, exhaustive, stack.slices.size() - 1, depth, x, y,
                                                      v, beam_top, images);
                EXPECT_NEAR(culled, all, 1e-12 * all) << "beam at " << theta_deg << " deg, point " << i;
                nonzero += all > 0.0 ? 1 : 0;
            }
        }
    }
    // Columns were found, so a missed one would show (with the reach cut to a
    // quarter of the bound, 2 of these comparisons failed: most columns are short).
    EXPECT_GT(nonzero, 800);
}

}  // namespace
}  // namespace paintlab
