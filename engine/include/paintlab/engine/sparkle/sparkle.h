#pragma once
// Sparkle: the glints of individual flakes (issue 7). The fast model's BRDF
// is the mean over many flakes; a surface element seen by one pixel holds a
// finite number, and only those whose normal lies within the angular
// resolution of light and eye around the half vector glint. This file gives
// the statistics of that count and its radiance; sparkle_texture.h draws a
// texture from them. Inside the flakes' layer (primes: refracted into the
// binder, n_r = n / n0):
//
//   rho = A / a_f (flakes per volume; A area per volume, a_f = pi d^2 / 4),
//   h' = (wi' + wo') / |.|, c_d = wi' . h',
//   Omega_w' = Omega_L mu_i / (n_r^2 mu_i') + Omega_V mu_o / (n_r^2 mu_o') + pi (2 beta)^2
//     (light + eye refracted into the binder, widened by the flake's own
//     lobe beta; Gaussian profiles add their variances),
//   Omega_h' = Omega_w' / (4 c_d) (Walter et al., EGSR 2007, eq. 14),
//   A_el = max(element area, a_f c_d / mu_o') (a flake larger than the element covers it).
//
//   Lambda = rho A_el D(h'_z) Omega_h' H                                    (1)
//   L_g(z) = E U_i U_o (mu_i / mu_i') R(c_d) / Omega_w' * a_f c_d / (mu_o' A_el) * w(z),
//   w(z) = exp(-sigma_e z), sigma_e = sigma_t(mu_i') / mu_i' + sigma_t(mu_o') / mu_o'  (2)
//   E[S] = E mu_i f_flake, f_flake = sum over slices of U_i U_o K / (mu_i' mu_o') int_0^H w dz,
//   K = A R(c_d) D(h'_z) / 4                                                (3)
//   Var[S] / E[S]^2 = E[w^2] / (Lambda E[w]^2)                              (4)
//
// Lambda is the Poisson mean of glinting flakes in a depth slice of height H
// (D: flake_orientation.h), L_g the radiance of one glint at depth z (E the
// light's irradiance, R the flake reflectance (thin_film.h), U_i and U_o the
// flux and radiance transmittances of the exit chain (mc_stack.h), sigma_t
// the fast model's extinction). (3) is the fast model's single-scattering
// flake term, so the texture moves energy between elements without creating
// it; (4) is the sparkle's contrast.
//
// Units: lengths in µm, solid angles in sr, radiance per unit irradiance in 1/sr.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/recipe.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace paintlab {

struct SparkleSettings {
    int bands = 16;                     // wavelengths, evenly over 380-780 nm
    int slices_per_profiled_layer = 4;  // depth slices of a layer whose flakes vary in depth
    int chain_nodes = 91;               // ambient polar angles of the exit-chain table (uniform in theta)
    // Cosines at which interference flakes' R and T are tabulated (evenly
    // over 0..1, linear in between): the full model's 257 by default; the
    // effect planner's quick estimate takes fewer (its thin-film work is most
    // of a plan's time).
    int flake_table_cosines = 257;
    // beta: the spread of one flake's own normals (degrees, in the binder):
    // sets how many flakes share a glint, not the BRDF. 1 deg is an assumption
    // for wavy milled aluminium, not a measurement; 0: plane mirrors.
    double flake_lobe_deg = 1.0;
};

// What the viewer and the light resolve at one surface element. Directions in
// the paint's local frame (z = normal); for a texture that stays put when the
// view turns, the frame's tangent must depend on the surface only (not on the view).
struct SparkleGeometry {
    Direction wi;                   // towards the light (unit, z > 0)
    Direction wo;                   // towards the viewer (unit, z > 0)
    double element_area_um2 = 0.0;  // surface element: pixel footprint on the surface, or eyeElementAreaUm2
    double light_solid_angle_sr = 0.0;  // the light's angular size (sun: 6.8e-5 sr); 0 for a point
    double view_solid_angle_sr = 0.0;   // the viewer's aperture seen from the surface (viewApertureSr)
};

