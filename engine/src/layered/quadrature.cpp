#include "paintlab/engine/layered/quadrature.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace paintlab::layered {

namespace {

// Legendre P_n(x) and P_{n-1}(x) by the three-term recurrence (Abramowitz & Stegun 8.5.3).
void legendre(int n, double x, double& p_n, double& p_nm1) {
    double p0 = 1.0;
    double p1 = x;
    if (n == 0) {
        p_n = 1.0;
        p_nm1 = 0.0;
        return;
    }
    for (int k = 2; k <= n; ++k) {
        const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
    }
    p_n = p1;
    p_nm1 = p0;
}

// Eigenvalues (ascending) of a symmetric tridiagonal Jacobi matrix: the nodes of the
// Gauss rule of its orthogonal polynomials (Golub & Welsch 1969). Only the eigenvalues
// are needed: the weights follow from closed formulas after a Newton polish.
Eigen::VectorXd jacobiEigenvalues(const std::vector<double>& diag, const std::vector<double>& off) {
    const auto n = static_cast<Eigen::Index>(diag.size());
    Eigen::VectorXd d(n);
    Eigen::VectorXd e(std::max<Eigen::Index>(n - 1, 1));
    e.setZero();
    for (Eigen::Index i = 0; i < n; ++i) d(i) = diag[static_cast<std::size_t>(i)];
    for (Eigen::Index i = 0; i + 1 < n; ++i) e(i) = off[static_cast<std::size_t>(i)];
    if (n == 1) return d;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
    solver.computeFromTridiagonal(d, e.head(n - 1), Eigen::EigenvaluesOnly);
    return solver.eigenvalues();
}

void mapInterval(double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
    const double half = 0.5 * (b - a);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        nodes[i] = a + half * (nodes[i] + 1.0);
        weights[i] *= half;
    }
}

}  // namespace

double Quadrature::fluxWeight(int i) const {
    const auto k = static_cast<std::size_t>(i);
    return 2.0 * mu[k] * weight[k];
}

void gaussLegendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
    std::vector<double> diag(static_cast<std::size_t>(n), 0.0);
    std::vector<double> off(static_cast<std::size_t>(std::max(n - 1, 0)));
    for (int k = 1; k < n; ++k) off[static_cast<std::size_t>(k - 1)] = k / std::sqrt(4.0 * k * k - 1.0);
    const Eigen::VectorXd x = jacobiEigenvalues(diag, off);
    nodes.assign(static_cast<std::size_t>(n), 0.0);
    weights.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) {
        // Two Newton steps on P_n polish the eigenvalue to full precision; the
        // weight then follows from w = 2 / ((1 - x^2) P_n'(x)^2) (A&S 25.4.29).
        double xi = x(i);
        double dp = 1.0;
        for (int it = 0; it < 2; ++it) {
            double p = 0.0;
            double pm1 = 0.0;
            legendre(n, xi, p, pm1);
            dp = n * (xi * p - pm1) / (xi * xi - 1.0);
            xi -= p / dp;
        }
        double p = 0.0;
        double pm1 = 0.0;
        legendre(n, xi, p, pm1);
        dp = n * (xi * p - pm1) / (xi * xi - 1.0);
        nodes[static_cast<std::size_t>(i)] = xi;
        weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - xi * xi) * dp * dp);
    }
    mapInterval(a, b, nodes, weights);
}

