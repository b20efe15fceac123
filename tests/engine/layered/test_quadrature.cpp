#include "paintlab/engine/layered/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace paintlab::layered;

namespace {

double polyIntegral(const std::vector<double>& x, const std::vector<double>& w, int degree) {
    double s = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) s += w[i] * std::pow(x[i], degree);
    return s;
}

}  // namespace

TEST(Quadrature, GaussLegendreIsExactToDegree2nMinus1) {
    std::vector<double> x;
    std::vector<double> w;
    gaussLegendre(7, 0.2, 0.9, x, w);
    for (int k = 0; k <= 13; ++k) {
        const double exact = (std::pow(0.9, k + 1) - std::pow(0.2, k + 1)) / (k + 1);
        // A few ulp per node, summed over 7 nodes.
        EXPECT_NEAR(polyIntegral(x, w, k), exact, 1e-14) << "degree " << k;
    }
}

TEST(Quadrature, GaussRadauIsExactToDegree2nMinus2AndEndsAtB) {
    std::vector<double> x;
    std::vector<double> w;
    gaussRadauRight(6, 0.3, 1.0, x, w);
    EXPECT_EQ(x.back(), 1.0);
    for (int k = 0; k <= 10; ++k) {
        const double exact = (1.0 - std::pow(0.3, k + 1)) / (k + 1);
        // Eigenvalue accuracy of the Golub-Welsch nodes, ~1e-15 each.
        EXPECT_NEAR(polyIntegral(x, w, k), exact, 1e-13) << "degree " << k;
    }
}

TEST(Quadrature, NormalisationAndCriticalSplit) {
    for (double eta : {1.0, 1.33, 1.5, 2.9}) {
        for (double mu0 : {1.0, 0.97, 0.995}) {
            const double mu_c = eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;
            if (mu0 <= mu_c) continue;
            const Quadrature q = makeQuadrature(16, eta, mu0);
            ASSERT_EQ(q.size(), 16);
            double sum_w = 0.0;
            double sum_c = 0.0;
            double sum_c_escape = 0.0;
            for (int i = 0; i < q.size(); ++i) {
                sum_w += q.weight[static_cast<std::size_t>(i)];
                sum_c += q.fluxWeight(i);
                if (i >= q.n_trapped) sum_c_escape += q.fluxWeight(i);
                const double mu = q.mu[static_cast<std::size_t>(i)];
                if (i > 0) {
                    EXPECT_LT(q.mu[static_cast<std::size_t>(i - 1)], mu);
                }
                // No node may sit on the wrong side of the critical cosine.
                if (i < q.n_trapped) {
                    EXPECT_LT(mu, mu_c);
                } else {
                    EXPECT_GT(mu, mu_c);
                }
            }
            // Each sub-rule integrates 1 and mu exactly: rounding only.
            EXPECT_NEAR(sum_w, 1.0, 1e-14);
            EXPECT_NEAR(sum_c, 1.0, 1e-14);
            EXPECT_NEAR(sum_c_escape, 1.0 / (eta * eta), 1e-14);
            EXPECT_EQ(q.mu[static_cast<std::size_t>(q.collimated)], mu0);
        }
    }
}
