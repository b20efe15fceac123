#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/layered/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace paintlab::layered;

namespace {

// HG normalised to a 4 pi average of 1.
double henyeyGreenstein(double g, double cos_theta) {
    return (1.0 - g * g) / std::pow(1.0 + g * g - 2.0 * g * cos_theta, 1.5);
}

}  // namespace

TEST(PhaseFunction, FourierSumReproducesHenyeyGreenstein) {
    // g = 0.5 with 60 moments: truncation g^60 ~ 1e-18, so no delta-M effect.
    const double g = 0.5;
    const DeltaMPhase phase = henyeyGreensteinDeltaM(g, 60);
    EXPECT_LT(phase.f, 1e-17);
    const std::vector<double> mu = {0.3, 0.8};
    const double dphi = 0.7;
    double sum_same = 0.0;
    double sum_opposite = 0.0;
    for (int m = 0; m < 60; ++m) {
        const PhaseMatrices h = phaseMatrices(mu, phase.chi, m);
        const double factor = (m == 0 ? 1.0 : 2.0) * std::cos(m * dphi);
        sum_same += factor * h.same(0, 1);
        sum_opposite += factor * h.opposite(0, 1);
    }
    const double s0 = std::sqrt(1.0 - 0.09);
    const double s1 = std::sqrt(1.0 - 0.64);
    const double cos_same = 0.3 * 0.8 + s0 * s1 * std::cos(dphi);
    const double cos_opposite = -0.3 * 0.8 + s0 * s1 * std::cos(dphi);
    // Series truncated at g^60 and rounding of ~60 terms of size <= 10.
    EXPECT_NEAR(sum_same, henyeyGreenstein(g, cos_same), 1e-12);
    EXPECT_NEAR(sum_opposite, henyeyGreenstein(g, cos_opposite), 1e-12);
}

TEST(PhaseFunction, DeltaMScaling) {
    const DeltaMPhase phase = henyeyGreensteinDeltaM(0.9, 16);
    const double f = std::pow(0.9, 16);
    EXPECT_DOUBLE_EQ(phase.f, f);
    EXPECT_DOUBLE_EQ(phase.chi[0], 1.0);
    EXPECT_NEAR(phase.chi[1], (0.9 - f) / (1.0 - f), 1e-15);  // rounding
    // tau* and a* keep the scattering and absorption optical thicknesses' balance:
    // a* tau* = a tau (1 - f) and (1 - a*) tau* = (1 - a) tau (Wiscombe 1977).
    const double a = 0.7;
    const double tau = 3.0;
    EXPECT_NEAR(phase.scaledAlbedo(a) * phase.scaledTau(a, tau), a * tau * (1.0 - f), 1e-14);
    EXPECT_NEAR((1.0 - phase.scaledAlbedo(a)) * phase.scaledTau(a, tau), (1.0 - a) * tau, 1e-14);
}

TEST(PhaseFunction, MatricesSymmetric) {
    const Quadrature q = makeQuadrature(12, 1.5);
    const DeltaMPhase phase = henyeyGreensteinDeltaM(0.75, 12);
    for (int m : {0, 1, 5}) {
        const PhaseMatrices h = phaseMatrices(q.mu, phase.chi, m);
        // Exactly symmetric by construction (L D L^T) up to rounding of the products.
        EXPECT_LT((h.same - h.same.transpose()).cwiseAbs().maxCoeff(), 1e-12);
        EXPECT_LT((h.opposite - h.opposite.transpose()).cwiseAbs().maxCoeff(), 1e-12);
    }
}
