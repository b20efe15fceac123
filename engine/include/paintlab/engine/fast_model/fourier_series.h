#pragma once
// The azimuthal Fourier series in which the fast model stores a BRDF
// (layered_brdf.h): f(dphi) = sum_m a_m cos(m dphi). Summed here once, for
// LayeredBrdf::eval and for the tools that sum the series of
// LayeredBrdf::fourierCoefficientsGrid themselves (the plots), so that both
// add the same terms in the same order.

#include <algorithm>
#include <cstddef>
#include <span>

namespace paintlab {

// scale * sum_m terms[m] * coefficients[m * stride] for m < terms.size(),
// summed in ascending m. terms[m]: the order's azimuthal factor, cos(m dphi)
// times whatever weight the coefficients leave out; scale >= 0: a factor
// applied after the sum (a Fresnel transmittance, pi).
inline double fourierSum(std::span<const double> terms, std::span<const double> coefficients,
                         std::size_t stride, double scale) {
    double sum = 0.0;
    for (std::size_t m = 0; m < terms.size(); ++m) sum += terms[m] * coefficients[m * stride];
    return scale * sum;
}

// The same, clipped at zero, because a truncated series can ring slightly below it.
inline double clippedFourierSum(std::span<const double> terms, std::span<const double> coefficients,
                                std::size_t stride, double scale) {
    return std::max(0.0, fourierSum(terms, coefficients, stride, scale));
}

}  // namespace paintlab
