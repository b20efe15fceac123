#include "paintlab/engine/optics/flake_orientation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace paintlab {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSpreadsDeg[] = {0.1, 1.0, 10.0, 30.0, 90.0};

double rad(double deg) { return deg * kPi / 180.0; }

// Composite Simpson of f on [a, b] with n (even) intervals: an independent
// quadrature, deliberately not the library's Gauss-Legendre.
template <class F> double simpson(F&& f, double a, double b, int n) {
    if (!(b > a)) return 0.0;
    const double h = (b - a) / n;
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
    return s * h / 3.0;
}

// Integral over the polar angle alpha in [a0, a1] of g(alpha) D(cos alpha) sin alpha,
// split where the density has decayed (15 sigma) so that narrow lobes are resolved.
template <class G> double overAlpha(const FlakeOrientation& d, G&& g, double a0, double a1, int n) {
    auto f = [&](double a) { return g(a) * d.pdf(std::cos(a)) * std::sin(a); };
    const double split = std::clamp(15.0 * rad(d.spreadDeg()), a0, a1);
    return simpson(f, a0, split, n) + simpson(f, split, a1, n);
}

TEST(FlakeOrientation, PdfIntegratesToOneOverTheHemisphere) {
    for (double s : kSpreadsDeg) {
        const FlakeOrientation d(s);
        const double total = 2.0 * kPi *
                             overAlpha(
                                 d, [](double) { return 1.0; }, 0.0, kPi / 2.0, 4000);
        // 1e-8: Simpson with 4000 steps on a smooth lobe resolved by >= 250 steps per width (h^4 error).
        EXPECT_NEAR(total, 1.0, 1e-8) << "spread " << s;
        const double mean_cos = 2.0 * kPi *
                                overAlpha(
                                    d, [](double a) { return std::cos(a); }, 0.0, kPi / 2.0, 4000);
        EXPECT_NEAR(d.meanCos(), mean_cos, 1e-8) << "spread " << s;  // same quadrature accuracy
    }
}

// Upper tail of the chi-square distribution by the Wilson-Hilferty cube-root
// normal approximation (accurate to ~1e-3 in p for dof >= 10, enough to
// compare against a 2e-3 significance level).
double chiSquareTail(double x, int dof) {
    const double k = dof;
    const double z = (std::cbrt(x / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
    return 0.5 * std::erfc(z / std::numbers::sqrt2);
}

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// pbrt-style chi-square test of sample() against pdf() (bsdfs_test.cpp): a
// histogram over (alpha, phi) bins, expected counts from integrating pdf,
// bins with fewer than 5 expected pooled.
TEST(FlakeOrientation, SamplingMatchesPdfChiSquare) {
    constexpr int kSamples = 200000;
    constexpr int kAlphaBins = 12, kPhiBins = 6;
    // Sidak: five independent tests at an overall 1 % significance level.
    const double level = 1.0 - std::pow(0.99, 1.0 / 5.0);
    for (double s : kSpreadsDeg) {
        const FlakeOrientation d(s);
        const double a_cap = std::min(kPi / 2.0, 4.0 * rad(s));
        std::vector<double> edges;
        for (int i = 0; i <= kAlphaBins; ++i) edges.push_back(a_cap * i / kAlphaBins);
        if (a_cap < kPi / 2.0) edges.push_back(kPi / 2.0);  // tail bin
        const std::size_t na = edges.size() - 1;
        std::vector<double> observed(na * kPhiBins, 0.0), expected(na * kPhiBins, 0.0);
        std::mt19937_64 rng(0x5eed + static_cast<std::uint64_t>(s * 10));
        for (int i = 0; i < kSamples; ++i) {
            const FlakeNormal n = d.sample(uniform01(rng), uniform01(rng));
            ASSERT_NEAR(n.x * n.x + n.y * n.y + n.z * n.z, 1.0, 1e-12);  // unit vector, rounding only
            ASSERT_GE(n.z, 0.0);
            const double alpha = std::atan2(std::hypot(n.x, n.y), n.z);
            double phi = std::atan2(n.y, n.x);
            if (phi < 0.0) phi += 2.0 * kPi;
            const auto ia = static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), alpha) -
                                                     edges.begin() - 1);
            const auto ip =
                std::min<std::size_t>(kPhiBins - 1, static_cast<std::size_t>(phi / (2.0 * kPi) * kPhiBins));
            observed[std::min(ia, na - 1) * kPhiBins + ip] += 1.0;
        }
        for (std::size_t ia = 0; ia < na; ++ia) {
            const double p = overAlpha(
                                 d, [](double) { return 1.0; }, edges[ia], edges[ia + 1], 400) *
                             2.0 * kPi;
            for (std::size_t ip = 0; ip < kPhiBins; ++ip)
                expected[ia * kPhiBins + ip] = kSamples * p / kPhiBins;
        }
        double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
        int dof = -1;
        for (std::size_t b = 0; b < observed.size(); ++b) {
            if (expected[b] < 5.0) {
                pooled_o += observed[b];
                pooled_e += expected[b];
                continue;
            }
            chi2 += std::pow(observed[b] - expected[b], 2) / expected[b];
            ++dof;
        }
        if (pooled_e >= 5.0)
            chi2 += std::pow(pooled_o - pooled_e, 2) / pooled_e, ++dof;
        else
            EXPECT_LT(pooled_o, 20.0) << "samples where the pdf says almost none";
        const double p_value = chiSquareTail(chi2, dof);
        EXPECT_GT(p_value, level) << "spread " << s << " chi2 " << chi2 << " dof " << dof;
    }
}

