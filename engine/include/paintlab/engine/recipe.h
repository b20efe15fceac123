#pragma once
// The recipe model: what a paint is made of, independent of how it is
// simulated. A paint = ambient medium above, an ordered list of layers (top
// first), a substrate. Every numeric field is declared in parameters.h; each
// struct exposes its fields through one traversal hook (after Mitsuba 3's
// traverse()) that JSON I/O, validation, the GUI editor and the fitter share:
//
//   template <class Self, class Visitor> static void traverse(Self& self, Visitor& v);
//
// calls v.scalar(decl, double&), v.spectrum(decl, Spectrum&) and
// v.optionalSpectrum(decl, std::optional<Spectrum>&) for each field, where
// Self is the struct or its const version.

#include "paintlab/engine/parameters.h"
#include "paintlab/engine/spectrum.h"

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace paintlab {

// Concentration over depth, as a shape: the local volume fraction at relative
// depth z (0 = top of the layer, 1 = bottom) is volume_fraction * w(z) / mean(w),
// with w piecewise linear through the samples. The mean volume fraction, and
// so the amount of material in the production recipe, does not depend on the shape.
struct DepthProfile {
    std::vector<double> depth;   // strictly increasing, from 0 to 1
    std::vector<double> weight;  // >= 0, not all zero

    double weightAt(double z) const;
    double meanWeight() const;                 // integral of w over [0, 1] (trapezoid rule is exact here)
    double peakRelativeConcentration() const;  // max(w) / mean(w)
    friend bool operator==(const DepthProfile&, const DepthProfile&) = default;
};

// Absorbing and scattering grains, treated as a continuous medium.
struct Pigment {
    static constexpr std::string_view kKind = "pigment";
    std::string name;
    std::string source;  // where the optical data came from
    double volume_fraction = 0.0;
    Spectrum sigma_a_per_um;  // per unit volume fraction, 1/µm
    Spectrum sigma_s_per_um;  // per unit volume fraction, 1/µm
    double hg_g = 0.0;
    double particle_diameter_um = 0.3;
    std::optional<DepthProfile> depth_profile;

    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.scalar(params::kPigmentVolumeFraction, self.volume_fraction);
        v.spectrum(params::kPigmentSigmaA, self.sigma_a_per_um);
        v.spectrum(params::kPigmentSigmaS, self.sigma_s_per_um);
        v.scalar(params::kPigmentHgG, self.hg_g);
        v.scalar(params::kPigmentDiameter, self.particle_diameter_um);
    }
    friend bool operator==(const Pigment&, const Pigment&) = default;
};

// Metal flakes acting as small two-sided mirrors. Reflectance is given
// either directly (a spectrum at normal incidence) or as the metal's complex
// index n + ik (then it follows from Fresnel at every angle): exactly one.
struct MirrorFlake {
    static constexpr std::string_view kKind = "mirror_flake";
    std::string name;
    std::string source;
    double volume_fraction = 0.0;
    double diameter_um = 0.0;
    double diameter_sd_um = 0.0;  // size distribution (the full model's tiles draw it)
    double thickness_um = 0.3;
    double orientation_spread_deg = 0.0;
    std::optional<Spectrum> reflectance;
    std::optional<Spectrum> metal_n;
    std::optional<Spectrum> metal_k;
    std::optional<DepthProfile> depth_profile;

    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.scalar(params::kMirrorVolumeFraction, self.volume_fraction);
        v.scalar(params::kMirrorDiameter, self.diameter_um);
        v.scalar(params::kFlakeDiameterSd, self.diameter_sd_um);
        v.scalar(params::kMirrorThickness, self.thickness_um);
        v.scalar(params::kOrientationSpread, self.orientation_spread_deg);
        v.optionalSpectrum(params::kMirrorReflectance, self.reflectance);
        v.optionalSpectrum(params::kMetalN, self.metal_n);
        v.optionalSpectrum(params::kMetalK, self.metal_k);
    }
    friend bool operator==(const MirrorFlake&, const MirrorFlake&) = default;
};

