#pragma once
// Small recipe builders shared by the physics tests (fast model, full model,
// stability), so every test states only the numbers that matter to it.

#include "paintlab/engine/recipe.h"

#include <utility>

namespace paintlab::test {

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

}  // namespace paintlab::test
