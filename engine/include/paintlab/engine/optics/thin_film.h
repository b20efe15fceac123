#pragma once
// Optics of planar multilayers and of the flakes made from them.
//
// Multilayer: the characteristic-matrix method of Born & Wolf, Principles of
// Optics, 7th ed., sec. 1.6.2-1.6.4 (Macleod, Thin-Film Optical Filters, 4th
// ed., ch. 2, is the same method in admittance form). Time dependence
// exp(-i omega t), complex index n + ik with k >= 0 for absorbing media, the
// same conventions as fresnel.h, so a layer of zero thickness reproduces
// fresnelAmplitudes exactly.
//
// Interference flake (pearlescent pigment): mica platelet coated on both faces
// with TiO2, embedded in the binder (Pfaff, Special Effect Pigments, the
// chapter on pearlescent pigments). Light reaching a flake sees binder / TiO2 / mica / TiO2 / binder.
//
// Never throws; all outputs finite for cos in [0, 1] and thicknesses >= 0.

#include <complex>
#include <span>

namespace paintlab {

struct ThinLayer {
    std::complex<double> n;  // refractive index n + ik, k >= 0
    double thickness_nm = 0.0;
};

// Power reflectance and transmittance per polarisation (s: TE, p: TM).
// Transmittance is the ratio of the normal components of the Poynting vector,
// Born & Wolf sec. 1.6.3; absorptance is 1 - R - T.
struct FilmResponse {
    double Rs = 0.0, Rp = 0.0, Ts = 0.0, Tp = 0.0;
    std::complex<double> rs, rp;                  // amplitude coefficients, same sign convention as fresnel.h
    double R() const { return 0.5 * (Rs + Rp); }  // unpolarised
    double T() const { return 0.5 * (Ts + Tp); }
};

// Reflectance and transmittance of the stack `layers` (first layer faces the
// incident medium) between a non-absorbing incident medium n_incident and an
// exit medium n_exit (may be complex; then T is the power entering it).
// cos_incident: cosine of the angle of incidence in the incident medium,
// clamped to [0, 1]; wavelength_nm in vacuum. At cos_incident = 0: R = 1, T = 0.
FilmResponse multilayerResponse(double n_incident, std::span<const ThinLayer> layers,
                                std::complex<double> n_exit, double cos_incident, double wavelength_nm);

// The pearlescent flake at one wavelength: indices and the thickness
// distributions. Both TiO2 coatings of one flake have the same thickness (they
// grow in one precipitation step, Pfaff); across flakes the mica and the
// TiO2 thickness are independent Gaussians, truncated to positive values.
struct InterferenceFlakeOptics {
    double binder_n = 1.5;
    std::complex<double> mica_n{1.58, 0.0};
    std::complex<double> tio2_n{2.6, 0.0};
    double mica_thickness_nm = 400.0;
    double mica_thickness_spread_nm = 0.0;  // standard deviation
    double tio2_thickness_nm = 100.0;       // each face
    double tio2_thickness_spread_nm = 0.0;  // standard deviation
};

// How the thickness averages are computed (thin_film.cpp derives it). R and
// T are pi-periodic in a lossless layer's phase beta = 2 pi d n cos / lambda,
// where Gauss-Hermite in d converges poorly for wide spreads, so: lossless
// mica is averaged exactly (analytic_mica); other layers fold the Gaussian
// onto one period and take the trapezoid rule on K phases (weakly absorbing
// ones: the same grid without folding); strongly absorbing layers and spreads
// too narrow for the grid take Gauss-Hermite (truncated to d > 0).
struct ThicknessQuadrature {
    // Phases per period K: the largest of min_period_nodes, ln(tolerance) / ln(rho)
    // (rho ~ the largest interface reflection amplitude) and 6.44 / sigma_beta,
    // capped at max_period_nodes. tolerance (the error aimed at in R) is not
    // met within the cap at very grazing incidence (cos < ~0.05).
    int min_period_nodes = 16;
    int max_period_nodes = 256;
    double tolerance = 1e-6;
    // Lossless mica with a spread: averaged analytically (R is a Moebius
    // function of exp(2 i beta_mica), whose Fourier series is geometric) when
    // its mean exceeds ~6.4 spreads. false: always the 2-D quadrature (tests).
    bool analytic_mica = true;
    int gauss_hermite_nodes = 0;       // when Gauss-Hermite is used: 0 = automatic
    bool force_gauss_hermite = false;  // for convergence studies
};

struct FlakeRT {
    double R = 0.0;  // unpolarised reflectance
    double T = 0.0;  // unpolarised transmittance (the light goes on undeviated)
};

// R and T of the flake, averaged over the thickness spreads, for light in the
// binder hitting the flake at a local angle with cosine cos_theta (either face:
// the flake is symmetric).
FlakeRT interferenceFlakeRT(const InterferenceFlakeOptics& flake, double cos_theta, double wavelength_nm,
                            ThicknessQuadrature quadrature = {});

// Tabulates R(cos) and T(cos) at one wavelength on the given cosine grid;
// writes min(cos_grid, R_out, T_out sizes) entries, allocating once per call.
void tabulateInterferenceFlake(const InterferenceFlakeOptics& flake, double wavelength_nm,
                               std::span<const double> cos_grid, std::span<double> R_out,
                               std::span<double> T_out, ThicknessQuadrature quadrature = {});

// Number of Gauss-Hermite nodes that averages exp(i a x) against exp(-x^2)
// to ~1e-6 for the largest round-trip phase spread that matters (the
// fallback quadrature; see thin_film.cpp for the derivation).
// phase_spread_rad: standard deviation of the round-trip phase 4 pi n d cos / lambda.
int gaussHermiteNodesForPhaseSpread(double phase_spread_rad);

// Gauss-Hermite rule for the weight exp(-x^2): integral f(x) exp(-x^2) dx =
// sum w_i f(x_i), exact for polynomials of degree < 2n. n in [1, kMaxGaussHermiteNodes];
// the spans point to static storage (thread-safe, built on first use).
inline constexpr int kMaxGaussHermiteNodes = 96;
struct GaussHermiteRule {
    std::span<const double> x;
    std::span<const double> w;
};
GaussHermiteRule gaussHermiteRule(int n);

// Mirror (metal) flake reflectance at a local angle cos_theta in the binder,
// from the metal's complex index: Fresnel (fresnel.h) from binder_n into metal_n.
double metalFlakeReflectance(double cos_theta, std::complex<double> metal_n, double binder_n);

// Mirror flake reflectance from its reflectance R0 at normal incidence (in
// the binder): Fresnel of an effective metal of relative index 1 + i k_eff,
// k_eff = 2 sqrt(R0 / (1 - R0)), which gives R0 exactly at the normal and
// behaves like a metal (and obeys Fresnel) elsewhere; for aluminium in a 1.5
// binder within 0.035 of the full complex Fresnel. R0 is clamped to [0, 1].
double mirrorFlakeReflectanceFromNormal(double cos_theta, double R0_normal);

}  // namespace paintlab
