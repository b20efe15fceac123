#include "paintlab/measured_brdf/rgb_brdf.h"

#include <cmath>
#include <numbers>

namespace paintlab::measured {

Lab reflectanceFactorLab(const RgbValue& f_per_sr) {
    constexpr double kPi = std::numbers::pi;
    const Xyz white = linearSrgbToXyz({1.0, 1.0, 1.0});
    return xyzToLab(linearSrgbToXyz({kPi * f_per_sr[0], kPi * f_per_sr[1], kPi * f_per_sr[2]}), white);
}

double cosineLogResidual(double f, double f_ref, double cos_theta_i) {
    return std::log1p(f * cos_theta_i) - std::log1p(f_ref * cos_theta_i);
}

}  // namespace paintlab::measured
