#include "paintlab/measured_brdf/rgb_brdf.h"

#include "paintlab/engine/fast_model/brdf_colour.h"

#include <cmath>
#include <numbers>

namespace paintlab::measured {

RgbValue SpectralAsRgb::eval(const Direction& wi, const Direction& wo) const {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {0.0, 0.0, 0.0};
    const std::vector<double> f = m_brdf.eval(wi, wo);
    const Rgb rgb = spectrumColour(m_brdf.wavelengthsNm(), f).linear_srgb;
    return {rgb.r, rgb.g, rgb.b};
}

Lab reflectanceFactorLab(const RgbValue& f_per_sr) {
    constexpr double kPi = std::numbers::pi;
    const Xyz white = linearSrgbToXyz({1.0, 1.0, 1.0});
    return xyzToLab(linearSrgbToXyz({kPi * f_per_sr[0], kPi * f_per_sr[1], kPi * f_per_sr[2]}), white);
}

double cosineLogResidual(double f, double f_ref, double cos_theta_i) {
    return std::log1p(f * cos_theta_i) - std::log1p(f_ref * cos_theta_i);
}

}  // namespace paintlab::measured
