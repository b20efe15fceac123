#include "paintlab/engine/parameters.h"

#include <array>

// Values: allowed ranges are physical (an index below 1 in a dielectric,
// an albedo above 1) or technological (concentrations). Typical ranges are
// what automotive and industrial coatings use; sources per group below.
namespace paintlab::params {

// Air by default; 1.33 lets a lab model a sample measured under water.
const ParameterDecl kAmbientIndex{"refractive_index", "Ambient refractive index", "1", 1.0, 3.0, false, false,
                                  1.0, 1.0, 1.5, "Real refractive index of the medium above the paint"};

// Automotive films: e-coat ~20 µm, primer ~35 µm, basecoat 12-25 µm, clear
// coat 35-50 µm (e.g. Streitberger & Dössel, Automotive Paints and Coatings, 2008).
const ParameterDecl kLayerThickness{"thickness_um", "Thickness", "µm", 0.0, 5000.0, true, true,
                                    0.0, 1.0, 100.0, "Dry film thickness of the layer"};
// Cured binders (acrylic, polyurethane, polyester) have n ~1.45-1.6 in the visible.
const ParameterDecl kBinderIndex{"refractive_index", "Binder refractive index", "1", 1.0, 3.0, false, false,
                                 1.5, 1.4, 1.7, "Real refractive index of the cured binder"};
const ParameterDecl kBinderAbsorption{"absorption_per_um", "Binder absorption", "1/µm", 0.0, 10.0, false, false,
                                      0.0, 0.0, 0.05, "Absorption coefficient of the clear binder"};

const ParameterDecl kOrientationSpread{"orientation_spread_deg", "Orientation spread", "deg", 0.0, 90.0, false,
                                       true, 0.0, 2.0, 30.0,
                                       "Standard deviation of the flake normal's angle to the surface normal"};

// Pigment volume concentration: the critical PVC of most systems is 0.5-0.6;
// random close packing of spheres (0.64) bounds it physically.
const ParameterDecl kPigmentVolumeFraction{"volume_fraction", "Pigment volume fraction", "1", 0.0, 0.64, false,
                                           true, 0.0, 0.0, 0.3, "Mean volume fraction of pigment in the film"};
// Coefficients per unit volume fraction: a layer with volume fraction c has
// sigma_a = c * sigma_a_per_um. Carbon black reaches ~100/µm, TiO2 scattering ~10/µm.
const ParameterDecl kPigmentSigmaA{"sigma_a_per_um", "Absorption per unit volume fraction", "1/µm", 0.0, 1000.0,
                                   false, true, 0.0, 0.0, 100.0,
                                   "Spectral absorption coefficient at volume fraction 1"};
const ParameterDecl kPigmentSigmaS{"sigma_s_per_um", "Scattering per unit volume fraction", "1/µm", 0.0, 1000.0,
                                   false, true, 0.0, 0.0, 100.0,
                                   "Spectral scattering coefficient at volume fraction 1"};
const ParameterDecl kPigmentHgG{"hg_g", "Henyey-Greenstein g", "1", -0.999, 0.999, false, false, 0.0, -0.3, 0.9,
                                "Mean cosine of the scattering angle"};
const ParameterDecl kPigmentDiameter{"particle_diameter_um", "Particle diameter", "µm", 0.0, 100.0, true, false,
                                     0.3, 0.02, 2.0, "Mean pigment particle diameter"};

// Aluminium flakes: 5-50 µm across, 0.05-1 µm thick, a few % to ~20 % by
// volume in a basecoat (Wissling, Metallic Effect Pigments, 2006).
const ParameterDecl kMirrorVolumeFraction{"volume_fraction", "Flake volume fraction", "1", 0.0, 0.3, false, true,
                                          0.0, 0.0, 0.15, "Mean volume fraction of flakes in the film"};
const ParameterDecl kMirrorDiameter{"diameter_um", "Flake diameter", "µm", 0.0, 200.0, true, true, 0.0, 5.0, 50.0,
                                    "Mean flake diameter"};
const ParameterDecl kMirrorThickness{"thickness_um", "Flake thickness", "µm", 0.0, 5.0, true, false, 0.3, 0.05,
                                     1.0, "Flake thickness (sets flake count per volume fraction)"};
const ParameterDecl kMirrorReflectance{"reflectance", "Flake reflectance", "1", 0.0, 1.0, false, false, 0.9, 0.3,
                                       1.0, "Spectral reflectance of the flake surface at normal incidence"};
const ParameterDecl kMetalN{"n", "Metal refractive index n", "1", 0.01, 20.0, false, false, 1.0, 0.05, 5.0,
                            "Real part of the metal's complex refractive index"};
const ParameterDecl kMetalK{"k", "Metal extinction coefficient k", "1", 0.0, 50.0, false, false, 0.0, 1.0, 10.0,
                            "Imaginary part of the metal's complex refractive index"};

// Pearlescent pigments: mica platelets 200-600 nm thick coated with 40-200 nm
// of TiO2, 5-60 µm across (Pfaff, Special Effect Pigments, 2008).
const ParameterDecl kInterferenceVolumeFraction{
    "volume_fraction", "Flake volume fraction", "1", 0.0, 0.3, false, true, 0.0, 0.0, 0.15,
    "Mean volume fraction of interference flakes in the film"};
const ParameterDecl kInterferenceDiameter{"diameter_um", "Flake diameter", "µm", 0.0, 200.0, true, true, 0.0, 5.0,
                                          60.0, "Mean flake diameter"};
const ParameterDecl kMicaThickness{"mica_thickness_nm", "Mica thickness", "nm", 10.0, 2000.0, false, true, 0.0,
                                   200.0, 800.0, "Mean thickness of the mica platelet"};
const ParameterDecl kMicaThicknessSpread{"mica_thickness_spread_nm", "Mica thickness spread", "nm", 0.0, 1000.0,
                                         false, false, 0.0, 0.0, 150.0,
                                         "Standard deviation of the mica thickness"};
const ParameterDecl kTio2Thickness{"tio2_thickness_nm", "TiO2 coating thickness", "nm", 0.0, 1000.0, false, true,
                                   0.0, 40.0, 200.0, "Mean thickness of each TiO2 coating"};
const ParameterDecl kTio2ThicknessSpread{"tio2_thickness_spread_nm", "TiO2 thickness spread", "nm", 0.0, 500.0,
                                         false, false, 0.0, 0.0, 30.0,
                                         "Standard deviation of the TiO2 coating thickness"};
// Muscovite mica n ~1.58-1.60 (handbook value); rutile TiO2 n ~2.6-2.9 in the visible (Devore 1951).
const ParameterDecl kMicaIndex{"mica_refractive_index", "Mica refractive index", "1", 1.3, 2.0, false, false,
                               1.58, 1.55, 1.62, "Spectral refractive index of the mica"};
const ParameterDecl kTio2Index{"tio2_refractive_index", "TiO2 refractive index", "1", 1.8, 3.5, false, false, 2.6,
                               2.2, 3.1, "Spectral refractive index of the TiO2 coating"};

const ParameterDecl kRawAlbedo{"albedo", "Single-scattering albedo", "1", 0.0, 1.0, false, true, 0.0, 0.0, 1.0,
                               "Scattering / extinction"};
const ParameterDecl kRawOpticalThickness{"optical_thickness", "Optical thickness", "1", 0.0, 1.0e4, false, true,
                                         0.0, 0.0, 50.0, "Extinction integrated over the layer thickness"};
const ParameterDecl kRawHgG{"hg_g", "Henyey-Greenstein g", "1", -0.999, 0.999, false, false, 0.0, -0.5, 0.95,
                            "Mean cosine of the scattering angle"};

const ParameterDecl kSubstrateAlbedo{"albedo", "Substrate albedo", "1", 0.0, 1.0, false, true, 0.0, 0.0, 1.0,
                                     "Spectral albedo of the Lambertian substrate"};
const ParameterDecl kSubstrateIndex{"refractive_index", "Medium below", "1", 1.0, 3.0, false, true, 1.0, 1.0,
                                    1.8, "Real refractive index of the transparent medium below the paint"};

const ParameterDecl kProfileDepth{"depth", "Relative depth", "1", 0.0, 1.0, false, true, 0.0, 0.0, 1.0,
                                  "0 at the top of the layer, 1 at the bottom"};
const ParameterDecl kProfileWeight{"weight", "Relative concentration", "1", 0.0, 1.0e3, false, true, 1.0, 0.0,
                                   10.0, "Shape of the concentration over depth; normalised to mean 1"};

} // namespace paintlab::params

namespace paintlab {

std::span<const ParameterDecl* const> allParameters() {
    using namespace params;
    static const std::array<const ParameterDecl*, 31> all{
        &kAmbientIndex,        &kLayerThickness,       &kBinderIndex,
        &kBinderAbsorption,    &kOrientationSpread,    &kPigmentVolumeFraction,
        &kPigmentSigmaA,       &kPigmentSigmaS,        &kPigmentHgG,
        &kPigmentDiameter,     &kMirrorVolumeFraction, &kMirrorDiameter,
        &kMirrorThickness,     &kMirrorReflectance,    &kMetalN,
        &kMetalK,              &kInterferenceVolumeFraction, &kInterferenceDiameter,
        &kMicaThickness,       &kMicaThicknessSpread,  &kTio2Thickness,
        &kTio2ThicknessSpread, &kMicaIndex,            &kTio2Index,
        &kRawAlbedo,           &kRawOpticalThickness,  &kRawHgG,
        &kSubstrateAlbedo,     &kSubstrateIndex,       &kProfileDepth,
        &kProfileWeight};
    return all;
}

} // namespace paintlab
