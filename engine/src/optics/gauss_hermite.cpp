// Gauss-Hermite quadrature rules (the fallback thickness average of
// thin_film.cpp, for narrow spreads and strongly absorbing layers).
#include "paintlab/engine/optics/thin_film.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace paintlab {
namespace {

// Gauss-Hermite nodes by root-finding on the orthonormal Hermite recurrence
// h_0 = pi^(-1/4), h_j = x sqrt(2/j) h_{j-1} - sqrt((j-1)/j) h_{j-2};
// h_n' = sqrt(2n) h_{n-1}; Christoffel weights w = 1 / sum_{j<n} h_j(x)^2
// (Gautschi, Orthogonal Polynomials: Computation and Approximation, 2004).
struct HermiteEval {
    double hn, hn1, sum_sq;  // h_n(x), h_{n-1}(x), sum_{j<n} h_j(x)^2
};

HermiteEval hermite(int n, double x) {
    double h_prev = 0.0;
    double h = std::pow(std::numbers::pi, -0.25);
    double sum_sq = 0.0;
    for (int j = 1; j <= n; ++j) {
        sum_sq += h * h;
        const double jd = static_cast<double>(j);
        const double h_next = x * std::sqrt(2.0 / jd) * h - std::sqrt((jd - 1.0) / jd) * h_prev;
        h_prev = h;
        h = h_next;
    }
    return {h, h_prev, sum_sq};
}

struct GaussHermiteTable {
    std::array<std::vector<double>, kMaxGaussHermiteNodes + 1> x, w;
    GaussHermiteTable() {
        for (int n = 1; n <= kMaxGaussHermiteNodes; ++n) {
            std::vector<double> roots;
            // All roots lie in |x| < sqrt(2n + 1); their spacing exceeds
            // ~pi / sqrt(2n + 1), so a scan with 40n steps brackets each once.
            const double x_max = std::sqrt(2.0 * n + 1.0);
            const int steps = 40 * n;
            double x_lo = -x_max;
            double f_lo = hermite(n, x_lo).hn;
            for (int k = 1; k <= steps; ++k) {
                const double x_hi = -x_max + 2.0 * x_max * k / steps;
                const double f_hi = hermite(n, x_hi).hn;
                if ((f_lo < 0.0) != (f_hi < 0.0)) roots.push_back(polish(n, x_lo, x_hi, f_lo));
                x_lo = x_hi;
                f_lo = f_hi;
            }
            auto& xs = x[static_cast<std::size_t>(n)];
            auto& ws = w[static_cast<std::size_t>(n)];
            for (double r : roots) {
                xs.push_back(r);
                ws.push_back(1.0 / hermite(n, r).sum_sq);
            }
        }
    }
    // Newton from the bracket midpoint, falling back to bisection whenever a
    // step leaves the bracket.
    static double polish(int n, double lo, double hi, double f_lo) {
        double xr = 0.5 * (lo + hi);
        for (int it = 0; it < 100; ++it) {
            const HermiteEval e = hermite(n, xr);
            if (e.hn == 0.0) return xr;
            if ((e.hn < 0.0) == (f_lo < 0.0)) {
                lo = xr;
                f_lo = e.hn;
            } else {
                hi = xr;
            }
            const double d = std::sqrt(2.0 * n) * e.hn1;
            double next = d != 0.0 ? xr - e.hn / d : 0.5 * (lo + hi);
            if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
            if (std::abs(next - xr) <= 1e-15 * std::max(1.0, std::abs(xr))) return next;
            xr = next;
        }
        return xr;
    }
};

}  // namespace

GaussHermiteRule gaussHermiteRule(int n) {
    static const GaussHermiteTable table;
    n = std::clamp(n, 1, kMaxGaussHermiteNodes);
    const auto k = static_cast<std::size_t>(n);
    return {table.x[k], table.w[k]};
}

int gaussHermiteNodesForPhaseSpread(double phase_spread_rad) {
    // With d = mean + sqrt(2) sigma x the phase is a x, a = sqrt(2) * phase
    // spread, and the average is the Gauss-Hermite sum of exp(i a x) (and its
    // harmonics from multiple reflections). The n-node rule is exact to
    // degree 2n - 1; the Taylor series of exp(i a x) against exp(-x^2) has
    // terms ~ (a/2)^(2n) / n!, which drop below 1e-6 once n > ~(e a^2 / 8 + 6).
    // Multiple reflections inside the TiO2 add a second harmonic 2a with
    // amplitude ~r^2 ~ 0.07 (r = 0.27 at TiO2/binder); we size for 1.5 a.
    // Used only where the periodic trapezoid is not (spreads narrower than
    // ~1/150 of a period, strongly absorbing or evanescent layers), i.e. for
    // small a; test_thin_film.cpp shows why it is not the default for wide
    // spreads (errors ~1e-2 even with 96 nodes: the sharp high-finesse
    // features near grazing incidence are not polynomial-like).
    if (!(phase_spread_rad > 0.0)) return 1;
    const double a = 1.5 * std::numbers::sqrt2 * phase_spread_rad;
    const double n = std::ceil(std::numbers::e * a * a / 8.0 + 6.0);
    return static_cast<int>(std::clamp(n, 4.0, static_cast<double>(kMaxGaussHermiteNodes)));
}

}  // namespace paintlab
