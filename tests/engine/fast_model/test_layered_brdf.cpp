// The fast model against closed forms, energy conservation and reciprocity.
#include "paintlab/engine/error.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/optics/fresnel.h"
#include "paintlab/engine/optics/thin_film.h"
#include "paintlab/engine/recipe_json.h"
#include "paintlab/engine/recipe_validation.h"

#include "paintlab/engine/layered/layer_operator.h"
#include "paintlab/engine/layered/phase_function.h"
#include "slab_operator.h"
#include "stack_quadrature.h"

#include "test_recipes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

namespace paintlab {
namespace {

using test::oneLayerRecipe;
using test::rawMedium;

constexpr double kPi = std::numbers::pi;

FastModelSettings settings(int nodes = 24, int orders = 16) {
    FastModelSettings s;
    s.nodes = nodes;
    s.orders = orders;
    s.bands = 2;
    s.max_start_tau = 1.0 / 1024.0;
    return s;
}

// Cosine-weighted hemispherical reflectance of the interface seen from inside
// (index n to air), total internal reflection included, by fine midpoint quadrature.
double internalDiffuseReflectance(double n) {
    const int steps = 200000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double mu = (i + 0.5) / steps;
        sum += 2.0 * mu * fresnelDielectric(mu, 1.0 / n) / steps;
    }
    return sum;
}

TEST(FastModelClosedForm, ClearCoatOverLambertianBase) {
    // A non-absorbing coat of index n over a Lambertian base rho, in air. The
    // base re-diffuses whatever the coat sends back, so the exact BRDF is
    //   f = (1 - r(mu_i)) (1 - r(mu_o)) rho / (pi n^2 (1 - rho r_i)),
    // r_i the coat's internal diffuse reflectance (e.g. Wolff 1994, Kelemen-Szirmay-Kalos 2001).
    const double n = 1.5;
    const double rho = 0.6;
    const LayeredBrdf brdf =
        computeLayeredBrdf(oneLayerRecipe(n, 40.0, LambertianSubstrate{Spectrum(rho)}), settings());
    const double r_i = internalDiffuseReflectance(n);
    for (double theta_i : {0.0, 20.0, 45.0, 70.0}) {
        for (double theta_o : {0.0, 30.0, 60.0, 80.0}) {
            const Direction wi = directionFromAnglesDeg(theta_i, 0.0);
            const Direction wo = directionFromAnglesDeg(theta_o, 120.0);
            const double expected = (1.0 - fresnelDielectric(wi.z, n)) * (1.0 - fresnelDielectric(wo.z, n)) *
                                    rho / (kPi * n * n * (1.0 - rho * r_i));
            // 0.5 %: linear interpolation between 24 nodes of a smooth Fresnel product,
            // and the quadrature's r_i (exact per interval split at the critical angle).
            EXPECT_NEAR(brdf.eval(wi, wo)[0], expected, 5e-3 * expected)
                << theta_i << " -> " << theta_o << " got " << brdf.eval(wi, wo)[0] << " expected "
                << expected;
        }
    }
    // Total reflectance including the mirror term: r + (1-r) rho (1 - r_i) / (1 - rho r_i).
    const double mu0 = std::cos(30.0 * kPi / 180.0);
    const double r0 = fresnelDielectric(mu0, n);
    const double total = r0 + (1.0 - r0) * rho * (1.0 - r_i) / (1.0 - rho * r_i);
    EXPECT_NEAR(brdf.albedo(directionFromAnglesDeg(30.0, 0.0))[0], total, 2e-3);  // interpolated in mu
    EXPECT_NEAR(brdf.specularReflectance(mu0)[0], r0, 1e-15);
}

TEST(FastModelClosedForm, IndexMatchedAbsorberOverLambertianBase) {
    // No interface, no scattering: f = rho/pi exp(-tau/mu_i - tau/mu_o).
    Recipe r = oneLayerRecipe(1.0, 10.0, LambertianSubstrate{Spectrum(0.8)});
    r.layers[0].components = {rawMedium(0.0, 0.5, 0.0)};
    const LayeredBrdf brdf = computeLayeredBrdf(r, settings());
    for (double theta_i : {0.0, 35.0, 60.0}) {
        for (double theta_o : {10.0, 50.0, 75.0}) {
            const Direction wi = directionFromAnglesDeg(theta_i, 0.0);
            const Direction wo = directionFromAnglesDeg(theta_o, 90.0);
            const double expected = 0.8 / kPi * std::exp(-0.5 / wi.z - 0.5 / wo.z);
            // 1 %: linear interpolation in mu of exp(-tau/mu), whose curvature grows towards grazing.
            EXPECT_NEAR(brdf.eval(wi, wo)[0], expected, 1e-2 * expected) << theta_i << " -> " << theta_o;
        }
    }
}

double henyeyGreenstein(double g, double cos_theta) {
    return (1.0 - g * g) / std::pow(1.0 + g * g - 2.0 * g * cos_theta, 1.5);  // 4 pi average 1
}

TEST(FastModelClosedForm, SingleScatteringLimitOfAThinSlab) {
    // tau << 1, index-matched, black below: f = a p(Theta) / (4 pi) (1 - e^{-tau(1/mu_i + 1/mu_o)}) / (mu_i +
    // mu_o), Theta between the incident propagation direction -wi and wo (Chandrasekhar 1960, sec. 47).
    const double a = 0.8, tau = 1e-3, g = 0.5;
    Recipe r = oneLayerRecipe(1.0, 1.0, BlackSubstrate{});
    r.layers[0].components = {rawMedium(a, tau, g)};
    const LayeredBrdf brdf = computeLayeredBrdf(r, settings(32, 32));
    for (double theta_i : {20.0, 50.0}) {
        for (double theta_o : {30.0, 60.0}) {
            for (double phi : {0.0, 90.0, 180.0}) {
                const Direction wi = directionFromAnglesDeg(theta_i, 0.0);
                const Direction wo = directionFromAnglesDeg(theta_o, phi);
                const double cos_theta = -(wi.x * wo.x + wi.y * wo.y + wi.z * wo.z);
                const double expected = a * henyeyGreenstein(g, cos_theta) / (4.0 * kPi) *
                                        (1.0 - std::exp(-tau * (1.0 / wi.z + 1.0 / wo.z))) / (wi.z + wo.z);
                // 3 %: multiple scattering adds O(tau) relative, the mu interpolation and 32 Fourier
                // orders of an HG lobe with g = 0.5 a few tenths of a percent.
                EXPECT_NEAR(brdf.eval(wi, wo)[0], expected, 3e-2 * expected)
                    << theta_i << " -> " << theta_o << " at " << phi;
            }
        }
    }
}

// Chandrasekhar's H-function for isotropic scattering with albedo a, from
// its integral equation 1/H(mu) = sqrt(1 - a) + (a/2) int_0^1 mu' H(mu') / (mu + mu') dmu'
// (Chandrasekhar 1960, eq. V.(11)), iterated on a fine Gauss-Legendre grid.
class HFunction {
public:
    explicit HFunction(double a) : m_a(a) {
        const int n = 200;
        m_x.resize(n);
        m_w.resize(n);
        for (int i = 0; i < n; ++i) {  // midpoint rule on a grid clustered towards 0 (mu = t^2)
            const double t = (i + 0.5) / n;
            m_x[static_cast<std::size_t>(i)] = t * t;
            m_w[static_cast<std::size_t>(i)] = 2.0 * t / n;
        }
        m_h.assign(n, 1.0);
        for (int it = 0; it < 500; ++it)
            for (std::size_t i = 0; i < m_x.size(); ++i) m_h[i] = (*this)(m_x[i]);
    }
    double operator()(double mu) const {
        double integral = 0.0;
        for (std::size_t j = 0; j < m_x.size(); ++j) integral += m_w[j] * m_x[j] * m_h[j] / (mu + m_x[j]);
        return 1.0 / (std::sqrt(1.0 - m_a) + 0.5 * m_a * integral);
    }

private:
    double m_a;
    std::vector<double> m_x, m_w, m_h;
};

TEST(FastModelClosedForm, SemiInfiniteIsotropicScatteringFollowsTheHFunction) {
    // f = (a / 4 pi) H(mu_i) H(mu_o) / (mu_i + mu_o) for a semi-infinite isotropic
    // medium without interfaces (Chandrasekhar 1960, ch. IV); tau = 10^4 is semi-infinite here.
    const double a = 0.9;
    Recipe r = oneLayerRecipe(1.0, 10.0, BlackSubstrate{});
    r.layers[0].components = {rawMedium(a, 1e4, 0.0)};
    const LayeredBrdf brdf = computeLayeredBrdf(r, settings(24, 2));
    const HFunction H(a);
    for (double ti : {0.0, 30.0, 60.0, 80.0}) {
        for (double to : {10.0, 45.0, 75.0}) {
            const Direction wi = directionFromAnglesDeg(ti, 0.0);
            const Direction wo = directionFromAnglesDeg(to, 70.0);
            const double expected = a / (4.0 * kPi) * H(wi.z) * H(wo.z) / (wi.z + wo.z);
            // 0.5 %: the H-function's own discretisation (~1e-4) and the BRDF's
            // interpolation between 24 nodes of a function with a sqrt-like edge at mu = 0.
            EXPECT_NEAR(brdf.eval(wi, wo)[0], expected, 5e-3 * expected) << ti << " -> " << to;
        }
    }
}

TEST(FastModelClosedForm, HorizontalMirrorFlakesAreATwoStreamProblem) {
    // Horizontal mirrors (spread 0) of area density A and reflectance rho_f,
    // index-matched, over black: a ray at any mu meets flakes at rate A per unit
    // depth and is mirrored into the same mu, so each mu is a Kubelka-Munk
    // problem with S = A rho_f, K = A (1 - rho_f):
    //   R = sinh(b S X) / (a sinh(b S X) + b cosh(b S X)), a = (S + K)/S, b = sqrt(a^2 - 1).
    const double c = 0.02, t_um = 0.5, X = 20.0, rho_f = 0.8;
    Recipe r = oneLayerRecipe(1.0, X, BlackSubstrate{});
    MirrorFlake flake;
    flake.name = "mirror";
    flake.volume_fraction = c;
    flake.thickness_um = t_um;
    flake.diameter_um = 10.0;
    flake.orientation_spread_deg = 0.0;
    flake.reflectance = Spectrum(rho_f);
    r.layers[0].components = {flake};
    const LayeredBrdf brdf = computeLayeredBrdf(r, settings(16, 4));
    const double A = c / t_um;
    // Assert at the nodes themselves (no interpolation). The flake's reflectance
    // depends on the local angle, which for horizontal flakes is the ray's own
    // (thin_film.h: an effective metal with R(normal) = rho_f).
    const auto& band = brdf.bands()[0];
    for (int i = 0; i < static_cast<int>(band.mu.size()); ++i) {
        const double mu = band.mu[static_cast<std::size_t>(i)];
        const double R_f = mirrorFlakeReflectanceFromNormal(mu, rho_f);
        const double S = A * R_f, K = A * (1.0 - R_f);
        const double ka = (S + K) / S, kb = std::sqrt(ka * ka - 1.0);
        const double expected =
            std::sinh(kb * S * X) / (ka * std::sinh(kb * S * X) + kb * std::cosh(kb * S * X));
        // 1e-4: the diamond start's O(d^2) error at d = 1/1024 and the 129-point
        // reflectance table's linear interpolation.
        EXPECT_NEAR(band.albedo(i), expected, 1e-4) << "mu " << mu;
    }
}

TEST(FastModelEnergy, NothingAbsorbsNothingIsLost) {
    // Conservative scattering, white mirror flakes and a white base under a
    // coat: every direction's albedo is 1 (the mirror term included).
    Recipe r = oneLayerRecipe(1.5, 15.0, LambertianSubstrate{Spectrum(1.0)});
    MirrorFlake flake;
    flake.name = "white mirror";
    flake.volume_fraction = 0.03;
    flake.thickness_um = 0.3;
    flake.diameter_um = 15.0;
    flake.orientation_spread_deg = 15.0;
    flake.reflectance = Spectrum(1.0);
    r.layers[0].components = {rawMedium(1.0, 3.0, 0.7), flake};
    const LayeredBrdf brdf = computeLayeredBrdf(r, settings());
    for (double a : brdf.bands()[0].albedo) EXPECT_NEAR(a, 1.0, 1e-6);  // round-off and the LU solves only
}

TEST(FastModelEnergy, NonAbsorbingInterferenceFlakesConserveEnergy) {
    // Lossless TiO2 / mica / TiO2 flakes reflect R and transmit T = 1 - R
    // straight on; in a clear binder over a white base nothing can be lost, so
    // the albedo is 1 in every direction at every band (the flakes' R + T = 1
    // and the kernel's energy bookkeeping both tested at once).
    Recipe r = oneLayerRecipe(1.5, 15.0, LambertianSubstrate{Spectrum(1.0)});
    InterferenceFlake pearl = test::interferenceFlake(0.06, 18.0, 10.0, 350.0, 120.0);
    pearl.mica_thickness_spread_nm = 40.0;
    pearl.tio2_thickness_spread_nm = 8.0;
    r.layers[0].components = {pearl};
    FastModelSettings s = settings();
    s.bands = 4;
    const LayeredBrdf brdf = computeLayeredBrdf(r, s);
    for (const auto& band : brdf.bands())
        for (double a : band.albedo) EXPECT_NEAR(a, 1.0, 1e-6);  // round-off of the LU solves only
}

TEST(FastModelReciprocity, DemoRecipesAreReciprocalFiniteAndConserveEnergy) {
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes")) {
        SCOPED_TRACE(entry.path().filename().string());
        const Recipe recipe = loadRecipeFile(entry.path());
        const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(Preset::Preview));
        for (const auto& band : brdf.bands()) {
            for (double a : band.albedo) {
                EXPECT_TRUE(std::isfinite(a));
                EXPECT_LE(a, 1.0 + 1e-6);  // no energy is created
                EXPECT_GE(a, 0.0);
            }
        }
        for (double ti : {10.0, 45.0, 75.0}) {
            for (double to : {0.0, 30.0, 65.0}) {
                const Direction wi = directionFromAnglesDeg(ti, 0.0);
                const Direction wo = directionFromAnglesDeg(to, 150.0);
                const auto f1 = brdf.eval(wi, wo);
                const auto f2 = brdf.eval(wo, wi);
                for (std::size_t b = 0; b < f1.size(); ++b) {
                    EXPECT_TRUE(std::isfinite(f1[b]));
                    // 1e-6 relative: the flux-to-flux tables satisfy diag(c)^-1 G = symmetric
                    // up to round-off, and the bilinear interpolation is symmetric too.
                    EXPECT_NEAR(f1[b], f2[b], 1e-6 * std::max(1.0, f1[b])) << ti << " <-> " << to;
                }
            }
        }
    }
}