void gaussRadauRight(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
    // Interior nodes: zeros of the Jacobi polynomial P^(1,0)_{n-1} (weight 1 - x),
    // recurrence a_k = -1/((2k+1)(2k+3)), b_k = sqrt(k(k+1))/(2k+1). Weights
    // (mirror of A&S 25.4.31): w_i = (1 + x_i) / (n^2 P_{n-1}(x_i)^2), w_end = 2/n^2.
    const int m = n - 1;
    std::vector<double> diag(static_cast<std::size_t>(m));
    std::vector<double> off(static_cast<std::size_t>(std::max(m - 1, 0)));
    for (int k = 0; k < m; ++k)
        diag[static_cast<std::size_t>(k)] = -1.0 / ((2.0 * k + 1.0) * (2.0 * k + 3.0));
    for (int k = 1; k < m; ++k)
        off[static_cast<std::size_t>(k - 1)] = std::sqrt(k * (k + 1.0)) / (2.0 * k + 1.0);
    const Eigen::VectorXd x = jacobiEigenvalues(diag, off);
    nodes.assign(static_cast<std::size_t>(n), 1.0);
    weights.assign(static_cast<std::size_t>(n), 2.0 / (static_cast<double>(n) * n));
    for (int i = 0; i < m; ++i) {
        // Two Newton steps on q(x) = P_{n-1}(x) - P_n(x), whose zeros are 1 and the interior
        // nodes, polish the eigenvalues; P_k'(x) = k (x P_k - P_{k-1}) / (x^2 - 1) (A&S 8.5.4).
        double xi = x(i);
        for (int it = 0; it < 2; ++it) {
            double p_n = 0.0;
            double p_nm1 = 0.0;
            double p_nm1b = 0.0;
            double p_nm2 = 0.0;
            legendre(n, xi, p_n, p_nm1);
            legendre(n - 1, xi, p_nm1b, p_nm2);
            const double dp_n = n * (xi * p_n - p_nm1) / (xi * xi - 1.0);
            const double dp_nm1 = (n - 1) * (xi * p_nm1 - p_nm2) / (xi * xi - 1.0);
            const double dq = dp_nm1 - dp_n;
            if (dq != 0.0) xi -= (p_nm1 - p_n) / dq;
        }
        double p = 0.0;
        double pm1 = 0.0;
        legendre(n, xi, p, pm1);
        nodes[static_cast<std::size_t>(i)] = xi;
        weights[static_cast<std::size_t>(i)] = (1.0 + xi) / (static_cast<double>(n) * n * pm1 * pm1);
    }
    mapInterval(a, b, nodes, weights);
    nodes.back() = b;  // exactly the fixed end
}

Quadrature makeQuadrature(int n_nodes, double eta, double mu_incident) {
    Quadrature q;
    const bool oblique = mu_incident < 1.0;
    const int n_escape_min = oblique ? 3 : 2;
    double lower = 0.0;
    std::vector<double> x;
    std::vector<double> w;
    if (eta > 1.0) {
        q.mu_critical = std::sqrt(1.0 - 1.0 / (eta * eta));
        lower = q.mu_critical;
        const int n_trapped =
            std::clamp(static_cast<int>(std::lround(n_nodes * q.mu_critical * q.mu_critical)), 1,
                       n_nodes - n_escape_min);
        gaussLegendre(n_trapped, 0.0, q.mu_critical, x, w);
        q.mu = x;
        q.weight = w;
        q.n_trapped = n_trapped;
    }
    const int n_escape = n_nodes - q.n_trapped;
    if (!oblique) {
        gaussRadauRight(n_escape, lower, 1.0, x, w);
        q.mu.insert(q.mu.end(), x.begin(), x.end());
        q.weight.insert(q.weight.end(), w.begin(), w.end());
        q.collimated = n_nodes - 1;
    } else {
        const double fraction = (mu_incident - lower) / (1.0 - lower);
        const int n_below = std::clamp(static_cast<int>(std::lround(n_escape * fraction)), 2, n_escape - 1);
        gaussRadauRight(n_below, lower, mu_incident, x, w);
        q.mu.insert(q.mu.end(), x.begin(), x.end());
        q.weight.insert(q.weight.end(), w.begin(), w.end());
        q.collimated = static_cast<int>(q.mu.size()) - 1;
        gaussLegendre(n_escape - n_below, mu_incident, 1.0, x, w);
        q.mu.insert(q.mu.end(), x.begin(), x.end());
        q.weight.insert(q.weight.end(), w.begin(), w.end());
    }
    return q;
}

}  // namespace paintlab::layered
