#include "paintlab/engine/multiangle.h"

#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/io/number_format.h"

#include <algorithm>
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

MultiAngleGeometry multiAngleDirections(double illumination_deg, double aspecular_deg,
                                        double azimuth_deg) noexcept {
    constexpr double kDeg = std::numbers::pi / 180.0;
    MultiAngleGeometry g;
    g.illumination_deg = illumination_deg;
    g.aspecular_deg = aspecular_deg;
    g.azimuth_deg = azimuth_deg;
    g.wi = directionFromAnglesDeg(illumination_deg, 0.0);
    if (isInPlane(azimuth_deg)) {
        // In the plane: the signed angle from the normal, positive on the
        // light's side: the light at +illumination, its specular direction at
        // -illumination, the detector at -illumination + aspecular.
        const double detector_deg = -illumination_deg + aspecular_deg;
        g.wo = directionFromAnglesDeg(std::abs(detector_deg), detector_deg >= 0.0 ? 0.0 : 180.0);
        return g;
    }
    // Rotated about the specular direction r (multiangle.h): u in the plane,
    // perpendicular to r and away from the normal; r x u = -y.
    const double s = std::sin(illumination_deg * kDeg);
    const double c = std::cos(illumination_deg * kDeg);
    const Direction r{-s, 0.0, c};
    const Direction u{-c, 0.0, -s};
    const double cos_as = std::cos(aspecular_deg * kDeg);
    const double sin_as = std::sin(aspecular_deg * kDeg);
    const double cos_az = std::cos(azimuth_deg * kDeg);
    const double sin_az = std::sin(azimuth_deg * kDeg);
    g.wo = {cos_as * r.x + sin_as * cos_az * u.x, -sin_as * sin_az, cos_as * r.z + sin_as * cos_az * u.z};
    return g;
}

std::string outOfPlaneFormProblem(double aspecular_deg, double azimuth_deg) {
    if (!(aspecular_deg > 0.0 && aspecular_deg <= 180.0))
        return "aspecular " + io::formatNumber(aspecular_deg) +
               "° out of the plane must be in (0, 180]: the same direction is the positive aspecular at the "
               "opposite azimuth";
    if (!(std::abs(azimuth_deg) < 180.0))
        return "azimuth " + io::formatNumber(azimuth_deg) +
               "° is the plane of incidence: name it without 'az'";
    return {};
}

double detectorPolarAngleDeg(const MultiAngleGeometry& geometry) noexcept {
    return std::acos(std::clamp(geometry.wo.z, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

MultiAngleGeometry multiAngleGeometry(double aspecular_deg) {
    MultiAngleGeometry g = multiAngleDirections(kMultiAngleIlluminationDeg, aspecular_deg);
    if (!(std::abs(aspecular_deg - kMultiAngleIlluminationDeg) < 90.0))
        throw std::invalid_argument("aspecular angle " + std::to_string(aspecular_deg) +
                                    " puts the detector below the horizon");
    return g;
}

double flopIndex(double L15, double L45, double L110) noexcept {
    if (!(L15 > L110) || !(L45 > 0.0)) return 0.0;
    return 2.69 * std::pow(L15 - L110, 1.11) / std::pow(L45, 0.86);
}

MultiAngleColour multiAngleColour(const SpectralBrdf& brdf, const MultiAngleGeometry& geometry,
                                  const ColourConditions& conditions) {
    SpectralColour colour = reflectanceFactorColour(brdf, geometry.wi, geometry.wo, conditions);
    MultiAngleColour c;
    c.aspecular_deg = geometry.aspecular_deg;
    c.illumination_deg = geometry.illumination_deg;
    c.azimuth_deg = geometry.azimuth_deg;
    c.reflectance_factor = std::move(colour.reflectance);
    c.xyz = colour.xyz;
    c.lab = colour.lab;
    return c;
}

MultiAngleReport multiAngleColours(const SpectralBrdf& brdf, Illuminant illuminant, Observer observer) {
    MultiAngleReport report;
    report.illuminant = illuminant;
    report.observer = observer;
    const ColourConditions conditions{.illuminant = illuminant, .observer = observer};
    for (double aspecular : kAspecularAnglesDeg)
        report.colours.push_back(multiAngleColour(brdf, multiAngleGeometry(aspecular), conditions));
    const auto L = [&report](double aspecular) {
        for (const auto& c : report.colours)
            if (c.aspecular_deg == aspecular) return c.lab.L;
        return 0.0;
    };
    report.flop_index = flopIndex(L(15.0), L(45.0), L(110.0));
    return report;
}

}  // namespace paintlab
