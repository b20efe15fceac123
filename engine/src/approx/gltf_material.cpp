// The glTF 2.0 material's BRDF (approx/gltf_material.h). Equations: glTF 2.0
// specification, Appendix B.3 (specular_brdf = V D, D of Trowbridge-Reitz,
// V the height-correlated Smith visibility of Heitz 2014), B.2 (fresnel_mix,
// conductor_fresnel); the KHR_materials_specular, _clearcoat and
// _iridescence extension texts for the rest.

#include "paintlab/engine/approx/gltf_material.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace paintlab::approx {

namespace {

constexpr double kPi = std::numbers::pi;

double schlick(double f0, double cos_theta) noexcept {
    const double m = std::clamp(1.0 - cos_theta, 0.0, 1.0);
    const double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

double iorToF0(double transmitted, double incident) noexcept {
    const double r = (transmitted - incident) / (transmitted + incident);
    return r * r;
}

// specular_brdf(alpha) = V D (Appendix B.3.2, B.3.3), 1/sr.
double specularBrdf(double alpha, double n_dot_l, double n_dot_v, double n_dot_h) noexcept {
    if (alpha <= 0.0 || n_dot_h <= 0.0) return 0.0;
    const double a2 = alpha * alpha;
    const double t = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    const double d = a2 / (kPi * t * t);
    const double gl = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    const double gv = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    const double denominator = gl + gv;
    return denominator > 0.0 ? 0.5 / denominator * d : 0.0;
}

// The XYZ sensitivity's Fourier transform at optical path difference opd_nm
// with phase shift `shift` per component, as linear sRGB (Belcour & Barla
// 2017, section 4: a Gaussian fit of the CIE functions, normalised to 1 at 0).
Rgb sensitivity(double opd_nm, const std::array<double, 3>& shift) noexcept {
    const double phase = 2.0 * kPi * opd_nm * 1.0e-9;
    constexpr std::array<double, 3> kValue{5.4856e-13, 4.4201e-13, 5.2481e-13};
    constexpr std::array<double, 3> kPosition{1.6810e+06, 1.7953e+06, 2.2084e+06};
    constexpr std::array<double, 3> kVariance{4.3278e+09, 9.3046e+09, 6.6121e+09};
    std::array<double, 3> xyz{};
    for (std::size_t k = 0; k < 3; ++k)
        xyz[k] = kValue[k] * std::sqrt(2.0 * kPi * kVariance[k]) * std::cos(kPosition[k] * phase + shift[k]) *
                 std::exp(-phase * phase * kVariance[k]);
    // The second lobe of x-bar (its blue bump).
    constexpr double kXValue = 9.7470e-14;
    constexpr double kXPosition = 2.2399e+06;
    constexpr double kXVariance = 4.5282e+09;
    xyz[0] += kXValue * std::sqrt(2.0 * kPi * kXVariance) * std::cos(kXPosition * phase + shift[0]) *
              std::exp(-kXVariance * phase * phase);
    constexpr double kNormalisation = 1.0685e-7;
    return xyzToLinearSrgb({xyz[0] / kNormalisation, xyz[1] / kNormalisation, xyz[2] / kNormalisation});
}

double channel(const Rgb& c, std::size_t k) noexcept { return k == 0 ? c.r : (k == 1 ? c.g : c.b); }
double& channel(Rgb& c, std::size_t k) noexcept { return k == 0 ? c.r : (k == 1 ? c.g : c.b); }
double maxChannel(const Rgb& c) noexcept { return std::max({c.r, c.g, c.b}); }

}  // namespace

Rgb iridescentFresnel(double outside_ior, double film_ior, const Rgb& base_f0, double thickness_nm,
                      double cos_theta1) noexcept {
    // First interface (outside -> film), Schlick at theta1.
    const double r12 = schlick(iorToF0(film_ior, outside_ior), cos_theta1);
    const double t121 = 1.0 - r12;
    const double sin2_sq =
        (outside_ior / film_ior) * (outside_ior / film_ior) * (1.0 - cos_theta1 * cos_theta1);
    const double cos2_sq = 1.0 - sin2_sq;
    if (cos2_sq < 0.0) return {1.0, 1.0, 1.0};  // total internal reflection
    const double cos2 = std::sqrt(cos2_sq);
    const double phi12 = film_ior < outside_ior ? kPi : 0.0;
    const double phi21 = kPi - phi12;
    const double opd_nm = 2.0 * film_ior * thickness_nm * cos2;
    Rgb r23;
    std::array<double, 3> phi{};
    for (std::size_t k = 0; k < 3; ++k) {
        // The base's index from its normal reflectance, as if a dielectric
        // (the extension's approximation for metals too); f0 below 1.
        const double s = std::sqrt(std::clamp(channel(base_f0, k), 0.0, 0.9998) + 1e-4);
        const double base_ior = (1.0 + s) / (1.0 - s);
        channel(r23, k) = schlick(iorToF0(base_ior, film_ior), cos2);
        phi[k] = phi21 + (base_ior < film_ior ? kPi : 0.0);
    }
    // Per channel: the m = 0 term (the incoherent sum) and the amplitude of
    // the terms m = 1, 2 (pairs of Diracs in the Fourier domain).
    Rgb f;
    Rgb cm;
    Rgb r123_root;
    for (std::size_t k = 0; k < 3; ++k) {
        const double r123 = std::clamp(r12 * channel(r23, k), 1e-5, 0.9999);
        const double rs = t121 * t121 * channel(r23, k) / (1.0 - r123);
        channel(f, k) = r12 + rs;
        channel(cm, k) = rs - t121;
        channel(r123_root, k) = std::sqrt(r123);
    }
    for (int m = 1; m <= 2; ++m) {
        const std::array<double, 3> shift{m * phi[0], m * phi[1], m * phi[2]};
        const Rgb sm = sensitivity(m * opd_nm, shift);
        for (std::size_t k = 0; k < 3; ++k) {
            channel(cm, k) *= channel(r123_root, k);
            channel(f, k) += channel(cm, k) * 2.0 * channel(sm, k);
        }
    }
    return {std::max(f.r, 0.0), std::max(f.g, 0.0), std::max(f.b, 0.0)};
}

Rgb evalGltf(const GltfMaterial& mat, const Direction& wi, const Direction& wo) noexcept {
    const double n_dot_l = wi.z;
    const double n_dot_v = wo.z;
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) return {};
    Direction h{wi.x + wo.x, wi.y + wo.y, wi.z + wo.z};
    const double length = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
    if (length <= 0.0) return {};
    h = {h.x / length, h.y / length, h.z / length};
    const double v_dot_h = std::abs(wo.x * h.x + wo.y * h.y + wo.z * h.z);
    const double alpha = mat.roughness * mat.roughness;
    const double lobe = specularBrdf(alpha, n_dot_l, n_dot_v, h.z);

