// Checks the observations of a fit problem and prepares them for the
// residuals (residual_model.h): every bad value an InputError naming its field.

#include "residual_model.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_paths.h"

#include <cmath>

namespace paintlab::fit {

namespace {

using io::formatNumber;

class Checker {
public:
    explicit Checker(std::string source) : m_source(std::move(source)) {}

    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        throw InputError(m_source, field, message);
    }
    void finite(const std::string& field, double value) const {
        if (!std::isfinite(value)) fail(field, "is not a finite number");
    }
    void nonNegative(const std::string& field, double value) const {
        finite(field, value);
        if (value < 0.0) fail(field, formatNumber(value) + " is negative");
    }
    // 0 means "the default".
    double noise(const std::string& field, double value, double fallback) const {
        nonNegative(field, value);
        return value > 0.0 ? value : fallback;
    }
    void angle(const std::string& field, double value, double lo, double hi) const {
        finite(field, value);
        if (value < lo || value >= hi)
            fail(field,
                 formatNumber(value) + "° is outside [" + formatNumber(lo) + ", " + formatNumber(hi) + ")");
    }
    // Ascending wavelengths and the indices of those inside the model's range
    // (at least two: a spectrum's colour needs them).
    std::vector<std::size_t> wavelengths(const std::string& field, const std::vector<double>& nm) const {
        std::vector<std::size_t> inside;
        for (std::size_t k = 0; k < nm.size(); ++k) {
            const std::string at = field + "[" + std::to_string(k) + "]";
            nonNegative(at, nm[k]);
            if (k > 0 && nm[k] <= nm[k - 1]) fail(at, "wavelengths must be strictly ascending");
            if (nm[k] >= kVisibleMinNm && nm[k] <= kVisibleMaxNm) inside.push_back(k);
        }
        if (inside.size() < 2)
            fail(field, "fewer than two wavelengths overlap the model's " + formatNumber(kVisibleMinNm) +
                            "-" + formatNumber(kVisibleMaxNm) + " nm");
        return inside;
    }

private:
    std::string m_source;
};

std::string sourceOf(const std::string& name) { return name.empty() ? "<measurement>" : name; }

void checkSide(const Checker& check, const std::string& field, Side side, const Recipe& recipe) {
    if (side == Side::Bottom && !std::holds_alternative<TransparentSubstrate>(recipe.substrate))
        check.fail(field,
                   "a bottom-side measurement needs the template's substrate to be transparent, not '" +
                       std::string(substrateKind(recipe.substrate)) + "'");
}

void prepareMultiAngle(const MultiAngleMeasurement& m, std::size_t mi, const Recipe& recipe,
                       PreparedObservations& out) {
    const Checker check(sourceOf(m.name));
    const std::string base = elementPath("", "multi_angle", mi);
    checkSide(check, fieldPath(base, "side"), m.side, recipe);
    if (m.readings.empty()) check.fail(fieldPath(base, "readings"), "no readings");
    for (std::size_t k = 0; k < m.readings.size(); ++k) {
        const MultiAngleReading& r = m.readings[k];
        const std::string at = elementPath(base, "readings", k);
        PreparedReading p;
        p.measurement = mi;
        p.index = k;
        p.side = m.side;
        p.conditions = {.illuminant = m.illuminant, .observer = m.observer};
        check.angle(fieldPath(at, "illumination_deg"), r.illumination_deg, 0.0, 90.0);
        p.illumination_deg = r.illumination_deg;
        check.finite(fieldPath(at, "aspecular_deg"), r.aspecular_deg);
        check.finite(fieldPath(at, "azimuth_deg"), r.azimuth_deg);
        if (std::abs(r.azimuth_deg) > 180.0)
            check.fail(fieldPath(at, "azimuth_deg"),
                       formatNumber(r.azimuth_deg) + "° is outside [-180, 180]");
        if (!isInPlane(r.azimuth_deg))
            if (const std::string problem = outOfPlaneFormProblem(r.aspecular_deg, r.azimuth_deg);
                !problem.empty())
                check.fail(fieldPath(at, "aspecular_deg"), problem);
        // The directions by multiangle.h's convention (the one conversion).
        const MultiAngleGeometry g = multiAngleDirections(r.illumination_deg, r.aspecular_deg, r.azimuth_deg);
        if (!(detectorPolarAngleDeg(g) <= kMaxDetectorPolarDeg))
            check.fail(
                fieldPath(at, "aspecular_deg"),
                formatNumber(r.aspecular_deg) + "° puts the detector below the horizon" +
                    (isInPlane(r.azimuth_deg) ? "" : " at azimuth " + formatNumber(r.azimuth_deg) + "°"));
        p.aspecular_deg = r.aspecular_deg;
        p.azimuth_deg = r.azimuth_deg;
        p.wi = g.wi;
        p.wo = g.wo;
        if (r.wavelengths_nm.size() != r.reflectance_factor.size())
            check.fail(fieldPath(at, "reflectance_factor"),
                       "has " + std::to_string(r.reflectance_factor.size()) + " values for " +
                           std::to_string(r.wavelengths_nm.size()) + " wavelengths");
        if (r.lab) {
            check.nonNegative(fieldPath(at, "lab.L"), r.lab->L);
            check.finite(fieldPath(at, "lab.a"), r.lab->a);
            check.finite(fieldPath(at, "lab.b"), r.lab->b);
            p.lab = r.lab;
        }
        const double rel = check.noise(fieldPath(at, "reflectance_relative_noise"),
                                       r.reflectance_relative_noise, kDefaultReflectanceRelativeNoise);
        const double abs = check.noise(fieldPath(at, "reflectance_absolute_noise"),
                                       r.reflectance_absolute_noise, kDefaultReflectanceAbsoluteNoise);
        p.lab_sigma = check.noise(fieldPath(at, "lab_noise"), r.lab_noise, kDefaultLabNoise);
        if (r.wavelengths_nm.empty()) {
            if (!r.lab) check.fail(at, "has neither spectral reflectance factors nor CIELAB");
            out.residual_count += 3;
        } else {
            p.spectral = true;
            for (std::size_t i = 0; i < r.reflectance_factor.size(); ++i)
                check.nonNegative(elementPath(at, "reflectance_factor", i), r.reflectance_factor[i]);
            for (std::size_t i : check.wavelengths(fieldPath(at, "wavelengths_nm"), r.wavelengths_nm)) {
                const double value = r.reflectance_factor[i];
                p.wavelengths_nm.push_back(r.wavelengths_nm[i]);
                p.measured.push_back(value);
                p.sigma.push_back(rel * value + abs);
            }
            out.residual_count += p.measured.size();
        }
        (m.side == Side::Top ? out.top : out.bottom) = true;
        out.readings.push_back(std::move(p));
    }
}

void prepareBrdf(const BrdfMeasurement& m, std::size_t mi, const Recipe& recipe, PreparedObservations& out) {
    const Checker check(sourceOf(m.name));
    const std::string base = elementPath("", "brdf", mi);
    checkSide(check, fieldPath(base, "side"), m.side, recipe);
    if (m.samples.empty()) check.fail(fieldPath(base, "samples"), "no samples");
    const bool rgb = m.values == BrdfValues::LinearSrgb;
    std::vector<std::size_t> inside{0, 1, 2};
    if (!rgb) inside = check.wavelengths(fieldPath(base, "wavelengths_nm"), m.wavelengths_nm);
    const std::size_t channels = rgb ? 3 : m.wavelengths_nm.size();
    for (std::size_t k = 0; k < m.samples.size(); ++k) {
        const BrdfSample& s = m.samples[k];
        const std::string at = elementPath(base, "samples", k);
        check.angle(fieldPath(at, "theta_i_deg"), s.theta_i_deg, 0.0, 90.0);
        check.angle(fieldPath(at, "theta_o_deg"), s.theta_o_deg, 0.0, 90.0);
        check.finite(fieldPath(at, "phi_i_deg"), s.phi_i_deg);
        check.finite(fieldPath(at, "phi_o_deg"), s.phi_o_deg);
        if (s.values.size() != channels)
            check.fail(fieldPath(at, "values"), "has " + std::to_string(s.values.size()) +
                                                    " values, expected " + std::to_string(channels) +
                                                    (rgb ? " (linear sRGB)" : " (one per wavelength)"));
        PreparedSample p;
        p.measurement = mi;
        p.index = k;
        p.side = m.side;
        p.rgb = rgb;
        p.wi = directionFromAnglesDeg(s.theta_i_deg, s.phi_i_deg);
        p.wo = directionFromAnglesDeg(s.theta_o_deg, s.phi_o_deg);
        p.cos_i = p.wi.z;
        for (std::size_t i = 0; i < s.values.size(); ++i)
            check.nonNegative(elementPath(at, "values", i), s.values[i]);
        p.sigma =
            check.noise(fieldPath(at, "log_noise"), s.log_noise, defaultBrdfLogNoise(s.values, p.cos_i));
        for (std::size_t i : inside) {
            p.measured_log.push_back(std::log1p(s.values[i] * p.cos_i));
            if (!rgb) p.wavelengths_nm.push_back(m.wavelengths_nm[i]);
        }
        out.residual_count += p.measured_log.size();
        (m.side == Side::Top ? out.top : out.bottom) = true;
        out.samples.push_back(std::move(p));
    }
}

}  // namespace

PreparedObservations prepareObservations(const Observations& observations, const Recipe& recipe) {
    PreparedObservations out;
    if (observations.multi_angle.empty() && observations.brdf.empty())
        throw InputError("<measurement>", "observations", "no measurement to fit");
    for (std::size_t i = 0; i < observations.multi_angle.size(); ++i)
        prepareMultiAngle(observations.multi_angle[i], i, recipe, out);
    for (std::size_t i = 0; i < observations.brdf.size(); ++i)
        prepareBrdf(observations.brdf[i], i, recipe, out);
    return out;
}

}  // namespace paintlab::fit
