#include "paintlab/engine/layered/boundary.h"
#include "paintlab/engine/layered/layer_operator.h"
#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/layered/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace paintlab::layered;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

VectorXd fluxWeights(const Quadrature& q) {
    VectorXd c(q.size());
    for (int i = 0; i < q.size(); ++i) c(i) = q.fluxWeight(i);
    return c;
}

// Largest deviation from symmetry of the star matrix diag(c)^-1 G (Prahl 1995: star matrices of reciprocal
// media are symmetric).
double reciprocityError(const MatrixXd& G, const VectorXd& c) {
    const MatrixXd star = c.cwiseInverse().asDiagonal() * G;
    return (star - star.transpose()).cwiseAbs().maxCoeff() / star.cwiseAbs().maxCoeff();
}

struct Medium {
    Quadrature q;
    PhaseMatrices h;
};

Medium medium(int n, double eta, double g) {
    Medium m{makeQuadrature(n, eta), {}};
    m.h = phaseMatrices(m.q.mu, henyeyGreensteinDeltaM(g, n).chi, 0);
    return m;
}

}  // namespace

TEST(LayerOperator, ZeroThicknessIsIdentity) {
    const Medium m = medium(8, 1.0, 0.5);
    const LayerOperator op = homogeneousSlab(m.q, m.h, 0.9, 0.0, 0);
    EXPECT_EQ(op.R01.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_TRUE(op.T01.isIdentity(0.0));
}

TEST(LayerOperator, PureAbsorberIsExact) {
    const Medium m = medium(8, 1.5, 0.0);
    const double tau = 0.37;
    // Closed-form path (albedo 0) and the fitted diamond start doubled (albedo 0 in startLayer).
    const LayerOperator closed = homogeneousSlab(m.q, m.h, 0.0, tau, 0);
    LayerOperator doubled = startLayer(m.q, m.h, 0.0, tau / 1024.0, 0);
    for (int k = 0; k < 10; ++k) doubled = addLayers(doubled, doubled);
    for (int i = 0; i < m.q.size(); ++i) {
        const double exact = std::exp(-tau / m.q.mu[static_cast<std::size_t>(i)]);
        // exp is correctly rounded to ~1 ulp.
        EXPECT_NEAR(closed.T01(i, i), exact, 2e-16);
        // 1024 factors of tanh-fitted diamond transmission, each within a few ulp of exp(-d/mu).
        EXPECT_NEAR(doubled.T01(i, i), exact, 1e-13 * (1.0 + exact));
    }
    EXPECT_EQ(doubled.R01.cwiseAbs().maxCoeff(), 0.0);
}

TEST(LayerOperator, ConservativeLayerConservesEnergy) {
    for (double g : {0.0, 0.75, -0.5}) {
        const Medium m = medium(16, 1.5, g);
        for (double tau : {1e-3, 1.0, 30.0}) {
            const LayerOperator op = homogeneousSlab(m.q, m.h, 1.0, tau, 0);
            const VectorXd column_sums = (op.R01 + op.T01).colwise().sum().transpose();
            // The diamond start with the renormalised phase matrix conserves exactly and the
            // doubling restores the column sums against rounding drift: rounding only.
            EXPECT_LT((column_sums.array() - 1.0).abs().maxCoeff(), 1e-13) << "g " << g << " tau " << tau;
        }
    }
}

TEST(LayerOperator, Reciprocity) {
    const Medium m = medium(16, 1.5, 0.8);
    const LayerOperator op = homogeneousSlab(m.q, m.h, 0.9, 2.0, 0);
    const VectorXd c = fluxWeights(m.q);
    // Star matrices of a homogeneous layer are symmetric; rounding only.
    EXPECT_LT(reciprocityError(op.R01, c), 1e-12);
    EXPECT_LT(reciprocityError(op.T01, c), 1e-12);

    // With Fresnel boundaries and different slides above and below, seen from the air:
    // the outside flux weights n^2 c replace c on both sides (same medium, air).
    LayerOperator stack = addLayers(topBoundary(m.q, 1.5, 1.6), op);
    stack = addLayers(stack, bottomBoundary(m.q, 1.5, 1.4));
    const int n = m.q.size();
    const int e = m.q.n_trapped;
    const VectorXd c_out = outsideFluxWeights(m.q, 1.5).tail(n - e);
    EXPECT_LT(reciprocityError(stack.R01.bottomRightCorner(n - e, n - e), c_out), 1e-12);
    EXPECT_LT(reciprocityError(stack.R10.bottomRightCorner(n - e, n - e), c_out), 1e-12);
    // Transmission down equals the transpose of transmission up (star form).
    const MatrixXd down = c_out.cwiseInverse().asDiagonal() * stack.T01.bottomRightCorner(n - e, n - e);
    const MatrixXd up = c_out.cwiseInverse().asDiagonal() * stack.T10.bottomRightCorner(n - e, n - e);
    EXPECT_LT((down - up.transpose()).cwiseAbs().maxCoeff() / down.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(LayerOperator, LayerSplittingInvariance) {
    const Medium m = medium(16, 1.0, 0.75);
    // 1.0 = 0.3 + 0.7: the three slabs start from different thin layers (2^-k multiples of
    // 1, 0.3 and 0.7), so agreement measures the O(d^2) error of the diamond start, d <= 2^-12
    // (measured 8.6e-7).
    const LayerOperator whole = homogeneousSlab(m.q, m.h, 0.95, 1.0, 0);
    const LayerOperator sum =
        addLayers(homogeneousSlab(m.q, m.h, 0.95, 0.3, 0), homogeneousSlab(m.q, m.h, 0.95, 0.7, 0));
    EXPECT_LT((whole.R01 - sum.R01).cwiseAbs().maxCoeff(), 2e-6);
    EXPECT_LT((whole.T01 - sum.T01).cwiseAbs().maxCoeff(), 2e-6);
}

TEST(LayerOperator, HigherFourierOrdersAreFiniteAndReciprocal) {
    const Quadrature q = makeQuadrature(16, 1.0);
    const DeltaMPhase phase = henyeyGreensteinDeltaM(0.9, 16);
    const VectorXd c = fluxWeights(q);
    for (int m : {1, 4, 15}) {
        const PhaseMatrices h = phaseMatrices(q.mu, phase.chi, m);
        const LayerOperator op = homogeneousSlab(q, h, phase.scaledAlbedo(1.0), phase.scaledTau(1.0, 5.0), m);
        EXPECT_TRUE(op.R01.allFinite());
        EXPECT_TRUE(op.T01.allFinite());
        // Rounding only (see Reciprocity).
        EXPECT_LT(reciprocityError(op.R01, c), 1e-11) << "m " << m;
    }
}
