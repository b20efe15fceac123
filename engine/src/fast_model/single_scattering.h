#pragma once
// Single scattering of the pigments with their full phase function: the
// "TMS" correction of Nakajima and Tanaka (J. Quant. Spectrosc. Radiat.
// Transfer 40, 51, 1988), as DISORT applies it.
//
// The tables hold the pigments' phase function truncated twice: delta-M keeps
// chi_l for l < N moments (the forward peak f = chi_N becomes unscattered
// light) and the Fourier series keeps orders m < M. Multiple scattering
// hardly notices, but the once-scattered light is the phase function itself
// seen through the slab, and a sharp lobe (g >= 0.75) truncated to N terms is
// wrong by tens of percent away from its peak, even negative. So, for light
// that reaches a slab and leaves it again without meeting anything but the
// slabs' extinction and the interfaces' Fresnel transmission, the
// once-scattered radiance is computed in closed form at the exact directions
// with the true phase function, and the truncated one the table holds is
// taken away:
//   Delta f = T_path (n_ambient/n)^2 [sigma_s p(Theta) - (1 - f) sigma_s p*_{N,M}(Theta)] / (4 pi)
//             x (1 - exp(-d K)) / (mu_i mu_o K),    K = e(mu_i)/mu_i + e(mu_o)/mu_o,
// with the delta-M-scaled extinction e of the tables (so the forward peak's
// light stays where the tables put it). Light reflected by the substrate or
// by flakes before or after the scattering event is left to the tables.

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/layer_optics.h"

#include <span>
#include <vector>

namespace paintlab::fast {

// One slab of pigment on the light's direct path.
struct PathSlab {
    double index = 1.0;
    double thickness_um = 0.0;
    double sigma_s_per_um = 0.0;             // the pigments' scattering, untruncated
    double pigment_extinction_per_um = 0.0;  // sigma_a + (1 - f) sigma_s
    // The flakes' extinction at cosines k / (size - 1) in the slab's medium (empty: no flakes).
    std::vector<double> flake_extinction_per_um;
    std::vector<PhaseLobe> lobes;  // the true phase function
    std::vector<double> chi;       // the delta-M-scaled moments of the tables
    double truncated = 0.0;        // f

    double extinctionPerUm(double mu) const;
};

class SingleScatteringCorrection {
public:
    // The slabs of the recipe at this wavelength, with the moments and the
    // number of Fourier orders the tables were computed with.
    SingleScatteringCorrection(const Recipe& recipe, double wavelength_nm, const FastModelSettings& settings,
                               int table_orders);

    // No slab scatters: the correction is zero.
    bool empty() const { return m_slabs.empty(); }

    // Exact minus truncated single scattering (1/sr) between ambient
    // directions with cosines mu_i, mu_o and azimuths phi_o - phi_i = dphi.
    double operator()(double mu_i, double mu_o, double dphi) const;

    // Its azimuthal Fourier coefficients, with the weights of
    // LayeredBrdf::fourierCoefficients (f = sum_m out[m] cos(m dphi)), for
    // m < out.size(), by a midpoint rule in dphi fine enough for them.
    void fourierCoefficients(double mu_i, double mu_o, std::span<double> out) const;

private:
    double m_ambient_index = 1.0;
    std::vector<PathSlab> m_slabs;
    int m_table_orders = 0;
};

}  // namespace paintlab::fast
