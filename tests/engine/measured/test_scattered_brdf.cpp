// Scattered samples of a measured BRDF interpolated in half/difference
// angles (engine measured/scattered_brdf.h), against an analytic truth: a
// Lambertian base plus a normalised Blinn-Phong lobe, f known everywhere.

#include "paintlab/engine/error.h"
#include "paintlab/engine/measured/scattered_brdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using paintlab::Direction;
using paintlab::directionFromAnglesDeg;
using namespace paintlab::measured;

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// Per channel: albedo / pi plus ks (n + 2) / (8 pi) cos^n theta_h (the
// energy-normalised Blinn-Phong lobe). n = 30: half maximum at theta_h 12°,
// a semi-gloss paint's width.
constexpr double kExponent = 30.0;
constexpr double kAlbedo[3] = {0.6, 0.3, 0.1};
constexpr double kSpecular = 0.3;

double truth(const Direction& wi, const Direction& wo, std::size_t c) {
    const double theta_h = halfDifference(wi, wo).theta_h;
    return kAlbedo[c] / kPi +
           kSpecular * (kExponent + 2.0) / (8.0 * kPi) * std::pow(std::cos(theta_h), kExponent);
}

Direction randomDirection(std::mt19937_64& rng, double max_theta_deg) {
    std::uniform_real_distribution<double> theta(0.0, max_theta_deg);
    std::uniform_real_distribution<double> phi(0.0, 360.0);
    return directionFromAnglesDeg(theta(rng), phi(rng));
}

std::vector<ScatteredSample> samplesOfTruth(std::size_t count, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::vector<ScatteredSample> out;
    for (std::size_t i = 0; i < count; ++i) {
        ScatteredSample s{randomDirection(rng, 85.0), randomDirection(rng, 85.0), {}};
        for (std::size_t c = 0; c < 3; ++c) s.values.push_back(truth(s.wi, s.wo, c));
        out.push_back(std::move(s));
    }
    return out;
}

// RMS relative error of the interpolated channels over random queries
// within 70° of the normal (a sphere's lit pixels short of the rim).
double rmsRelativeError(const ScatteredBrdf& brdf, unsigned seed) {
    std::mt19937_64 rng(seed);
    double sum = 0.0;
    constexpr int kQueries = 2000;
    std::vector<double> f(3);
    for (int q = 0; q < kQueries; ++q) {
        const Direction wi = randomDirection(rng, 70.0);
        const Direction wo = randomDirection(rng, 70.0);
        brdf.eval(wi, wo, f);
        for (std::size_t c = 0; c < 3; ++c) {
            const double t = truth(wi, wo, c);
            sum += (f[c] - t) * (f[c] - t) / (t * t);
        }
    }
    return std::sqrt(sum / (3.0 * kQueries));
}

TEST(HalfDifference, ClosedForms) {
    // The mirror pair: the half vector is the normal, theta_d the incidence.
    const auto mirror =
        halfDifference(directionFromAnglesDeg(40.0, 180.0), directionFromAnglesDeg(40.0, 0.0));
    EXPECT_NEAR(mirror.theta_h, 0.0, 1e-12);
    EXPECT_NEAR(mirror.theta_d, 40.0 * kDeg, 1e-12);
    // Retroreflection: the half vector is the direction itself, theta_d 0.
    const Direction d = directionFromAnglesDeg(35.0, 70.0);
    const auto retro = halfDifference(d, d);
    EXPECT_NEAR(retro.theta_h, 35.0 * kDeg, 1e-12);
    EXPECT_NEAR(retro.theta_d, 0.0, 1e-6);
}

TEST(HalfDifference, ReciprocalAndIsotropic) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 200; ++i) {
        const Direction wi = randomDirection(rng, 85.0);
        const Direction wo = randomDirection(rng, 85.0);
        const auto a = halfDifference(wi, wo);
        const auto swapped = halfDifference(wo, wi);
        // Both rotated by 123° about the normal.
        const double c = std::cos(123.0 * kDeg);
        const double s = std::sin(123.0 * kDeg);
        const auto rotate = [&](const Direction& v) {
            return Direction{c * v.x - s * v.y, s * v.x + c * v.y, v.z};
        };
        const auto rotated = halfDifference(rotate(wi), rotate(wo));
        // Mirrored in the x-z plane.
        const auto mirrored = halfDifference({wi.x, -wi.y, wi.z}, {wo.x, -wo.y, wo.z});
        for (const auto& b : {swapped, rotated, mirrored}) {
            EXPECT_NEAR(a.theta_h, b.theta_h, 1e-9);
            EXPECT_NEAR(a.theta_d, b.theta_d, 1e-9);
            EXPECT_NEAR(a.phi_d, b.phi_d, 1e-6);
        }
        EXPECT_GE(a.phi_d, 0.0);
        EXPECT_LE(a.phi_d, 0.5 * kPi + 1e-12);
    }
}

