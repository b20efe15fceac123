#pragma once
// An RGB BRDF of a measured material: f(wi, wo) in 1/sr per linear sRGB
// channel (D65), the form in which the compact reconstructions of
// shared/data/measured-brdf give real paints (neural_brdf.h, analytic_brdf.h).
// Frame and directions as paintlab::SpectralBrdf (brdf.h): z the normal, both
// directions away from the surface.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/colour/colour.h"

#include <array>
#include <string>

namespace paintlab::measured {

using RgbValue = std::array<double, 3>;

class RgbBrdf {
public:
    virtual ~RgbBrdf() = default;
    virtual const std::string& name() const = 0;
    // f in 1/sr per channel; 0 when a direction is at or below the horizon.
    // Never throws.
    virtual RgbValue eval(const Direction& wi, const Direction& wo) const = 0;
};

// A spectral BRDF (a fitted recipe's LayeredBrdf) seen as linear sRGB, as the
// fitter compares it with RGB samples (fit.h: spectrumColour's linear sRGB of
// f, brdf_colour.h). Keeps a reference to brdf.
class SpectralAsRgb final : public RgbBrdf {
public:
    SpectralAsRgb(std::string name, const SpectralBrdf& brdf) : m_name(std::move(name)), m_brdf(brdf) {}
    const std::string& name() const override { return m_name; }
    RgbValue eval(const Direction& wi, const Direction& wo) const override;

private:
    std::string m_name;
    const SpectralBrdf& m_brdf;
};

// CIELAB (D65 white, the 2° observer of sRGB's definition) of the reflectance
// factor pi f given as linear sRGB: Lab of RGB (1, 1, 1) is (100, 0, 0).
Lab reflectanceFactorLab(const RgbValue& f_per_sr);

// The cosine-weighted log residual of the fit's loss (fit.h) for one channel:
// ln(1 + f cos θi) - ln(1 + f_ref cos θi).
double cosineLogResidual(double f, double f_ref, double cos_theta_i);

}  // namespace paintlab::measured