    // Dielectric: KHR_materials_specular's fresnel_mix, iridescence mixed into its weight.
    const double f0_ior = iorToF0(mat.ior, 1.0);
    Rgb f0;
    Rgb weight;
    for (std::size_t k = 0; k < 3; ++k) {
        channel(f0, k) = std::min(f0_ior * channel(mat.specular_color, k), 1.0);
        channel(weight, k) = mat.specular * schlick(channel(f0, k), v_dot_h);
    }
    Rgb metal_fresnel;
    for (std::size_t k = 0; k < 3; ++k)
        channel(metal_fresnel, k) = schlick(channel(mat.base_color, k), v_dot_h);
    if (mat.iridescence > 0.0) {
        const Rgb weighted_f0{mat.specular * f0.r, mat.specular * f0.g, mat.specular * f0.b};
        const Rgb dielectric_film =
            iridescentFresnel(1.0, mat.iridescence_ior, weighted_f0, mat.iridescence_thickness_nm, v_dot_h);
        const Rgb metal_film = iridescentFresnel(1.0, mat.iridescence_ior, mat.base_color,
                                                 mat.iridescence_thickness_nm, v_dot_h);
        for (std::size_t k = 0; k < 3; ++k) {
            channel(weight, k) += mat.iridescence * (channel(dielectric_film, k) - channel(weight, k));
            channel(metal_fresnel, k) +=
                mat.iridescence * (channel(metal_film, k) - channel(metal_fresnel, k));
        }
    }
    const double diffuse_weight = 1.0 - maxChannel(weight);

    // Clear coat: fresnel_coat at N.V (ior 1.5, f0 0.04); its lobe unless a mirror.
    const double coat_fresnel = mat.clearcoat * schlick(0.04, n_dot_v);
    const double coat_lobe =
        mat.clearcoat_roughness > 0.0
            ? specularBrdf(mat.clearcoat_roughness * mat.clearcoat_roughness, n_dot_l, n_dot_v, h.z)
            : 0.0;
    Rgb f;
    for (std::size_t k = 0; k < 3; ++k) {
        const double dielectric =
            diffuse_weight * channel(mat.base_color, k) / kPi + channel(weight, k) * lobe;
        const double metal = channel(metal_fresnel, k) * lobe;
        const double material = dielectric + mat.metallic * (metal - dielectric);
        channel(f, k) = (1.0 - coat_fresnel) * material + coat_fresnel * coat_lobe;
    }
    return f;
}

double gltfMirrorReflectance(const GltfMaterial& material, double cos_theta) noexcept {
    if (material.clearcoat_roughness > 0.0) return 0.0;
    return material.clearcoat * schlick(0.04, cos_theta);
}

}  // namespace paintlab::approx