TEST(ScatteredBrdf, ReproducesItsSamples) {
    const auto samples = samplesOfTruth(300, 1);
    const ScatteredBrdf brdf(samples, 3, "test");
    std::vector<double> f(3);
    for (const auto& s : samples) {
        brdf.eval(s.wi, s.wo, f);
        for (std::size_t c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(f[c], s.values[c]);
        EXPECT_NEAR(brdf.nearestDistance(s.wi, s.wo), 0.0, 1e-9);
    }
}

TEST(ScatteredBrdf, CloseToTheTruthWhereDenseAndConverges) {
    // 4,000 samples put one about every 0.08 rad (4.7°) in the 3-D
    // half/difference space; within that spacing the lobe (half width 12°)
    // changes f by up to ~25 %, the weighting averages it down. Measured
    // (release build, these seeds): RMS relative error 3.6 % with 4,000
    // samples (k = 6), 2.3 % with 16,000; the nearest sample alone (k = 1)
    // gives 5.9 %. The bounds sit between: room for another compiler's
    // rounding, none for losing the weighting.
    const ScatteredBrdf coarse(samplesOfTruth(4000, 11), 3, "test");
    const ScatteredBrdf fine(samplesOfTruth(16000, 12), 3, "test");
    const double e_coarse = rmsRelativeError(coarse, 99);
    const double e_fine = rmsRelativeError(fine, 99);
    EXPECT_LT(e_coarse, 0.045);
    EXPECT_LT(e_fine, 0.03);
    // Convergence under refinement: four times the samples, smaller error.
    EXPECT_LT(e_fine, 0.8 * e_coarse);
}

TEST(ScatteredBrdf, DensityOfASparseAndADenseSet) {
    std::mt19937_64 rng(5);
    std::vector<DirectionPair> queries;
    queries.reserve(500);
    for (int i = 0; i < 500; ++i) queries.push_back({randomDirection(rng, 70.0), randomDirection(rng, 70.0)});
    const ScatteredBrdf sparse(samplesOfTruth(40, 2), 3, "test");
    const Density s = density(sparse, queries);
    EXPECT_FALSE(s.dense);
    EXPECT_NE(s.reason.find("40 samples"), std::string::npos) << s.reason;
    // Enough samples but all at one incidence: the coverage fails.
    std::vector<ScatteredSample> one_incidence;
    one_incidence.reserve(400);
    for (int i = 0; i < 400; ++i) {
        ScatteredSample smp{directionFromAnglesDeg(45.0, 180.0), directionFromAnglesDeg(0.2 * i, 0.0), {1.0}};
        one_incidence.push_back(smp);
    }
    const Density o = density(ScatteredBrdf(one_incidence, 1, "test"), queries);
    EXPECT_FALSE(o.dense);
    EXPECT_LT(o.covered, 0.9);
    EXPECT_NE(o.reason.find('%'), std::string::npos) << o.reason;
    const Density d = density(ScatteredBrdf(samplesOfTruth(4000, 3), 3, "test"), queries);
    EXPECT_TRUE(d.dense) << d.reason;
    EXPECT_GT(d.covered, 0.9);
}

TEST(ScatteredBrdf, BadSamplesNameTheField) {
    auto samples = samplesOfTruth(5, 4);
    samples[3].values[1] = -0.5;
    try {
        const ScatteredBrdf brdf(samples, 3, "panel.csv");
        FAIL() << "a negative value was accepted";
    } catch (const paintlab::InputError& e) {
        EXPECT_EQ(e.field(), "samples[3].values[1]");
    }
    samples[3].values[1] = 0.1;
    samples[2].wo = directionFromAnglesDeg(95.0, 0.0);
    EXPECT_THROW(ScatteredBrdf(samples, 3, "panel.csv"), paintlab::InputError);
    EXPECT_THROW(ScatteredBrdf(std::vector<ScatteredSample>{}, 3, "panel.csv"), paintlab::InputError);
}

}  // namespace
