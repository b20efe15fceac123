#pragma once
// The published analytic fits of the MERL materials in shared/data/measured-brdf
// (tables from jdupuy/dj_brdf), implemented from the papers' equations. Both
// are microfacet models, reciprocal by construction, in MERL's scaled RGB
// (taken as linear sRGB, neural_brdf.h). θh, θd: Rusinkiewicz's half and
// difference angles (cos θd = wi·h).
//
// ABC: Low, Kronander, Ynnerman, Unger, "BRDF models for accurate and
// efficient rendering of glossy surfaces", ACM TOG 31(1), 2012, the
// microfacet form with their ABC distribution:
//   f = kD/π + F(θd; ior) D(θh) G / (π cos θi cos θo),
//   D = A / (1 + B (1 - cos θh))^C,
//   G = min(1, 2 cos θh cos θi / cos θd, 2 cos θh cos θo / cos θd) (Cook-Torrance),
//   F the unpolarised Fresnel reflectance of a dielectric of index ior.
// SGD: Bagher, Soler, Holzschuch, "Accurate fitting of measured reflectances
// using a Shifted Gamma micro-facet distribution", CGF 31(4), 2012:
//   f = [ρd + ρs F(θd) D(θh) G1(θi) G1(θo) / (cos θi cos θo)] / π,
//   D = K exp(-a) / (π a^p cos⁴θh), a = α + tan²θh / α (the shifted gamma),
//   F = F0 - F1 cos θd + (1 - F0)(1 - cos θd)^5 (their Schlick extension),
//   G1(θ) = clamp(1 + Λ (1 - exp(c (θ - θ0)^k)), 0, 1) for θ > θ0, else 1
//   (θ in radians; the table's kap, lambda, c, k, theta0 are K, Λ, c, k, θ0).

#include "paintlab/measured_brdf/rgb_brdf.h"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace paintlab::measured {

struct AbcParameters {
    std::string name;
    RgbValue kD{};
    RgbValue A{};
    double B = 0.0;
    double C = 0.0;
    double ior = 1.5;
};

struct SgdParameters {
    std::string name;
    RgbValue rho_d{}, rho_s{}, alpha{}, p{}, f0{}, f1{}, kap{}, lambda{}, c{}, k{}, theta0{};
};

class AbcBrdf final : public RgbBrdf {
public:
    explicit AbcBrdf(AbcParameters parameters) : m_p(std::move(parameters)) {}
    const std::string& name() const override { return m_p.name; }
    RgbValue eval(const Direction& wi, const Direction& wo) const override;

private:
    AbcParameters m_p;
};

class SgdBrdf final : public RgbBrdf {
public:
    explicit SgdBrdf(SgdParameters parameters) : m_p(std::move(parameters)) {}
    const std::string& name() const override { return m_p.name; }
    RgbValue eval(const Direction& wi, const Direction& wo) const override;

private:
    SgdParameters m_p;
};

// The unpolarised Fresnel reflectance of a dielectric of relative index eta
// for the cosine of the incidence angle (Born & Wolf; total reflection gives 1).
double dielectricFresnel(double cos_theta, double eta);

// The tables (merl_abc_low2012_params.csv, merl_sgd_bagher2012_params.csv):
// lines starting with '#' are comments. Throws InputError naming the file, the
// line and the column for a missing column or a value that is not a number.
std::vector<AbcParameters> loadAbcParameters(const std::filesystem::path& file);
std::vector<SgdParameters> loadSgdParameters(const std::filesystem::path& file);

}  // namespace paintlab::measured