// The Fourier coefficients are the series eval() sums: summed at any
// azimuth they give eval()'s value (where eval() does not clip ringing below
// zero), to round-off.
TEST(FastModelFourier, CoefficientsSumToEval) {
    const Recipe recipe =
        loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes" / "silver-metallic.json");
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(Preset::Preview));
    const auto bands = brdf.wavelengthsNm().size();
    const auto orders = static_cast<std::size_t>(brdf.orders());
    ASSERT_GE(orders, 2U);
    std::vector<double> c(orders * bands);
    std::vector<double> f(bands);
    int compared = 0;
    for (const double theta_i : {5.0, 45.0, 80.0})
        for (const double theta_o : {0.0, 30.0, 70.0}) {
            brdf.fourierCoefficients(std::cos(theta_i * std::numbers::pi / 180.0),
                                     std::cos(theta_o * std::numbers::pi / 180.0), c);
            for (const double phi : {0.0, 60.0, 135.0, 180.0}) {
                brdf.eval(directionFromAnglesDeg(theta_i, 0.0), directionFromAnglesDeg(theta_o, phi), f);
                const double dphi = phi * std::numbers::pi / 180.0;
                for (std::size_t b = 0; b < bands; ++b) {
                    double sum = 0.0;
                    for (std::size_t m = 0; m < orders; ++m)
                        sum += c[m * bands + b] * std::cos(double(m) * dphi);
                    if (sum <= 0.0) continue;  // eval() clips there
                    EXPECT_NEAR(sum, f[b], 1e-12 * f[b] + 1e-15) << theta_i << " " << theta_o << " " << phi;
                    ++compared;
                }
            }
        }
    EXPECT_GT(compared, 100);
    // Below the horizon there is nothing.
    brdf.fourierCoefficients(0.5, -0.1, c);
    for (const double x : c) EXPECT_EQ(x, 0.0);
}

