#include "residual_model.h"

#include "paintlab/engine/colour/band_weights.h"
#include "paintlab/engine/colour/ciede2000.h"
#include "paintlab/engine/fast_model/brdf_colour.h"
#include "paintlab/engine/recipe_validation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

namespace paintlab::fit {

namespace {

// The band -> linear sRGB weights of a wavelength grid, computed once per
// grid (one per preset in a fit) and shared by every evaluation.
const BandColourWeights& rgbWeights(std::span<const double> wavelengths_nm) {
    static std::mutex mutex;
    static std::map<std::vector<double>, BandColourWeights> cache;
    const std::lock_guard lock(mutex);
    std::vector<double> key(wavelengths_nm.begin(), wavelengths_nm.end());
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, bandColourWeights(wavelengths_nm)).first;
    return it->second;
}

// ln(1 + f cos θi), kept finite for a model value slightly below 0
// (out-of-gamut linear sRGB).
double logTerm(double f, double cos_i) { return std::log1p(std::max(f * cos_i, -0.99)); }

const LayeredBrdf& brdfFor(const SideBrdfs& brdfs, Side side) {
    return side == Side::Top ? *brdfs.top : *brdfs.bottom;
}

// The model's values of one BRDF sample, per channel of the measurement.
std::vector<double> sampleModel(const LayeredBrdf& brdf, const PreparedSample& s) {
    const std::vector<double> f = brdf.eval(s.wi, s.wo);
    if (s.rgb) {
        const Rgb rgb = weightedLinearSrgb(rgbWeights(brdf.wavelengthsNm()), f);
        return {rgb.r, rgb.g, rgb.b};
    }
    return interpolate(brdf.wavelengthsNm(), f, s.wavelengths_nm);
}

}  // namespace

std::vector<double> interpolate(std::span<const double> x, std::span<const double> y,
                                std::span<const double> at) {
    std::vector<double> out(at.size());
    for (std::size_t k = 0; k < at.size(); ++k) {
        const double t = at[k];
        if (t <= x.front()) {
            out[k] = y.front();
        } else if (t >= x.back()) {
            out[k] = y.back();
        } else {
            const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), t) - x.begin());
            const std::size_t lo = hi - 1;
            const double w = (t - x[lo]) / (x[hi] - x[lo]);
            out[k] = (1.0 - w) * y[lo] + w * y[hi];
        }
    }
    return out;
}

std::vector<double> modelReflectanceFactor(const SpectralBrdf& brdf, const Direction& wi,
                                           const Direction& wo) {
    std::vector<double> r = brdf.eval(wi, wo);
    for (double& v : r) v *= std::numbers::pi;
    return r;
}

std::optional<SideBrdfs> modelBrdfs(const Recipe& recipe, const PreparedObservations& prepared,
                                    const FastModelSettings& settings) {
    for (const RecipeProblem& p : checkRecipe(recipe))
        if (p.severity == Severity::Error) return std::nullopt;
    SideBrdfs out;
    if (prepared.top) out.top = computeLayeredBrdf(recipe, settings);
    if (prepared.bottom) out.bottom = computeLayeredBrdf(recipeSeenFromBelow(recipe), settings);
    return out;
}

void whitenedResiduals(const SideBrdfs& brdfs, const PreparedObservations& prepared, std::span<double> out) {
    std::size_t n = 0;
    for (const PreparedReading& r : prepared.readings) {
        const LayeredBrdf& brdf = brdfFor(brdfs, r.side);
        const std::vector<double> model = modelReflectanceFactor(brdf, r.wi, r.wo);
        if (r.spectral) {
            const std::vector<double> at = interpolate(brdf.wavelengthsNm(), model, r.wavelengths_nm);
            for (std::size_t k = 0; k < at.size(); ++k) out[n++] = (at[k] - r.measured[k]) / r.sigma[k];
        } else {
            const Lab lab = spectrumColour(brdf.wavelengthsNm(), model, r.conditions).lab;
            out[n++] = (lab.L - r.lab->L) / r.lab_sigma;
            out[n++] = (lab.a - r.lab->a) / r.lab_sigma;
            out[n++] = (lab.b - r.lab->b) / r.lab_sigma;
        }
    }
    for (const PreparedSample& s : prepared.samples) {
        const std::vector<double> model = sampleModel(brdfFor(brdfs, s.side), s);
        for (std::size_t c = 0; c < model.size(); ++c)
            out[n++] = (logTerm(model[c], s.cos_i) - s.measured_log[c]) / s.sigma;
    }
}

