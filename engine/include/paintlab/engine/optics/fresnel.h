#pragma once
// Fresnel equations at a planar interface, for real (dielectric) and complex
// (absorbing, metal) refractive indices, both polarisations.
// Born & Wolf, Principles of Optics, 7th ed., sec. 1.5.2 (dielectrics) and
// sec. 14.2 (absorbing media). cos_i is the cosine of the angle of incidence
// in the incident medium, 0 <= cos_i <= 1. Never throws; no NaN for cos_i in [0, 1].

#include <complex>

namespace paintlab {

struct FresnelAmplitudes {
    std::complex<double> rs, rp;  // reflected amplitude / incident amplitude (s: TE, p: TM)
    std::complex<double> ts, tp;  // transmitted amplitude / incident amplitude
    std::complex<double> cos_t;   // cosine of the (complex) refraction angle
};

// Amplitude coefficients from medium n_i into medium n_t. Total internal
// reflection comes out naturally (|rs| = |rp| = 1) through the complex cos_t.
FresnelAmplitudes fresnelAmplitudes(double cos_i, std::complex<double> n_i, std::complex<double> n_t);

// Unpolarised power reflectance (|rs|^2 + |rp|^2) / 2 for any indices.
double fresnelReflectance(double cos_i, std::complex<double> n_i, std::complex<double> n_t);

// Unpolarised reflectance of a dielectric interface, eta = n_t / n_i (real);
// 1 under total internal reflection.
double fresnelDielectric(double cos_i, double eta);

// Cosine of the refraction angle for eta = n_t / n_i (Snell), or 0 when the
// ray is totally internally reflected.
double refractedCos(double cos_i, double eta);

}  // namespace paintlab