// The grid form is the pair-by-pair series reduced by the weights: the same
// sums in another order (round-off, 1e-12), and zero below the horizon.
TEST(FastModelFourier, GridIsThePairwiseSeriesReduced) {
    const Recipe recipe =
        loadRecipeFile(std::filesystem::path(PAINTLAB_DEMO_DIR) / "recipes" / "pearlescent-two-layer.json");
    const LayeredBrdf brdf = computeLayeredBrdf(recipe, presetSettings(Preset::Preview));
    const auto bands = brdf.wavelengthsNm().size();
    const auto orders = static_cast<std::size_t>(brdf.orders());
    const std::vector<double> cos_o{1.0, 0.7, 0.2, -0.1};
    const std::vector<double> cos_i{0.95, 0.5, 0.05};
    Eigen::MatrixXd weights(static_cast<Eigen::Index>(bands), 2);
    for (std::size_t b = 0; b < bands; ++b) {
        weights(static_cast<Eigen::Index>(b), 0) = 1.0 + 0.1 * static_cast<double>(b);
        weights(static_cast<Eigen::Index>(b), 1) = std::sin(static_cast<double>(b));
    }
    std::vector<double> grid(cos_o.size() * cos_i.size() * orders * 2);
    brdf.fourierCoefficientsGrid(cos_o, cos_i, weights, grid);
    std::vector<double> pair(orders * bands);
    for (std::size_t o = 0; o < cos_o.size(); ++o)
        for (std::size_t i = 0; i < cos_i.size(); ++i) {
            brdf.fourierCoefficients(cos_o[o], cos_i[i], pair);
            for (std::size_t m = 0; m < orders; ++m)
                for (Eigen::Index c = 0; c < 2; ++c) {
                    double expected = 0.0;
                    double scale = 0.0;
                    for (std::size_t b = 0; b < bands; ++b) {
                        expected += weights(static_cast<Eigen::Index>(b), c) * pair[m * bands + b];
                        scale += std::abs(weights(static_cast<Eigen::Index>(b), c) * pair[m * bands + b]);
                    }
                    const double got =
                        grid[((o * cos_i.size() + i) * orders + m) * 2 + static_cast<std::size_t>(c)];
                    EXPECT_NEAR(got, expected, 1e-12 * scale + 1e-15) << o << " " << i << " " << m;
                }
        }
    EXPECT_THROW(brdf.fourierCoefficientsGrid(cos_o, cos_i, Eigen::MatrixXd(2, 3), grid), InputError);
}

}  // namespace
}  // namespace paintlab
