#include "paintlab/engine/fit/simulate.h"

#include "residual_model.h"

#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/recipe_validation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace paintlab::fit {

MultiAngleMeasurement standardMultiAngleMeasurement(Side side, std::vector<double> wavelengths_nm) {
    if (wavelengths_nm.empty()) wavelengths_nm = uniformWavelengthGrid(400.0, 700.0, 10.0);
    MultiAngleMeasurement m;
    m.name = side == Side::Top ? "standard geometries (top)" : "standard geometries (bottom)";
    m.side = side;
    for (const double aspecular : kAspecularAnglesDeg) {
        MultiAngleReading r;
        r.illumination_deg = kMultiAngleIlluminationDeg;
        r.aspecular_deg = aspecular;
        r.wavelengths_nm = wavelengths_nm;
        r.reflectance_factor.assign(wavelengths_nm.size(), 0.0);
        m.readings.push_back(std::move(r));
    }
    return m;
}

Observations simulateObservations(const Recipe& recipe, const Observations& at, Preset preset) {
    validateRecipe(recipe, "<recipe>");
    Observations out = at;
    // A reading with neither spectra nor Lab asks for Lab.
    for (auto& m : out.multi_angle)
        for (auto& r : m.readings)
            if (r.wavelengths_nm.empty() && !r.lab) r.lab = Lab{};
    const PreparedObservations prepared = prepareObservations(out, recipe);
    const std::optional<SideBrdfs> brdfs = modelBrdfs(recipe, prepared, fitSettings(preset));
    for (const PreparedReading& p : prepared.readings) {
        const LayeredBrdf& brdf = p.side == Side::Top ? *brdfs->top : *brdfs->bottom;
        MultiAngleReading& r = out.multi_angle[p.measurement].readings[p.index];
        const std::vector<double> model = modelReflectanceFactor(brdf, p.wi, p.wo);
        if (!r.wavelengths_nm.empty())
            r.reflectance_factor = interpolate(brdf.wavelengthsNm(), model, r.wavelengths_nm);
        if (r.lab) r.lab = spectrumColour(brdf.wavelengthsNm(), model, p.conditions).lab;
    }
    for (const PreparedSample& p : prepared.samples) {
        const LayeredBrdf& brdf = p.side == Side::Top ? *brdfs->top : *brdfs->bottom;
        const BrdfMeasurement& m = out.brdf[p.measurement];
        BrdfSample& s = out.brdf[p.measurement].samples[p.index];
        const std::vector<double> f = brdf.eval(p.wi, p.wo);
        if (p.rgb) {
            const Rgb rgb = spectrumColour(brdf.wavelengthsNm(), f).linear_srgb;
            s.values = {rgb.r, rgb.g, rgb.b};
        } else {
            s.values = interpolate(brdf.wavelengthsNm(), f, m.wavelengths_nm);
        }
    }
    return out;
}

void addMeasurementNoise(Observations& observations, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (auto& m : observations.multi_angle)
        for (auto& r : m.readings) {
            const double rel = r.reflectance_relative_noise > 0.0 ? r.reflectance_relative_noise
                                                                  : kDefaultReflectanceRelativeNoise;
            const double abs = r.reflectance_absolute_noise > 0.0 ? r.reflectance_absolute_noise
                                                                  : kDefaultReflectanceAbsoluteNoise;
            for (double& v : r.reflectance_factor) v = std::max(0.0, v + (rel * v + abs) * normal(rng));
            if (r.lab) {
                const double sigma = r.lab_noise > 0.0 ? r.lab_noise : kDefaultLabNoise;
                r.lab->L = std::max(0.0, r.lab->L + sigma * normal(rng));
                r.lab->a += sigma * normal(rng);
                r.lab->b += sigma * normal(rng);
            }
        }
    for (auto& m : observations.brdf)
        for (auto& s : m.samples) {
            const double cos_i = std::cos(s.theta_i_deg * std::numbers::pi / 180.0);
            const double sigma = s.log_noise > 0.0 ? s.log_noise : defaultBrdfLogNoise(s.values, cos_i);
            for (double& v : s.values) {
                const double l = std::log1p(std::max(v * cos_i, -0.99)) + sigma * normal(rng);
                v = std::max(0.0, std::expm1(l) / cos_i);
            }
        }
}

}  // namespace paintlab::fit