void observationDetails(const SideBrdfs& brdfs, const PreparedObservations& prepared,
                        std::vector<ObservationResidual>& residuals, std::vector<GeometryMatch>& geometries) {
    for (const PreparedReading& r : prepared.readings) {
        const LayeredBrdf& brdf = brdfFor(brdfs, r.side);
        const std::vector<double> model = modelReflectanceFactor(brdf, r.wi, r.wo);
        GeometryMatch g;
        g.measurement = r.measurement;
        g.index = r.index;
        g.side = r.side;
        g.illumination_deg = r.illumination_deg;
        g.aspecular_deg = r.aspecular_deg;
        g.azimuth_deg = r.azimuth_deg;
        ObservationResidual o{r.measurement, r.index, ObservationKind::MultiAngleLab, r.side, 0.0, 0.0};
        // The fitted colour is computed as the measured one is: from the
        // spectrum at the measured wavelengths, or, where the instrument gave
        // L*a*b*, from the model's whole spectrum.
        if (r.spectral) {
            o.kind = ObservationKind::MultiAngleSpectral;
            g.wavelengths_nm = r.wavelengths_nm;
            g.fitted_reflectance_factor = interpolate(brdf.wavelengthsNm(), model, r.wavelengths_nm);
            double sum = 0.0;
            for (std::size_t k = 0; k < r.measured.size(); ++k) {
                const double w = (g.fitted_reflectance_factor[k] - r.measured[k]) / r.sigma[k];
                sum += w * w;
            }
            o.whitened_rms = std::sqrt(sum / static_cast<double>(r.measured.size()));
        } else {
            g.wavelengths_nm.assign(brdf.wavelengthsNm().begin(), brdf.wavelengthsNm().end());
            g.fitted_reflectance_factor = model;
        }
        if (r.lab) {
            g.measured = *r.lab;
            g.fitted = spectrumColour(brdf.wavelengthsNm(), model, r.conditions).lab;
        } else {
            g.measured = spectrumColour(r.wavelengths_nm, r.measured, r.conditions).lab;
            g.fitted = spectrumColour(r.wavelengths_nm, g.fitted_reflectance_factor, r.conditions).lab;
        }
        if (!r.spectral) {
            const double dL = g.fitted.L - g.measured.L;
            const double da = g.fitted.a - g.measured.a;
            const double db = g.fitted.b - g.measured.b;
            o.whitened_rms = std::sqrt((dL * dL + da * da + db * db) / 3.0) / r.lab_sigma;
        }
        g.delta_e00 = ciede2000(g.measured, g.fitted);
        residuals.push_back(o);
        geometries.push_back(std::move(g));
    }
    for (const PreparedSample& s : prepared.samples) {
        const std::vector<double> model = sampleModel(brdfFor(brdfs, s.side), s);
        double sum = 0.0;
        for (std::size_t c = 0; c < model.size(); ++c) {
            const double d = logTerm(model[c], s.cos_i) - s.measured_log[c];
            sum += d * d;
        }
        const double rms = std::sqrt(sum / static_cast<double>(model.size()));
        residuals.push_back(
            {s.measurement, s.index, ObservationKind::BrdfSample, s.side, rms / s.sigma, rms});
    }
}

}  // namespace paintlab::fit
