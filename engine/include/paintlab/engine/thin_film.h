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

// How the thickness averages are computed (thin_film.cpp has the derivation).
// R and T depend on a layer's thickness d only through the phase
// beta = 2 pi d n cos / lambda and are pi-periodic in beta for a non-absorbing
// layer, with harmonics that decay like rho^m, rho ~ the largest interface
// reflection amplitude (slowly near grazing incidence, where rho -> 1).
// Gauss-Hermite in d converges poorly for spreads of a period or more (see the
// convergence test), so by default:
//  - mica (lossless, mean > ~6.4 spreads): exact average over its phase
//    through the geometric Fourier series of R (analytic_mica below);
//  - otherwise, per layer: fold the truncated Gaussian onto one period (the
//    wrapped density) and use the trapezoid rule on K equispaced phases,
//    spectrally accurate for periodic integrands and no costlier for wide
//    spreads than for narrow ones; weakly absorbing layers (|Im| <= 0.1 Re of
//    n cos) use the same grid over the whole Gaussian without folding;
//  - strongly absorbing or evanescent layers, and spreads too narrow for
//    max_period_nodes phases: Gauss-Hermite (truncated to d > 0).
struct ThicknessQuadrature {
    // Phases per period K: the largest of min_period_nodes, ln(tolerance) / ln(rho)
    // (rho ~ largest interface reflection amplitude: harmonics of R decay like
    // rho^m) and 6.44 / sigma_beta (resolves the Gaussian), capped at
    // max_period_nodes. tolerance is the aimed-at error in R; it is not met
    // within the cap at very grazing incidence (cos < ~0.05 with 256 nodes).
    int min_period_nodes = 16;
    int max_period_nodes = 256;
    double tolerance = 1e-6;
    // Lossless mica with a spread: average over its thickness analytically (the
    // flake's R is a Moebius function of exp(2 i beta_mica), whose Fourier series
    // is geometric), leaving a 1-D quadrature over the TiO2 thickness. Used when
    // the mica mean exceeds ~6.4 spreads (else the truncation at 0 makes the 2-D
    // quadrature cheaper). false: always the 2-D quadrature (reference for tests).
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
// writes min(cos_grid, R_out, T_out sizes) entries. Workspace is allocated
// once per call; the loops over cosines and thickness nodes do not allocate.
// Cost per cosine: (active TiO2 nodes) x (a few series terms) with the analytic
// mica average; (active mica nodes) x (active TiO2 nodes) 3-layer products
// without it (~16 x 16 near normal incidence, up to K x K near grazing).
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

// Mirror flake reflectance from a reflectance R0 measured at normal incidence
// (in the binder). The angular dependence is that of an effective metal whose
// index relative to the binder is 1 + i k_eff with k_eff = 2 sqrt(R0 / (1 - R0)),
// the only such index with real part equal to the binder's that gives
// R(normal) = |ik / (2 + ik)|^2 = R0 exactly. It reflects like a metal
// (rises to 1 at grazing with a shallow p-polarised dip) and obeys Fresnel's
// equations, so it stays energy-consistent. For aluminium in a 1.5 binder it
// is within 0.035 of the full complex Fresnel at every angle (Schlick's
// approximation: 0.066). R0 is clamped to [0, 1].
double mirrorFlakeReflectanceFromNormal(double cos_theta, double R0_normal);

}  // namespace paintlab
