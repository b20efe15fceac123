#pragma once
// Small recipe builders shared by the physics tests (fast model, full model,
// stability), so every test states only the numbers that matter to it.

#include "paintlab/engine/recipe.h"
#include "paintlab/engine/recipe_json.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace paintlab::test {

#ifdef PAINTLAB_DEMO_DIR  // defined for the tests (tests/CMakeLists.txt), not the tools
// A bundled demo recipe by file name without ".json" ("silver-metallic").
inline Recipe demoRecipe(const std::string& name) {
    return loadRecipeFile(std::string(PAINTLAB_DEMO_DIR) + "/recipes/" + name + ".json");
}
#endif

// One layer of the given binder index and thickness over a substrate, in air.
inline Recipe oneLayerRecipe(double n_binder, double thickness_um, Substrate substrate) {
    Recipe r;
    r.name = "test";
    Layer layer;
    layer.name = "layer";
    layer.thickness_um = thickness_um;
    layer.binder.refractive_index = Spectrum(n_binder);
    r.layers = {layer};
    r.substrate = std::move(substrate);
    return r;
}

inline RawMedium rawMedium(double albedo, double tau, double g) {
    RawMedium raw;
    raw.name = "raw";
    raw.albedo = Spectrum(albedo);
    raw.optical_thickness = Spectrum(tau);
    raw.hg_g = g;
    return raw;
}

// sigma_a and sigma_s per unit volume fraction (1/µm).
inline Pigment pigment(double volume_fraction, double sigma_a_per_um, double sigma_s_per_um, double g) {
    Pigment p;
    p.name = "pigment";
    p.volume_fraction = volume_fraction;
    p.sigma_a_per_um = Spectrum(sigma_a_per_um);
    p.sigma_s_per_um = Spectrum(sigma_s_per_um);
    p.hg_g = g;
    return p;
}

// Pearl flakes (TiO2 on mica) of the given size, spread and layer thicknesses;
// thickness spreads 0 unless set afterwards. Non-absorbing: R + T = 1.
inline InterferenceFlake interferenceFlake(double volume_fraction, double diameter_um, double spread_deg,
                                           double mica_nm, double tio2_nm) {
    InterferenceFlake flake;
    flake.name = "pearl";
    flake.volume_fraction = volume_fraction;
    flake.diameter_um = diameter_um;
    flake.orientation_spread_deg = spread_deg;
    flake.mica_thickness_nm = mica_nm;
    flake.tio2_thickness_nm = tio2_nm;
    return flake;
}

// A small pearlescent for the full model's tests: a 20 µm clear coat (n 1.55)
// over a 10 µm basecoat (n 1.5: an index step between the layers) of blue
// interference flakes (4 %, 12 µm, 12 deg; mica 350 ± 40 nm, TiO2 120 ± 8 nm)
// with the given pigment, over a grey Lambertian base.
inline Recipe smallPearlescent(const Pigment& pigment, double base_albedo) {
    Recipe r = oneLayerRecipe(1.55, 20.0, LambertianSubstrate{Spectrum(base_albedo)});
    Layer base;
    base.name = "basecoat";
    base.thickness_um = 10.0;
    base.binder.refractive_index = Spectrum(1.5);
    InterferenceFlake pearl = interferenceFlake(0.04, 12.0, 12.0, 350.0, 120.0);
    pearl.mica_thickness_spread_nm = 40.0;
    pearl.tio2_thickness_spread_nm = 8.0;
    base.components = {pearl, pigment};
    r.layers.push_back(base);
    return r;
}

// Flakes 15 µm across and 0.5 µm thick with a normal-incidence reflectance.
inline MirrorFlake mirrorFlake(double volume_fraction, double spread_deg, double reflectance) {
    MirrorFlake flake;
    flake.name = "mirror";
    flake.volume_fraction = volume_fraction;
    flake.thickness_um = 0.5;
    flake.diameter_um = 15.0;
    flake.orientation_spread_deg = spread_deg;
    flake.reflectance = Spectrum(reflectance);
    return flake;
}

// The hiding effect of horizontal disk flakes (diameter d, area density A per
// unit depth, Poisson placed) that the two-stream (independent flakes) value
// leaves out: over the first ~d / (2 tan theta) above a flake, the ray it
// reflects crosses space the incident ray found empty. For two straight rays
// meeting at a reflection at polar angle theta, the expected number of disks
// both would cross is (A / (pi a^2)) int_0^inf lens(2 s tan theta) ds with
// lens(delta) the overlap of two disks of radius a = d / 2 at distance delta
// (int_0^2a lens = 8 a^3 / 3), so the round trip's optical depth is smaller by
//   dtau = 2 A d / (3 pi tan theta)
// (0.017 for the 2 µm flakes at A = 0.04 / µm and 45 deg: measured +1.3 % in the
// albedo, of which single reflections are most). As an allowance on a value
// (mostly single reflections): value (exp(dtau) - 1). mu = cos theta.
inline double hidingAllowance(double value, double area_density_per_um, double diameter_um, double mu) {
    const double tan_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu)) / mu;
    if (!(tan_theta > 0.0)) return 0.0;
    const double dtau = 2.0 * area_density_per_um * diameter_um / (3.0 * 3.14159265358979323846 * tan_theta);
    return value * (std::exp(dtau) - 1.0);
}

// Albedo of horizontal mirror flakes (reflectance R_f at the beam's cosine,
// area density A per µm) in an index-matched layer X µm thick over black:
// at normal incidence a reflected ray retraces its own column, so the
// covered share of a Poisson field of flakes, R_f (1 - exp(-A X)), whatever
// their sizes; oblique, the flakes a ray meets are independent and the
// albedo is the two-stream (Kubelka-Munk) value with S = A R_f, K = A (1 - R_f).
inline double horizontalMirrorAlbedo(bool normal_incidence, double R_f, double area_density_per_um,
                                     double thickness_um) {
    const double A = area_density_per_um;
    const double X = thickness_um;
    if (normal_incidence) return R_f * (1.0 - std::exp(-A * X));
    const double S = A * R_f, K = A * (1.0 - R_f);
    const double ka = (S + K) / S, kb = std::sqrt(ka * ka - 1.0);
    return std::sinh(kb * S * X) / (ka * std::sinh(kb * S * X) + kb * std::cosh(kb * S * X));
}

}  // namespace paintlab::test
