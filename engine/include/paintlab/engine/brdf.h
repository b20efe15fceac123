#pragma once
// The interface every spectral BRDF of PaintLab offers (the fast model's
// LayeredBrdf, the Monte Carlo estimate, analytic test BRDFs), so that colour
// metrics, plots, relighting and fitting work on any of them (after pbrt-v4's
// base/bxdf.h: the interface alone, implementations elsewhere).
//
// Frame: z is the surface normal; directions point away from the surface,
// wi towards the light and wo towards the viewer, both with z > 0 for reflection.

#include <span>
#include <vector>

namespace paintlab {

struct Direction {
    double x = 0.0;
    double y = 0.0;
    double z = 1.0;
};

// theta from the normal, phi from the x axis, both in degrees.
Direction directionFromAnglesDeg(double theta_deg, double phi_deg) noexcept;

class SpectralBrdf {
public:
    virtual ~SpectralBrdf() = default;
    // The wavelengths (nm) at which eval() reports values.
    virtual std::span<const double> wavelengthsNm() const = 0;
    // f(wi, wo, lambda) in 1/sr at every wavelength, written to out
    // (out.size() == wavelengthsNm().size()). Includes no delta (mirror) term.
    // Never throws; directions below the horizon give 0.
    virtual void eval(const Direction& wi, const Direction& wo, std::span<double> out_per_sr) const = 0;

    std::vector<double> eval(const Direction& wi, const Direction& wo) const {
        std::vector<double> out(wavelengthsNm().size());
        eval(wi, wo, out);
        return out;
    }
};

}  // namespace paintlab
