#pragma once
// From recipe to optics: the bulk optical properties of a layer (or of one
// depth slice of it) at one wavelength, as the fast and the full model need
// them. Pigments become a continuous absorbing/scattering medium; flakes
// become an area density of oriented reflectors (their optics per angle are
// in thin_film.h and fresnel.h). Units: coefficients in 1/µm, lengths in µm.

#include "paintlab/engine/recipe.h"

#include <complex>
#include <optional>
#include <vector>

namespace paintlab {

// One Henyey-Greenstein lobe of the medium's phase function. A mixture of
// pigments has the phase function sum_k w_k HG(g_k) with w_k = sigma_s_k / sigma_s;
// its Legendre moments are sum_k w_k g_k^l, so the mixture is kept exactly
// rather than collapsed into one HG of the mean g.
struct PhaseLobe {
    double weight = 0.0;  // fraction of the scattering coefficient, sums to 1 over lobes
    double g = 0.0;
};

struct MirrorFlakeContent {
    double area_density_per_um = 0.0;  // flake area (one face) per unit volume, 1/µm
    double orientation_spread_deg = 0.0;
    double diameter_um = 0.0;
    // Either a normal-incidence reflectance or the metal's index (relative
    // indices are formed with the binder index by the optics code).
    std::optional<double> reflectance;
    std::optional<std::complex<double>> metal_index;
};

struct InterferenceFlakeContent {
    double area_density_per_um = 0.0;
    double orientation_spread_deg = 0.0;
    double diameter_um = 0.0;
    double mica_thickness_nm = 0.0;
    double mica_thickness_spread_nm = 0.0;
    double tio2_thickness_nm = 0.0;
    double tio2_thickness_spread_nm = 0.0;
    double mica_index = 1.58;
    double tio2_index = 2.6;
};

// A homogeneous slab: the binder plus everything dispersed in it, at one wavelength.
struct SlabOptics {
    double thickness_um = 0.0;
    double binder_index = 1.5;
    double sigma_a_per_um = 0.0;  // binder + pigment absorption
    double sigma_s_per_um = 0.0;  // pigment scattering
    std::vector<PhaseLobe> lobes;
    std::vector<MirrorFlakeContent> mirror_flakes;
    std::vector<InterferenceFlakeContent> interference_flakes;

    double sigmaT() const noexcept { return sigma_a_per_um + sigma_s_per_um; }
    double albedo() const noexcept;            // single-scattering albedo of the continuous medium
    double opticalThickness() const noexcept;  // of the continuous medium, tau = sigma_t * thickness
    double meanCosine() const noexcept;        // asymmetry g of the lobe mixture
};

// The slab [z0, z1] (relative depth, 0 = top, 1 = bottom) of a layer at one
// wavelength. Each component's concentration is its exact mean over the slab
// (profiles are piecewise linear, so the integral is exact).
// A raw medium contributes its optical thickness in proportion to the slab's share.
SlabOptics slabOptics(const Layer& layer, double wavelength_nm, double z0 = 0.0, double z1 = 1.0);

// Depth boundaries that split a layer into homogeneous-enough slices: the
// layer itself if no component has a depth profile, else slice_count equal
// slices. Returned as slice_count + 1 relative depths from 0 to 1.
std::vector<double> sliceBoundaries(const Layer& layer, int slice_count);

// Mean of a depth profile's relative concentration w(z)/mean(w) over [z0, z1]
// (1 for no profile). Exact for piecewise-linear profiles.
double meanRelativeConcentration(const std::optional<DepthProfile>& profile, double z0, double z1);

}  // namespace paintlab
