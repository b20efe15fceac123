#include "paintlab/engine/optics/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace paintlab {
namespace {

// Closed forms: normal incidence R = ((n1-n2)/(n1+n2))^2, or |(n-1+ik)/(n+1+ik)|^2
// for a metal; Brewster's angle zeroes rp; TIR beyond the critical angle.
TEST(Fresnel, NormalIncidenceMatchesClosedForm) {
    EXPECT_NEAR(fresnelDielectric(1.0, 1.5), 0.04, 1e-15);
    EXPECT_NEAR(fresnelReflectance(1.0, 1.0, 1.5), 0.04, 1e-15);
    const std::complex<double> al(0.96, 6.69);  // aluminium at ~550 nm (Rakic 1995)
    const double expected = std::norm((al - 1.0) / (al + 1.0));
    EXPECT_NEAR(fresnelReflectance(1.0, 1.0, al), expected, 1e-14);
    EXPECT_GT(expected, 0.9);
}

TEST(Fresnel, BrewsterAngleZeroesP) {
    const double eta = 1.5;
    const double cos_b = std::cos(std::atan(eta));
    const auto a = fresnelAmplitudes(cos_b, 1.0, eta);
    EXPECT_NEAR(std::abs(a.rp), 0.0, 1e-14);
    EXPECT_NEAR(fresnelDielectric(cos_b, eta), 0.5 * std::norm(a.rs), 1e-14);
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
    const double eta = 1.0 / 1.5;                           // glass to air
    const double cos_c = std::sqrt(1.0 - eta * eta);        // critical angle
    EXPECT_EQ(fresnelDielectric(cos_c * 0.999, eta), 1.0);  // just beyond: TIR
    EXPECT_LT(fresnelDielectric(std::min(1.0, cos_c * 1.001), eta), 1.0);
    EXPECT_NEAR(fresnelReflectance(cos_c * 0.5, 1.5, 1.0), 1.0, 1e-14);
    EXPECT_EQ(refractedCos(cos_c * 0.5, eta), 0.0);
}

TEST(Fresnel, EnergyIsConservedAtDielectricInterfaces) {
    // R + T = 1 with T = (n_t cos_t)/(n_i cos_i) |t|^2 for each polarisation.
    for (double cos_i = 0.01; cos_i <= 1.0; cos_i += 0.01) {
        for (double eta : {1.0 / 1.5, 1.33, 1.5, 2.9}) {
            const auto a = fresnelAmplitudes(cos_i, 1.0, eta);
            if (std::abs(a.cos_t.imag()) > 0.0) continue;  // TIR: no transmitted power
            const double factor = eta * a.cos_t.real() / cos_i;
            EXPECT_NEAR(std::norm(a.rs) + factor * std::norm(a.ts), 1.0, 1e-12);
            EXPECT_NEAR(std::norm(a.rp) + factor * std::norm(a.tp), 1.0, 1e-12);
        }
    }
}

TEST(Fresnel, DielectricAndGeneralFormsAgreeAndAreSymmetric) {
    for (double cos_i = 0.0; cos_i <= 1.0; cos_i += 0.05) {
        EXPECT_NEAR(fresnelDielectric(cos_i, 1.5), fresnelReflectance(cos_i, 1.0, 1.5), 1e-13);
        // Reciprocity: R from either side along the refracted pair of angles is the same.
        const double cos_t = refractedCos(cos_i, 1.5);
        EXPECT_NEAR(fresnelDielectric(cos_i, 1.5), fresnelDielectric(cos_t, 1.0 / 1.5), 1e-12);
    }
    EXPECT_NEAR(fresnelDielectric(0.0, 1.5), 1.0, 1e-15);  // grazing: everything reflected
    EXPECT_EQ(fresnelDielectric(0.3, 1.0), 0.0);           // index matched: no interface
}

}  // namespace
}  // namespace paintlab
