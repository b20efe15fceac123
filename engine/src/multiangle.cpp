#include "paintlab/engine/multiangle.h"

#include "paintlab/engine/fast_model/brdf_colour.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace paintlab {

Direction directionFromAnglesDeg(double theta_deg, double phi_deg) noexcept {
    constexpr double kDeg = std::numbers::pi / 180.0;
    const double theta = theta_deg * kDeg;
    const double phi = phi_deg * kDeg;
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

MultiAngleGeometry multiAngleGeometry(double aspecular_deg) {
    // Signed in-plane angle from the normal, positive on the light's side:
    // the light is at +45, its specular direction at -45, and the detector at
    // -45 + aspecular.
    const double detector_deg = -kMultiAngleIlluminationDeg + aspecular_deg;
    if (!(std::abs(detector_deg) < 90.0))
        throw std::invalid_argument("aspecular angle " + std::to_string(aspecular_deg) +
                                    " puts the detector below the horizon");
    MultiAngleGeometry g;
    g.aspecular_deg = aspecular_deg;
    g.wi = directionFromAnglesDeg(kMultiAngleIlluminationDeg, 0.0);
    g.wo = directionFromAnglesDeg(std::abs(detector_deg), detector_deg >= 0.0 ? 0.0 : 180.0);
    return g;
}

double flopIndex(double L15, double L45, double L110) noexcept {
    if (!(L15 > L110) || !(L45 > 0.0)) return 0.0;
    return 2.69 * std::pow(L15 - L110, 1.11) / std::pow(L45, 0.86);
}

MultiAngleReport multiAngleColours(const SpectralBrdf& brdf, Illuminant illuminant, Observer observer) {
    MultiAngleReport report;
    report.illuminant = illuminant;
    report.observer = observer;
    const ColourConditions conditions{.illuminant = illuminant, .observer = observer};
    for (double aspecular : kAspecularAnglesDeg) {
        const MultiAngleGeometry g = multiAngleGeometry(aspecular);
        SpectralColour colour = reflectanceFactorColour(brdf, g.wi, g.wo, conditions);
        MultiAngleColour c;
        c.aspecular_deg = aspecular;
        c.reflectance_factor = std::move(colour.reflectance);
        c.xyz = colour.xyz;
        c.lab = colour.lab;
        report.colours.push_back(std::move(c));
    }
    const auto L = [&report](double aspecular) {
        for (const auto& c : report.colours)
            if (c.aspecular_deg == aspecular) return c.lab.L;
        return 0.0;
    };
    report.flop_index = flopIndex(L(15.0), L(45.0), L(110.0));
    return report;
}

}  // namespace paintlab
