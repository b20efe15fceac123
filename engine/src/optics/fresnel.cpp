#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>

namespace paintlab {

FresnelAmplitudes fresnelAmplitudes(double cos_i, std::complex<double> n_i, std::complex<double> n_t) {
    using C = std::complex<double>;
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    const double sin2_i = std::max(0.0, 1.0 - cos_i * cos_i);
    // Snell in the complex form n_i sin_i = n_t sin_t; the principal square
    // root gives Re(cos_t) >= 0, the decaying wave for absorbing media and TIR.
    const C ratio = n_i / n_t;
    const C cos_t = std::sqrt(C(1.0) - ratio * ratio * sin2_i);
    const C ni_cos_i = n_i * cos_i;
    const C nt_cos_t = n_t * cos_t;
    const C nt_cos_i = n_t * cos_i;
    const C ni_cos_t = n_i * cos_t;
    FresnelAmplitudes a;
    a.cos_t = cos_t;
    const C ds = ni_cos_i + nt_cos_t;
    const C dp = nt_cos_i + ni_cos_t;
    // At exactly grazing incidence on a dielectric with n_t == n_i both denominators
    // vanish; the limit is r = 0, t = 1 (no interface).
    if (std::abs(ds) < 1e-300 || std::abs(dp) < 1e-300) {
        a.rs = a.rp = C(0.0);
        a.ts = a.tp = C(1.0);
        return a;
    }
    a.rs = (ni_cos_i - nt_cos_t) / ds;
    a.rp = (nt_cos_i - ni_cos_t) / dp;
    a.ts = 2.0 * ni_cos_i / ds;
    a.tp = 2.0 * ni_cos_i / dp;
    return a;
}

double fresnelReflectance(double cos_i, std::complex<double> n_i, std::complex<double> n_t) {
    const FresnelAmplitudes a = fresnelAmplitudes(cos_i, n_i, n_t);
    return std::clamp(0.5 * (std::norm(a.rs) + std::norm(a.rp)), 0.0, 1.0);
}

double refractedCos(double cos_i, double eta) {
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    return sin2_t >= 1.0 ? 0.0 : std::sqrt(1.0 - sin2_t);
}

double fresnelDielectric(double cos_i, double eta) {
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    // Index matched: no interface. Return 0 exactly; the general formula leaves
    // ~1e-32 from rounding cos_t = sqrt(1 - sin^2) back to cos_i.
    if (eta == 1.0) return 0.0;
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return 1.0;  // total internal reflection
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return std::clamp(0.5 * (rs * rs + rp * rp), 0.0, 1.0);
}

}  // namespace paintlab
