#include "paintlab/engine/optics/flake_orientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab {
namespace {

// Below this kappa the distribution is uniform to 1e-12 in every output
// (the first correction is kappa / 2 in the density).
constexpr double kUniformKappa = 1e-12;
// exp(-45) ~ 3e-20: beyond 45 e-folds the truncated-exponential weight is
// below double precision relative to its peak.
constexpr double kEFolds = 45.0;

// 16-point Gauss-Legendre rule on [-1, 1] by Newton on P_16 with the
// the asymptotic initial guesses cos(pi (i - 1/4) / (n + 1/2)); weights
// 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz & Stegun 25.4.29).
struct GaussLegendre16 {
    static constexpr int kN = 16;
    std::array<double, kN> x{}, w{};
    GaussLegendre16() {
        for (int i = 0; i < kN; ++i) {
            double z = std::cos(std::numbers::pi * (i + 0.75) / (kN + 0.5));
            double dp = 1.0;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1.0, p1 = z;
                for (int k = 2; k <= kN; ++k) {
                    const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = kN * (z * p1 - p0) / (z * z - 1.0);
                const double dz = p1 / dp;
                z -= dz;
                if (std::abs(dz) < 1e-16) break;
            }
            x[static_cast<std::size_t>(i)] = z;
            w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
    }
};

const GaussLegendre16& gl16() {
    static const GaussLegendre16 rule;
    return rule;
}

// Composite 16-point Gauss-Legendre over [lo, hi] with `panels` equal panels.
template <class F> double integrate(F&& f, double lo, double hi, int panels) {
    if (!(hi > lo)) return 0.0;
    const GaussLegendre16& r = gl16();
    const double h = (hi - lo) / panels;
    double sum = 0.0;
    for (int p = 0; p < panels; ++p) {
        const double mid = lo + (p + 0.5) * h;
        for (std::size_t i = 0; i < r.x.size(); ++i) sum += r.w[i] * f(mid + 0.5 * h * r.x[i]);
    }
    return 0.5 * h * sum;
}

}  // namespace

FlakeOrientation::FlakeOrientation(double spread_deg) {
    m_spread_deg = std::isnan(spread_deg) ? 0.0 : std::clamp(spread_deg, 0.0, 90.0);
    // Spreads below 1e-6 deg (kappa > 3e15) are the delta: the tilt is
    // below any flake's flatness.
    m_delta = m_spread_deg < 1e-6;
    if (m_delta) {
        m_kappa = std::numeric_limits<double>::infinity();
        m_norm = std::numeric_limits<double>::infinity();
        return;
    }
    const double sigma = m_spread_deg * std::numbers::pi / 180.0;
    const double half_pi = 0.5 * std::numbers::pi;
    m_kappa = std::max(0.0, 1.0 / (sigma * sigma) - 1.0 / (half_pi * half_pi));
    // kappa / (1 - exp(-kappa)) -> 1 as kappa -> 0 (expm1 keeps it exact).
    m_norm = m_kappa < kUniformKappa ? 1.0 : m_kappa / -std::expm1(-m_kappa);
}

double FlakeOrientation::pdfMu(double mu) const {
    mu = std::min(1.0, std::abs(mu));
    if (m_delta) return 0.0;
    if (m_kappa < kUniformKappa) return 1.0;
    return m_norm * std::exp(-m_kappa * (1.0 - mu));
}

double FlakeOrientation::pdf(double cos_alpha) const { return pdfMu(cos_alpha) / (2.0 * std::numbers::pi); }

FlakeNormal FlakeOrientation::sample(double u1, double u2) const {
    if (m_delta) return {};
    u1 = std::clamp(u1, 0.0, 1.0);
    // P(mu >= m) = (1 - exp(-kappa (1 - m))) / (1 - exp(-kappa)) = u1, solved
    // for t = 1 - m with log1p/expm1 so that neither kappa ~ 3e5 nor kappa -> 0
    // loses digits.
    double t = u1;
    if (m_kappa >= kUniformKappa) t = -std::log1p(u1 * std::expm1(-m_kappa)) / m_kappa;
    t = std::clamp(t, 0.0, 1.0);
    const double mu = 1.0 - t;
    const double sin_alpha = std::sqrt(t * (2.0 - t));
    const double phi = 2.0 * std::numbers::pi * std::clamp(u2, 0.0, 1.0);
    return {sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), mu};
}

double FlakeOrientation::meanCos() const {
    if (m_delta) return 1.0;
    const double k = m_kappa;
    // Series 1/2 + k/12 - k^3/720 (Bernoulli numbers of x / (1 - e^-x)) where
    // the closed form cancels; the next term k^5/30240 is < 1e-19 there.
    if (k < 1e-3) return 0.5 + k / 12.0 - k * k * k / 720.0;
    return 1.0 / -std::expm1(-k) - 1.0 / k;
}

double FlakeOrientation::meanProjectedCos(double cos_w) const {
    const double c_w = std::min(1.0, std::abs(cos_w));
    if (m_delta) return c_w;
    const double s_w = std::sqrt(std::max(0.0, (1.0 - c_w) * (1.0 + c_w)));
    // Averaged over the flake azimuth, w . n = a + b cos(phi) with a = c_w mu,
    // b = s_w sqrt(1 - mu^2), and the mean of |a + b cos phi| is a when a >= b,
    // else (2/pi) (a asin(a/b) + sqrt(b^2 - a^2)). a >= b exactly when
    // mu >= s_w, so the mu integral splits at the kink mu = s_w; there
    // b^2 - a^2 = s_w^2 - mu^2.
    const double k = m_kappa < kUniformKappa ? 0.0 : m_kappa;
    const double norm = m_norm;
    // Part A, mu in [s_w, 1]: c_w E[mu; mu >= s_w], in t = 1 - mu with weight
    // norm exp(-k t), cut after kEFolds e-folds.
    double t_hi = 1.0 - s_w;
    if (k > 0.0) t_hi = std::min(t_hi, kEFolds / k);
    const double part_a =
        c_w * integrate([&](double t) { return (1.0 - t) * norm * std::exp(-k * t); }, 0.0, t_hi, 8);
    // Part B, mu in [0, s_w]: mu = s_w - v^2 removes the square-root kink
    // (sqrt(s_w^2 - mu^2) = v sqrt(2 s_w - v^2)); dmu = 2 v dv.
    double v_hi = std::sqrt(s_w);
    if (k > 0.0) v_hi = std::min(v_hi, std::sqrt(kEFolds / k));
    const double part_b = integrate(
        [&](double v) {
            const double mu = s_w - v * v;
            const double a = c_w * mu;
            const double root = v * std::sqrt(std::max(0.0, 2.0 * s_w - v * v));
            const double g = 2.0 / std::numbers::pi * (a * std::atan2(a, root) + root);
            return g * norm * std::exp(-k * (1.0 - mu)) * 2.0 * v;
        },
        0.0, v_hi, 8);
    return part_a + part_b;
}

}  // namespace paintlab