TEST(FlakeOrientation, ProjectedAreaMatchesBruteForce) {
    for (double s : {1.0, 10.0, 30.0, 60.0}) {
        const FlakeOrientation d(s);
        for (double theta_deg : {0.0, 20.0, 45.0, 70.0, 85.0, 90.0}) {
            const double th = rad(theta_deg);
            // E|w.n| by a 2-D Simpson over (alpha, phi); phi in [0, pi] by symmetry.
            auto over_phi = [&](double a) {
                return simpson(
                           [&](double phi) {
                               return std::abs(std::sin(th) * std::sin(a) * std::cos(phi) +
                                               std::cos(th) * std::cos(a));
                           },
                           0.0, kPi, 2000) /
                       kPi * 2.0 * kPi;
            };
            const double brute = overAlpha(d, over_phi, 0.0, kPi / 2.0, 1000);
            // 2e-5: Simpson across the |.| kink in phi converges as h^2 ~ (pi/2000)^2.
            EXPECT_NEAR(d.meanProjectedCos(std::cos(th)), brute, 2e-5) << s << " " << theta_deg;
        }
    }
}

TEST(FlakeOrientation, ProjectedAreaLimits) {
    // sigma -> 0: |cos theta_w|, with |E|w.n| - |w.z|| <= E|n - z| <= E[alpha] ~ 1.25 sigma.
    const FlakeOrientation narrow(0.1);
    const FlakeOrientation delta(0.0);
    EXPECT_TRUE(delta.isDelta());
    for (double c = -1.0; c <= 1.0; c += 0.01) {
        EXPECT_EQ(delta.meanProjectedCos(c), std::abs(c));
        EXPECT_NEAR(narrow.meanProjectedCos(c), std::abs(c), 1.3 * rad(0.1));
    }
    // Away from grazing the deviation is second order, ~sigma^2 cos / 2... tighter:
    EXPECT_NEAR(narrow.meanProjectedCos(0.7), 0.7 * narrow.meanCos(), 1e-12);  // all flakes have a >= b here
    // sigma = 90 deg is the uniform hemisphere: E|w.n| = (1/2pi) * (1/2) * 2pi = 1/2 for every w
    // (|w.n| averages 1/2 over the sphere; two-sided flakes make the hemisphere the same).
    const FlakeOrientation uniform(90.0);
    EXPECT_LT(uniform.kappa(), 1e-12);
    for (double c = 0.0; c <= 1.0; c += 0.01)
        EXPECT_NEAR(uniform.meanProjectedCos(c), 0.5,
                    1e-10);  // 8x16-point GL, analytic integrand: ~5e-12 measured
    EXPECT_NEAR(uniform.meanCos(), 0.5, 1e-15);
    EXPECT_NEAR(uniform.pdf(0.3), 1.0 / (2.0 * kPi), 1e-15);
    // Monotone approach: a wider spread moves E|w.n| at normal incidence toward 1/2.
    double prev = 1.0;
    for (double s : kSpreadsDeg) {
        const double e = FlakeOrientation(s).meanProjectedCos(1.0);
        EXPECT_LT(e, prev);
        prev = e;
    }
}

TEST(FlakeOrientation, FiniteAtTheExtremes) {
    for (double s :
         {0.0, 1e-9, 1e-6, 0.1, 45.0, 89.999, 90.0, 200.0, -3.0, std::numeric_limits<double>::quiet_NaN()}) {
        const FlakeOrientation d(s);
        for (double c : {0.0, 1e-300, 1e-8, 0.5, 1.0 - 1e-15, 1.0}) {
            EXPECT_TRUE(std::isfinite(d.meanProjectedCos(c))) << s << " " << c;
            EXPECT_TRUE(std::isfinite(d.pdf(c)) || d.isDelta()) << s << " " << c;
            EXPECT_GE(d.meanProjectedCos(c), 0.0);
            EXPECT_LE(d.meanProjectedCos(c), 1.0 + 1e-12);
        }
        for (double u : {0.0, 1e-300, 0.5, 1.0 - 0x1.0p-53, 1.0}) {
            const FlakeNormal n = d.sample(u, u);
            EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << s << " " << u;
            EXPECT_NEAR(n.x * n.x + n.y * n.y + n.z * n.z, 1.0, 1e-12);
        }
        EXPECT_TRUE(std::isfinite(d.meanCos()));
    }
}

}  // namespace
}  // namespace paintlab
