#include "paintlab/engine/layered/phase_function.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace paintlab::layered {

namespace {

// Lambda_l^m(x) for l = m .. n_moments-1 by the stable upward recurrence in l
// (e.g. Numerical Recipes 3rd ed., sec. 6.7, in its semi-normalised form):
//   Lambda_m^m = prod_{k=1}^{m} sqrt((2k-1)/(2k)) (1 - x^2)^{m/2},
//   Lambda_{m+1}^m = sqrt(2m+1) x Lambda_m^m,
//   Lambda_l^m = ((2l-1) x Lambda_{l-1}^m - sqrt((l-1)^2 - m^2) Lambda_{l-2}^m) / sqrt(l^2 - m^2).
// The sign (-1)^m of P_l^m cancels in h^m, which is a product of two.
void seminormalisedLegendre(int m, double x, std::span<double> out) {
    const int n_moments = static_cast<int>(out.size());
    std::fill(out.begin(), out.end(), 0.0);
    if (m >= n_moments) return;
    const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
    double pmm = 1.0;
    for (int k = 1; k <= m; ++k) pmm *= std::sqrt((2.0 * k - 1.0) / (2.0 * k)) * s;
    out[static_cast<std::size_t>(m)] = pmm;
    if (m + 1 < n_moments) out[static_cast<std::size_t>(m) + 1] = std::sqrt(2.0 * m + 1.0) * x * pmm;
    for (int l = m + 2; l < n_moments; ++l) {
        const auto k = static_cast<std::size_t>(l);
        out[k] = ((2.0 * l - 1.0) * x * out[k - 1] -
                  std::sqrt((l - 1.0) * (l - 1.0) - static_cast<double>(m) * m) * out[k - 2]) /
                 std::sqrt(static_cast<double>(l) * l - static_cast<double>(m) * m);
    }
}

}  // namespace

double DeltaMPhase::scaledAlbedo(double albedo) const {
    const double denom = 1.0 - albedo * f;
    return denom > 0.0 ? albedo * (1.0 - f) / denom : albedo;
}

double DeltaMPhase::scaledTau(double albedo, double tau) const { return (1.0 - albedo * f) * tau; }

DeltaMPhase henyeyGreensteinDeltaM(double g, int n_moments) {
    DeltaMPhase out;
    out.f = std::pow(g, n_moments);
    out.chi.resize(static_cast<std::size_t>(n_moments));
    double gl = 1.0;
    for (int l = 0; l < n_moments; ++l) {
        out.chi[static_cast<std::size_t>(l)] = (gl - out.f) / (1.0 - out.f);
        gl *= g;
    }
    return out;
}

PhaseMatrices phaseMatrices(const std::vector<double>& mu, const std::vector<double>& chi, int m) {
    const auto n = static_cast<Eigen::Index>(mu.size());
    const int n_moments = static_cast<int>(chi.size());
    Eigen::MatrixXd lambda(n, n_moments);
    for (Eigen::Index i = 0; i < n; ++i) {
        std::vector<double> values(static_cast<std::size_t>(n_moments));
        seminormalisedLegendre(m, mu[static_cast<std::size_t>(i)], values);
        for (int l = 0; l < n_moments; ++l) lambda(i, l) = values[static_cast<std::size_t>(l)];
    }
    // Lambda_l^m(-x) = (-1)^(l+m) Lambda_l^m(x).
    Eigen::VectorXd coeff_same(n_moments);
    Eigen::VectorXd coeff_opposite(n_moments);
    for (int l = 0; l < n_moments; ++l) {
        const double c = (2.0 * l + 1.0) * chi[static_cast<std::size_t>(l)];
        coeff_same(l) = c;
        coeff_opposite(l) = ((l + m) % 2 == 0) ? c : -c;
    }
    PhaseMatrices h;
    h.same = lambda * coeff_same.asDiagonal() * lambda.transpose();
    h.opposite = lambda * coeff_opposite.asDiagonal() * lambda.transpose();
    return h;
}

