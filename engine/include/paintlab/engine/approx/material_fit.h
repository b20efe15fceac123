#pragma once
// A recipe's fast-model BRDF approximated by the glTF 2.0 material
// (approx/gltf_material.h), for renderers that take glTF or a shading model
// close to it (OpenPBR, plugins/materialx): the parameters fitted by bounded
// least squares (Levenberg-Marquardt, Eigen's header-only module: the
// export plugins must not load Ceres, tests/cli/light_commands.sh) to the BRDF in linear sRGB, and
// what is left, as CIEDE2000 at the six multi-angle geometries.
//
// The fit (docs/ARCHITECTURE.md, "Renderer approximations"):
//   - directions: gltfFitDirections(), theta_i and theta_o in {5, 20, 35, 50,
//     65, 80} degrees with phi_o - phi_i in {0, 30, ..., 180} (252 pairs),
//     plus the plane of incidence at 45° illumination, aspecular -40..130° in
//     5° steps (35 pairs, the multi-angle geometries among them);
//   - residual per pair and channel: ln(0.01 + f_gltf cos_i) - ln(0.01 + f cos_i)
//     (the recipe fit's log residual with a floor of 0.01 1/sr instead of 1,
//     so that a dark flop counts; a target channel below 0, a colour
//     outside the sRGB gamut, counts as 0);
//   - free: base colour, metallic, roughness, specular, specular colour, and
//     for a recipe with interference flakes iridescence factor and thickness
//     (film index: the flakes' TiO2 at 550 nm); 6 starts (3 roughnesses, a
//     metal's or a dielectric's lobe), then 10 film thicknesses; the best kept;
//   - fixed: ior 1.5 (redundant with the specular colour); the clear coat
//     stands for the smooth top interface's mirror term, which eval() of both
//     BRDFs excludes: roughness 0, factor the least-squares match of its
//     Schlick reflectance 0.04 + 0.96 (1 - mu)^5 to the fast model's mirror
//     reflectance (luminance), clamped to [0, 1].

#include "paintlab/engine/approx/gltf_material.h"
#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/colour.h"

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace paintlab {
class LayeredBrdf;
struct Recipe;
}  // namespace paintlab

namespace paintlab::approx {

// The colour difference at one multi-angle geometry (multiangle.h): the
// reference by multiAngleColours (D65, CIE 1931 2°, the conditions of sRGB),
// the approximation's linear sRGB through the exact inverse of the sRGB
// matrix to XYZ, both relative to the same white.
struct GeometryDeltaE {
    double aspecular_deg = 0.0;
    Lab reference;
    Lab approximation;
    double delta_e00 = 0.0;
};

struct MaterialFit {
    GltfMaterial material;
    std::vector<GeometryDeltaE> geometries;  // 45as-15, 15, 25, 45, 75, 110
    double max_delta_e00 = 0.0;
    double mean_delta_e00 = 0.0;
    double rms_log_residual = 0.0;  // over gltfFitDirections() and the channels
    int starts = 0;
    double seconds = 0.0;
};

struct MaterialFitOptions {
    bool iridescence = false;      // fit iridescence factor and thickness
    double iridescence_ior = 1.3;  // the film's index when it is fitted
    double clearcoat = 0.0;        // the clear coat factor (its roughness is 0)
    int max_iterations = 60;       // per start
};

// The stated set of direction pairs (wi, wo) the fit compares at.
std::vector<std::pair<Direction, Direction>> gltfFitDirections();

// An approximation of `reference` (any BRDF in linear sRGB) at the six
// geometries. Throws as multiAngleColours.
std::vector<GeometryDeltaE>
multiAngleDeltaE(const SpectralBrdf& reference,
                 const std::function<Rgb(const Direction& wi, const Direction& wo)>& approximation);

// One line for people: "<model> approximation: max ΔE00 0.81 against the
// fast model (45as-15 0.81, ..., 45as110 0.10, fit 0.17 s)".
std::string deltaESummary(const MaterialFit& fit, std::string_view model);

// Fits the glTF material to a spectral BRDF (no mirror term in it) with the
// options' fixed parts. Throws InputError if the BRDF has fewer than 2
// wavelengths; never for a poor fit (the ΔE00 says how poor).
MaterialFit fitGltfMaterial(const SpectralBrdf& brdf, const MaterialFitOptions& options);

// The options for a recipe (iridescence when a layer holds interference
// flakes) and its fast-model BRDF (the clear coat from its mirror term), then
// fitGltfMaterial.
MaterialFitOptions gltfFitOptions(const Recipe& recipe, const LayeredBrdf& brdf);
MaterialFit fitGltfMaterial(const Recipe& recipe, const LayeredBrdf& brdf);

}  // namespace paintlab::approx