// Pearlescent flakes: a mica platelet coated on both faces with TiO2.
struct InterferenceFlake {
    static constexpr std::string_view kKind = "interference_flake";
    std::string name;
    std::string source;
    double volume_fraction = 0.0;
    double diameter_um = 0.0;
    double diameter_sd_um = 0.0;  // size distribution (the full model's tiles draw it)
    double orientation_spread_deg = 0.0;
    double mica_thickness_nm = 0.0;
    double mica_thickness_spread_nm = 0.0;
    double tio2_thickness_nm = 0.0;
    double tio2_thickness_spread_nm = 0.0;
    Spectrum mica_refractive_index{1.58};
    Spectrum tio2_refractive_index{2.6};
    std::optional<DepthProfile> depth_profile;

    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.scalar(params::kInterferenceVolumeFraction, self.volume_fraction);
        v.scalar(params::kInterferenceDiameter, self.diameter_um);
        v.scalar(params::kFlakeDiameterSd, self.diameter_sd_um);
        v.scalar(params::kOrientationSpread, self.orientation_spread_deg);
        v.scalar(params::kMicaThickness, self.mica_thickness_nm);
        v.scalar(params::kMicaThicknessSpread, self.mica_thickness_spread_nm);
        v.scalar(params::kTio2Thickness, self.tio2_thickness_nm);
        v.scalar(params::kTio2ThicknessSpread, self.tio2_thickness_spread_nm);
        v.spectrum(params::kMicaIndex, self.mica_refractive_index);
        v.spectrum(params::kTio2Index, self.tio2_refractive_index);
    }
    friend bool operator==(const InterferenceFlake&, const InterferenceFlake&) = default;
};

// A medium given directly by its radiative-transfer parameters, for
// validation against published tables and for labs that measured them.
// It fills the whole layer; its optical thickness replaces thickness_um.
struct RawMedium {
    static constexpr std::string_view kKind = "raw_medium";
    std::string name;
    std::string source;
    Spectrum albedo;
    Spectrum optical_thickness;
    double hg_g = 0.0;

    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.spectrum(params::kRawAlbedo, self.albedo);
        v.spectrum(params::kRawOpticalThickness, self.optical_thickness);
        v.scalar(params::kRawHgG, self.hg_g);
    }
    friend bool operator==(const RawMedium&, const RawMedium&) = default;
};

using Component = std::variant<Pigment, MirrorFlake, InterferenceFlake, RawMedium>;

std::string_view componentKind(const Component& component);
const std::string& componentName(const Component& component);
// Mean volume fraction (0 for a raw medium, which has no concentration).
double componentVolumeFraction(const Component& component);
const std::optional<DepthProfile>* componentDepthProfile(const Component& component);

struct Binder {
    std::string name;
    Spectrum refractive_index{1.5};
    Spectrum absorption_per_um{0.0};

    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.spectrum(params::kBinderIndex, self.refractive_index);
        v.spectrum(params::kBinderAbsorption, self.absorption_per_um);
    }
    friend bool operator==(const Binder&, const Binder&) = default;
};

struct Layer {
    std::string name;
    double thickness_um = 0.0;
    Binder binder;
    std::vector<Component> components;

    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.scalar(params::kLayerThickness, self.thickness_um);
    }
    double totalVolumeFraction() const;
    friend bool operator==(const Layer&, const Layer&) = default;
};

struct LambertianSubstrate {
    static constexpr std::string_view kKind = "lambertian";
    Spectrum albedo;
    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.spectrum(params::kSubstrateAlbedo, self.albedo);
    }
    friend bool operator==(const LambertianSubstrate&, const LambertianSubstrate&) = default;
};

struct MetalSubstrate {
    static constexpr std::string_view kKind = "metal";
    Spectrum n{1.0};
    Spectrum k{0.0};
    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.spectrum(params::kMetalN, self.n);
        v.spectrum(params::kMetalK, self.k);
    }
    friend bool operator==(const MetalSubstrate&, const MetalSubstrate&) = default;
};

struct BlackSubstrate {
    static constexpr std::string_view kKind = "black";
    template <class Self, class Visitor> static void traverse(Self& /*self*/, Visitor& /*v*/) {}
    friend bool operator==(const BlackSubstrate&, const BlackSubstrate&) = default;
};

// A transparent carrier (glass, film) whose medium continues below: light
// leaving the paint downwards is lost, which is what two-sided measurements need.
struct TransparentSubstrate {
    static constexpr std::string_view kKind = "transparent";
    double refractive_index = 1.0;
    template <class Self, class Visitor> static void traverse(Self& self, Visitor& v) {
        v.scalar(params::kSubstrateIndex, self.refractive_index);
    }
    friend bool operator==(const TransparentSubstrate&, const TransparentSubstrate&) = default;
};

using Substrate = std::variant<LambertianSubstrate, MetalSubstrate, BlackSubstrate, TransparentSubstrate>;

std::string_view substrateKind(const Substrate& substrate);

struct Recipe {
    static constexpr int kSchemaVersion = 1;
    std::string name;
    std::string description;
    double ambient_refractive_index = 1.0;
    std::vector<Layer> layers;  // top first
    Substrate substrate = BlackSubstrate{};

    double totalThicknessUm() const;
    friend bool operator==(const Recipe&, const Recipe&) = default;
};

}  // namespace paintlab