// The surface area the eye resolves at a distance: (distance x acuity)^2 / mu_o.
// Normal visual acuity: 1 arcmin (Snellen 20/20).
double eyeElementAreaUm2(double distance_m, double mu_o, double acuity_arcmin = 1.0);
// Solid angle of an aperture (the eye's pupil, ~3 mm in daylight) at a distance.
double viewApertureSr(double distance_m, double aperture_mm = 3.0);

// One (depth slice, flake kind) of the paint at one geometry.
struct SparkleTerm {
    int layer = 0;      // index into Recipe::layers
    int component = 0;  // index into that layer's components
    int slice = 0;      // depth slice within the layer (0 = top)
    double top_um = 0.0, bottom_um = 0.0;
    double diameter_um = 0.0;
    double mean_glints = 0.0;     // Lambda, eq. (1), at the reference band (~560 nm)
    double mean_weight = 1.0;     // E[w] over the slice, eq. (2)
    double mean_weight_sq = 1.0;  // E[w^2]
    double sigma_e_per_um = 0.0;  // the reference band's round-trip extinction, eq. (2)
    double half_slope_x = 0.0;    // h'_x / h'_z, h'_y / h'_z: where the window sits in slope space
    double half_slope_y = 0.0;
    double window_width_rad = 0.0;          // angular diameter of Omega_h': 2 sqrt(Omega_h' / pi)
    std::vector<double> flake_brdf_per_sr;  // this term's share of f_flake, eq. (3), per band
    // L_g(0) / E, eq. (2), per band: one glint at the slice's top (1/sr).
    std::vector<double> glint_radiance_per_irradiance;
    // Eq. (4); 0 when Lambda = 0 (a zero element or angular resolution: no glint
    // is drawn and the element shows the mean).
    double relativeVariance() const;
};

struct SparkleStats {
    std::vector<double> flake_brdf_per_sr;  // f_flake: sum of the terms, per band
    double expected_glints = 0.0;           // sum of Lambda over the terms
    double sparkle_probability = 0.0;       // 1 - exp(-expected_glints): the element holds a glint
    // Var[S] / E[S]^2 of the element's luminance-like sum (band-mean weights).
    double relative_variance = 0.0;
    std::vector<SparkleTerm> terms;
};

// The paint's flakes, tabulated once per recipe (per band: the exit chains
// on a polar grid, each slice's flakes and extinction). Thread safe after construction.
class SparkleModel {
public:
    // Throws InputError if the recipe is invalid (validateRecipe) or a setting is out of range.
    explicit SparkleModel(const Recipe& recipe, const SparkleSettings& settings = {});
    ~SparkleModel();
    SparkleModel(const SparkleModel&) = delete;
    SparkleModel& operator=(const SparkleModel&) = delete;
    SparkleModel(SparkleModel&&) noexcept;
    SparkleModel& operator=(SparkleModel&&) noexcept;

    std::span<const double> wavelengthsNm() const;
    bool hasFlakes() const;  // any flake with a density of normals (spread > 0)
    // The statistics at one element. Never throws; directions below the
    // horizon, a zero element area or a zero angular resolution give no glints
    // (f_flake is still computed).
    SparkleStats evaluate(const SparkleGeometry& geometry) const;
    // The same into `out`, reusing its vectors (a pass over many pixels
    // allocates nothing once they have their size).
    void evaluate(const SparkleGeometry& geometry, SparkleStats& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

// The Poisson mean (1) for given flake numbers: flakes per volume rho, the
// element area, the slice height, the normal density at h' and the window.
// What the full model's explicit flake tile is counted against (tests).
double expectedGlints(double flakes_per_um3, double element_area_um2, double height_um,
                      double normal_pdf_per_sr, double window_sr);

}  // namespace paintlab