namespace {

// The coefficients of the recurrence in seminormalisedLegendre for every
// m, l < n: its square roots dominate evaluating phaseFourierOrders at many
// direction pairs, and they depend on n alone. One table per thread, kept
// while n stays the same.
struct LegendreCoefficients {
    int n = 0;
    std::vector<double> a,
        b;  // a[m n + l] = (2l-1) / sqrt(l^2 - m^2), b[m n + l] = sqrt((l-1)^2 - m^2) / sqrt(l^2 - m^2)
    std::vector<double> start;  // start[m] = prod_{k<=m} sqrt((2k-1)/(2k))

    static const LegendreCoefficients& forMoments(int n) {
        thread_local LegendreCoefficients table;
        if (table.n != n) {
            const auto size = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
            table.n = n;
            table.a.assign(size, 0.0);
            table.b.assign(size, 0.0);
            table.start.assign(static_cast<std::size_t>(n), 1.0);
            for (int m = 0; m < n; ++m) {
                if (m > 0)
                    table.start[static_cast<std::size_t>(m)] =
                        table.start[static_cast<std::size_t>(m) - 1] * std::sqrt((2.0 * m - 1.0) / (2.0 * m));
                for (int l = m + 2; l < n; ++l) {
                    const double norm = std::sqrt(static_cast<double>(l) * l - static_cast<double>(m) * m);
                    const auto k = static_cast<std::size_t>(m) * static_cast<std::size_t>(n) +
                                   static_cast<std::size_t>(l);
                    table.a[k] = (2.0 * l - 1.0) / norm;
                    table.b[k] = std::sqrt((l - 1.0) * (l - 1.0) - static_cast<double>(m) * m) / norm;
                }
            }
        }
        return table;
    }

    // Lambda_l^m(x) for l = m .. n-1 into out (entries below m untouched).
    void values(int m, double x, double* out) const {
        const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
        const double pmm = start[static_cast<std::size_t>(m)] * std::pow(s, m);
        out[m] = pmm;
        if (m + 1 < n) out[m + 1] = std::sqrt(2.0 * m + 1.0) * x * pmm;
        const std::size_t row = static_cast<std::size_t>(m) * static_cast<std::size_t>(n);
        for (int l = m + 2; l < n; ++l)
            out[l] = a[row + static_cast<std::size_t>(l)] * x * out[l - 1] -
                     b[row + static_cast<std::size_t>(l)] * out[l - 2];
    }
};

}  // namespace

void phaseFourierOrders(double mu, double mu_prime, const std::vector<double>& chi, std::span<double> out) {
    const int n_moments = static_cast<int>(chi.size());
    std::fill(out.begin(), out.end(), 0.0);
    if (n_moments == 0) return;
    const LegendreCoefficients& legendre = LegendreCoefficients::forMoments(n_moments);
    thread_local std::vector<double> a;
    thread_local std::vector<double> b;
    a.resize(chi.size());
    b.resize(chi.size());
    for (int m = 0; m < std::min(static_cast<int>(out.size()), n_moments); ++m) {
        legendre.values(m, mu, a.data());
        legendre.values(m, mu_prime, b.data());
        double h = 0.0;
        for (int l = m; l < n_moments; ++l) {
            const auto k = static_cast<std::size_t>(l);
            h += (2.0 * l + 1.0) * chi[k] * a[k] * b[k];
        }
        out[static_cast<std::size_t>(m)] = (m == 0 ? 1.0 : 2.0) * h;
    }
}

double phaseFourierSum(double mu, double mu_prime, double cos_dphi, const std::vector<double>& chi,
                       int orders) {
    thread_local std::vector<double> terms;
    terms.assign(static_cast<std::size_t>(std::max(0, orders)), 0.0);
    phaseFourierOrders(mu, mu_prime, chi, terms);
    // cos(m dphi) by the Chebyshev recurrence.
    double sum = 0.0;
    double c_prev = cos_dphi;  // cos(-dphi)
    double c_now = 1.0;
    for (double term : terms) {
        sum += term * c_now;
        const double c_next = 2.0 * cos_dphi * c_now - c_prev;
        c_prev = c_now;
        c_now = c_next;
    }
    return sum;
}

}  // namespace paintlab::layered
