#pragma once
// MaterialX documents with an OpenPBR surface (issue 29): the materialx
// plugin's format.
//
// One `open_pbr_surface` node (OpenPBR 1.x input names, MaterialX 1.39's
// `libraries/bxdf/open_pbr_surface.mtlx`) and one `surfacematerial` using
// it, colour space lin_rec709 (linear sRGB). Its values are the glTF
// material fitted to the fast model (engine approx/material_fit.h), mapped:
//   base_weight 1, base_color, base_metalness, base_diffuse_roughness 0
//     (Lambertian, as glTF's diffuse);
//   specular_roughness = glTF roughness (both alpha = roughness^2, GGX);
//   the dielectric's normal reflectance per channel, glTF's
//     specular * min(f0(ior) specularColor, 1), kept exactly: specular_ior
//     from its largest channel, specular_color the channels relative to
//     it (<= 1), specular_weight 1 (0 when glTF's specular is 0);
//   coat_weight = clearcoat, coat_roughness 0, coat_ior 1.5 (glTF's fixed
//     clear coat index), coat_darkening 0 (glTF's coat does not darken);
//   thin_film_weight = iridescence, thin_film_thickness in micrometres,
//     thin_film_ior = iridescence ior.
// What differs (the ΔE00 reported is the glTF BRDF's with these values, not
// a render of OpenPBR): OpenPBR's specular_weight leaves the grazing
// reflectance at 1 where glTF's specular scales it; its specular_color also
// tints a metal's edge (F82), glTF's metal edge is white; its layering
// conserves energy (the diffuse under the lobe by the lobe's albedo, glTF by
// 1 - F(V.H)); its thin film is the full Airy sum, glTF's a two-term
// spectral approximation.

#include "paintlab/engine/approx/material_fit.h"

#include <string>
#include <string_view>

namespace paintlab::plugins::materialx {

// How the reports name this approximation.
inline constexpr std::string_view kModelName = "OpenPBR (the glTF fit's parameters)";

struct OpenPbr {
    double base_weight = 1.0;
    Rgb base_color{0.8, 0.8, 0.8};
    double base_metalness = 0.0;
    double base_diffuse_roughness = 0.0;
    double specular_weight = 1.0;
    Rgb specular_color{1.0, 1.0, 1.0};
    double specular_roughness = 0.3;
    double specular_ior = 1.5;
    double coat_weight = 0.0;
    double coat_roughness = 0.0;
    double coat_ior = 1.5;
    double coat_darkening = 0.0;
    double thin_film_weight = 0.0;
    double thin_film_thickness_um = 0.5;
    double thin_film_ior = 1.4;
};

OpenPbr openPbrFromGltf(const approx::GltfMaterial& gltf);

// A MaterialX element name from any text: letters, digits and '_' (others
// become '_'), not starting with a digit, never empty.
std::string elementName(std::string_view text);

struct Provenance {
    std::string recipe_name;
    std::string recipe_path;
};

// The .mtlx document (UTF-8 XML).
std::string mtlxText(const OpenPbr& surface, const approx::MaterialFit& fit, const Provenance& provenance);

}  // namespace paintlab::plugins::materialx
