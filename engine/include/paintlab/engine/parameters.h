#pragma once
// Every recipe parameter is declared once, here and in parameters.cpp
// (after F3D's library/options.json): its JSON key, label, unit, allowed
// range, default and typical range. The declarations drive validation, JSON
// I/O, the GUI editor (field + slider), the database and the fitter.
//
// Two ranges per parameter:
// - allowed [min, max]: outside it a recipe is rejected. For concentrations
//   max is the technological maximum (what can be dispersed and still form
//   a film), for the rest it is the physically meaningful range.
// - typical [typicalMin, typicalMax]: what labs normally use; the default
//   slider range in the GUI, and a warning (not an error) when left.

#include <span>
#include <string_view>

namespace paintlab {

struct ParameterDecl {
    std::string_view key;    // JSON key and fitter name, with the unit in it: "thickness_um"
    std::string_view label;  // for people: "Thickness"
    std::string_view unit;   // "µm", "nm", "deg", "1/µm", "1" (dimensionless)
    double min = 0.0;        // allowed range, inclusive unless minExclusive
    double max = 0.0;
    bool minExclusive = false;
    bool required = false;  // if false, defaultValue is used when absent
    double defaultValue = 0.0;
    double typicalMin = 0.0;
    double typicalMax = 0.0;
    std::string_view help;

    bool allows(double value) const noexcept {
        return value == value && (minExclusive ? value > min : value >= min) && value <= max;
    }
    bool isTypical(double value) const noexcept { return value >= typicalMin && value <= typicalMax; }
};

namespace params {
// Paint as a whole.
extern const ParameterDecl kAmbientIndex;
// Layer and its binder.
extern const ParameterDecl kLayerThickness;
extern const ParameterDecl kBinderIndex;
extern const ParameterDecl kBinderAbsorption;
// Shared by concentration-carrying components.
extern const ParameterDecl kOrientationSpread;
// Pigment.
extern const ParameterDecl kPigmentVolumeFraction;
extern const ParameterDecl kPigmentSigmaA;
extern const ParameterDecl kPigmentSigmaS;
extern const ParameterDecl kPigmentHgG;
extern const ParameterDecl kPigmentDiameter;
// Mirror flake.
extern const ParameterDecl kMirrorVolumeFraction;
extern const ParameterDecl kMirrorDiameter;
extern const ParameterDecl kFlakeDiameterSd;  // both flake kinds
extern const ParameterDecl kMirrorThickness;
extern const ParameterDecl kMirrorReflectance;
extern const ParameterDecl kMetalN;
extern const ParameterDecl kMetalK;
// Interference flake (TiO2 / mica / TiO2).
extern const ParameterDecl kInterferenceVolumeFraction;
extern const ParameterDecl kInterferenceDiameter;
extern const ParameterDecl kMicaThickness;
extern const ParameterDecl kMicaThicknessSpread;
extern const ParameterDecl kTio2Thickness;
extern const ParameterDecl kTio2ThicknessSpread;
extern const ParameterDecl kMicaIndex;
extern const ParameterDecl kTio2Index;
// Raw optical medium.
extern const ParameterDecl kRawAlbedo;
extern const ParameterDecl kRawOpticalThickness;
extern const ParameterDecl kRawHgG;
// Substrates.
extern const ParameterDecl kSubstrateAlbedo;
extern const ParameterDecl kSubstrateIndex;
// Depth profile samples.
extern const ParameterDecl kProfileDepth;
extern const ParameterDecl kProfileWeight;
}  // namespace params

// Every declaration above, for documentation, the GUI and tests.
std::span<const ParameterDecl* const> allParameters();

}  // namespace paintlab
