#pragma once
// Henyey-Greenstein phase function on the quadrature grid, per azimuthal
// Fourier order m, with the delta-M truncation (Wiscombe 1977).
//
// Convention: with p normalised to a 4 pi average of 1 and
//   p(cos Theta) = sum_m (2 - delta_m0) h^m(mu, mu') cos(m (phi - phi')),
//   h^m(mu, mu') = sum_{l=m}^{L-1} (2l + 1) chi_l Lambda_l^m(mu) Lambda_l^m(mu'),
// Lambda_l^m = sqrt((l-m)!/(l+m)!) P_l^m (the semi-normalised associated Legendre
// function), every Fourier order obeys the same equation
//   mu dL^m/dtau = -L^m + (albedo/2) int_{-1}^{1} h^m(mu, mu') L^m(mu') dmu'
// and (1/2) int h^0 dmu' = 1 (van de Hulst 1980; Prahl 1995, redistribution function).

#include <Eigen/Dense>

#include <span>
#include <vector>

namespace paintlab::layered {

// Legendre moments chi_l (l = 0 .. n_moments-1) of the delta-M scaled HG function,
// and the scaling of the medium (Wiscombe 1977):
//   f = g^L, chi*_l = (g^l - f) / (1 - f), tau* = (1 - albedo f) tau,
//   albedo* = albedo (1 - f) / (1 - albedo f).
struct DeltaMPhase {
    std::vector<double> chi;  // chi*_l
    double f = 0.0;           // fraction of the forward peak moved into the unscattered beam
    double scaledAlbedo(double albedo) const;
    double scaledTau(double albedo, double tau) const;  // tau may be +infinity
};

// n_moments >= 1; g in (-1, 1). Never throws.
DeltaMPhase henyeyGreensteinDeltaM(double g, int n_moments);

// h^m between two node sets: same[i][j] = h^m(mu_i, mu_j) (both directions in the same
// hemisphere), opposite[i][j] = h^m(mu_i, -mu_j). Symmetric for one node set.
struct PhaseMatrices {
    Eigen::MatrixXd same;
    Eigen::MatrixXd opposite;
};

PhaseMatrices phaseMatrices(const std::vector<double>& mu, const std::vector<double>& chi, int m);

// The Fourier terms of that series one by one: out[m] = (2 - delta_m0) h^m(mu, mu')
// for m < out.size() (zero from m = chi.size() on).
void phaseFourierOrders(double mu, double mu_prime, const std::vector<double>& chi, std::span<double> out);

// The phase function of moments chi as its first `orders` Fourier orders
// carry it: sum_{m < orders} (2 - delta_m0) h^m(mu, mu') cos(m dphi), for signed
// cosines mu, mu' and the azimuth difference dphi. With orders >= chi.size()
// it is the Legendre series sum_l (2l + 1) chi_l P_l(cos Theta).
double phaseFourierSum(double mu, double mu_prime, double cos_dphi, const std::vector<double>& chi,
                       int orders);

}  // namespace paintlab::layered
