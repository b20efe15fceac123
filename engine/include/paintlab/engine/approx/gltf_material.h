#pragma once
// The glTF 2.0 physically based material as a BRDF in linear sRGB (issue 29):
// what a renderer of the glTF ecosystem draws for the parameters the glTF
// exporter writes, evaluated as the specifications define it:
//   - core metallic-roughness: glTF 2.0 specification, Appendix B (GGX /
//     Trowbridge-Reitz D, the height-correlated Smith visibility V, Schlick
//     Fresnel at V.H, material = mix(dielectric_brdf, metal_brdf, metallic));
//   - KHR_materials_ior and KHR_materials_specular (ratified form:
//     f0 = min(((ior-1)/(ior+1))^2 specularColor, 1), the diffuse weighted by
//     1 - specular max(fr), the specular lobe by specular fr);
//   - KHR_materials_iridescence (Belcour & Barla 2017 as the extension's
//     notes give it: Schlick interfaces, phase shifts 0 or pi, the Fourier
//     terms m = 0..2 with the Gaussian fit of the XYZ sensitivities),
//     evaluated at the microfacet's V.H so that the BRDF stays reciprocal;
//   - KHR_materials_clearcoat: fresnel_coat with ior 1.5 at N.V (as the
//     extension defines it; this factor alone is not reciprocal).
// A clear coat of roughness 0 is a mirror (a delta), which eval() excludes as
// SpectralBrdf::eval does; mirrorReflectance() gives it.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/colour.h"

namespace paintlab::approx {

struct GltfMaterial {
    Rgb base_color{1.0, 1.0, 1.0};      // linear sRGB, [0, 1]
    double metallic = 0.0;              // [0, 1]
    double roughness = 1.0;             // perceptual, [0, 1]; alpha = roughness^2
    double ior = 1.5;                   // KHR_materials_ior
    double specular = 1.0;              // KHR_materials_specular specularFactor, [0, 1]
    Rgb specular_color{1.0, 1.0, 1.0};  // specularColorFactor, >= 0
    double clearcoat = 0.0;             // KHR_materials_clearcoat clearcoatFactor, [0, 1]
    double clearcoat_roughness = 0.0;   // [0, 1]; 0: a mirror (mirrorReflectance)
    double iridescence = 0.0;           // KHR_materials_iridescence iridescenceFactor, [0, 1]
    double iridescence_ior = 1.3;
    double iridescence_thickness_nm = 400.0;  // the thickness without a texture (the range's maximum)
};

// f(wi, wo) per linear sRGB channel, 1/sr; the clear coat's mirror excluded
// when its roughness is 0. Directions as brdf.h (z the normal, wo towards the
// viewer); below the horizon: 0. Never throws.
Rgb evalGltf(const GltfMaterial& material, const Direction& wi, const Direction& wo) noexcept;

// The clear coat's mirror reflectance at this cosine (roughness 0 only, else 0):
// clearcoat * (0.04 + 0.96 (1 - cos)^5).
double gltfMirrorReflectance(const GltfMaterial& material, double cos_theta) noexcept;

// The iridescence Fresnel of KHR_materials_iridescence at cos_theta1 (the
// angle in the outside medium) for a film of film_ior and thickness over a
// base of normal reflectance base_f0 (per channel), linear sRGB.
Rgb iridescentFresnel(double outside_ior, double film_ior, const Rgb& base_f0, double thickness_nm,
                      double cos_theta1) noexcept;

}  // namespace paintlab::approx
