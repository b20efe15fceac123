// The fast model's validity boundary from the fast-vs-full comparison report
// (docs/VALIDATION.md, "Fast vs full model: comparison report"; data in
// docs/fast_vs_full.csv, made by tools/compare_report/compare_report.py).
//
// Mechanism (model_validity.h): light reflected by a flake at depth z leaves
// along a path that, for flakes large next to the lateral offset between the
// way in and the way out, crosses the same flakes the way in crossed. With N
// flakes (Poisson, mean lambda) on the way in and flake transmittance T, the
// round trip keeps E[T^2N] = exp(-lambda (1 - T^2)) of the light instead of
// the continuum's E[T^N]^2 = exp(-2 lambda (1 - T)). Single scattering in a
// layer of extinction optical thickness tau = (1 - T) * coverage / mu (along
// the refracted beam) is then brighter by the factor
//   1 + E(tau, T) = 2 / (1 + T) * (1 - e^(-(1 + T) tau)) / (1 - e^(-2 tau)),
// which for metal flakes (T = 0) is 1 + tanh(tau / 2), up to a factor of
// two, and for nearly transparent flakes (T -> 1) tends to 1: the most the
// correlation can give. How much of it a paint gets depends on the flake
// diameter d against the distance over which the way out leaves the way in:
// the extinction free path ell = t / (c (1 - T)) (flake thickness t, volume
// fraction c), or the film thickness H when the film is the shorter:
// x = d / min(H, ell). The report's grid fits
//   expected = A * E(tau, T) * x^p / (x^p + x0^p).

#include "paintlab/engine/model_validity.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_validation.h"
#include "paintlab/engine/thin_film.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

namespace paintlab {

namespace {

// Fitted to the 102 points of docs/fast_vs_full.csv (weighted_rel of the
// grid and the small-flake series, by tools/compare_report/fit_boundary.py:
// least squares weighted by 1 / (se^2 + 0.03^2)). Residuals: RMS 6
// percentage points, largest 34 (metal flakes at the maximum concentration
// and 20 deg spread, measured +115 % against 81 %); at the 10 % boundary the
// rule never calls a paint inside that the report measured outside by more
// than 2 standard errors, and calls one outside that was inside (50 µm
// interference flakes in the 20 µm film, which the full model squeezes).
constexpr double kAmplitude = 0.90;
constexpr double kX0 = 2.225;
constexpr double kPower = 1.0;

// The report's incidence: 45° in air, refracted into the binder.
constexpr double kIncidenceDeg = 45.0;
// An interference flake's transmittance is averaged over 400-700 nm (the
// report's band means) every 10 nm.
constexpr double kMinNm = 400.0;
constexpr double kStepNm = 10.0;
constexpr int kWavelengths = 31;

struct FlakeTerm {
    double tau = 0.0;            // extinction optical thickness along the refracted beam
    double transmittance = 0.0;  // of one flake, straight on (0 for metal)
    double x = 0.0;              // diameter over min(film thickness, extinction free path)
    double coverage = 0.0;       // flake area per unit film area
    std::string what;            // layer and component, for the reason
};

// Transmittance of an interference flake straight on at normal incidence,
// averaged over 400-700 nm weighted by its reflectance: the band mean of f
// that the report compares is made where the flakes reflect (for the blue
// pearl 0.72 against a plain mean of 0.82). A metal flake's is 0.
double flakeTransmittance(const InterferenceFlake& f, const Layer& layer) {
    double rt_sum = 0.0;
    double r_sum = 0.0;
    for (int i = 0; i < kWavelengths; ++i) {
        const double wl = kMinNm + kStepNm * i;
        InterferenceFlakeOptics optics;
        optics.binder_n = layer.binder.refractive_index(wl);
        optics.mica_n = f.mica_refractive_index(wl);
        optics.tio2_n = f.tio2_refractive_index(wl);
        optics.mica_thickness_nm = f.mica_thickness_nm;
        optics.mica_thickness_spread_nm = f.mica_thickness_spread_nm;
        optics.tio2_thickness_nm = f.tio2_thickness_nm;
        optics.tio2_thickness_spread_nm = f.tio2_thickness_spread_nm;
        const FlakeRT rt = interferenceFlakeRT(optics, 1.0, wl);
        rt_sum += rt.R * rt.T;
        r_sum += rt.R;
    }
    return r_sum > 0.0 ? std::clamp(rt_sum / r_sum, 0.0, 1.0) : 1.0;
}

std::string componentLabel(std::size_t layer_index, const Layer& layer, const Component& component) {
    std::string text = "layer ";
    text.append(std::to_string(layer_index + 1)).append(" '").append(layer.name).append("' ");
    text.append(componentKind(component)).append(" '").append(componentName(component)).append("'");
    return text;
}

FlakeTerm flakeTerm(const Layer& layer, double volume_fraction, double thickness_um, double diameter_um,
                    double transmittance, double mu) {
    FlakeTerm term;
    term.transmittance = transmittance;
    const double extinction = 1.0 - transmittance;
    const double H = layer.thickness_um;
    term.coverage = volume_fraction * H / thickness_um;
    term.tau = extinction * term.coverage / mu;
    const double sigma_per_um = extinction * volume_fraction / thickness_um;  // extinction area per volume
    term.x = diameter_um * std::max(1.0 / H, sigma_per_um);
    return term;
}

// E(tau, T) above: expm1 keeps it accurate as tau -> 0 (where it -> (1 - T) tau / 2).
double hidingExcess(double tau, double T) {
    return 2.0 / (1.0 + T) * std::expm1(-(1.0 + T) * tau) / std::expm1(-2.0 * tau) - 1.0;
}

double expectedDifference(double tau, double T, double x) {
    if (!(tau > 0.0) || !(x > 0.0)) return 0.0;
    const double xp = std::pow(x, kPower);
    return kAmplitude * std::max(0.0, hidingExcess(tau, T)) * xp / (xp + std::pow(kX0, kPower));
}

}  // namespace

FastModelValidity fastModelValidity(const Recipe& recipe, double tolerance) {
    if (!(tolerance > 0.0 && tolerance <= 1.0))
        throw InputError("<argument>", "tolerance", std::to_string(tolerance) + " must be in (0, 1]");
    validateRecipe(recipe, recipe.name);

    FastModelValidity result;
    result.tolerance = tolerance;
    const double sin_i = std::sin(kIncidenceDeg * std::numbers::pi / 180.0);
    std::string worst;
    bool any_flakes = false;
    for (std::size_t l = 0; l < recipe.layers.size(); ++l) {
        const Layer& layer = recipe.layers[l];
        const double n_layer = layer.binder.refractive_index(550.0);
        const double mu = std::sqrt(std::max(0.0, 1.0 - sin_i * sin_i / (n_layer * n_layer)));
        // The flakes of one layer shade one another: their optical thicknesses
        // add; x and T are the extinction-weighted means.
        double tau = 0.0;
        double x_weighted = 0.0;
        double T_weighted = 0.0;
        const FlakeTerm* dominant = nullptr;
        std::vector<FlakeTerm> terms;
        terms.reserve(layer.components.size());
        for (const auto& component : layer.components) {
            FlakeTerm term;
            if (const auto* m = std::get_if<MirrorFlake>(&component)) {
                term = flakeTerm(layer, m->volume_fraction, m->thickness_um, m->diameter_um, 0.0, mu);
            } else if (const auto* p = std::get_if<InterferenceFlake>(&component)) {
                const double t_um = (p->mica_thickness_nm + 2.0 * p->tio2_thickness_nm) * 1e-3;
                term = flakeTerm(layer, p->volume_fraction, t_um, p->diameter_um,
                                 flakeTransmittance(*p, layer), mu);
            } else {
                continue;
            }
            if (!(term.tau > 0.0)) continue;
            any_flakes = true;
            term.what = componentLabel(l, layer, component);
            terms.push_back(std::move(term));
        }
        for (const auto& term : terms) {
            tau += term.tau;
            x_weighted += term.tau * term.x;
            T_weighted += term.tau * term.transmittance;
            if (dominant == nullptr || term.tau * term.x > dominant->tau * dominant->x) dominant = &term;
        }
        if (terms.empty()) continue;
        const double expected = expectedDifference(tau, T_weighted / tau, x_weighted / tau);
        if (expected >= result.expected_rel_difference) {
            result.expected_rel_difference = expected;
            char text[256];
            std::snprintf(text, sizeof text,
                          ": coverage %.3g flake layers, diameter / min(film, free path) %.3g",
                          dominant->coverage, x_weighted / tau);
            worst = dominant->what;
            worst.append(text);
        }
    }
    result.within = result.expected_rel_difference <= tolerance;
    if (!any_flakes) {
        result.reason = "no flakes that take light out of the beam: both models solve the same "
                        "radiative-transfer equation";
        return result;
    }
    char head[128];
    std::snprintf(head, sizeof head, "expected difference %.1f %% (%s %.0f %%) from ",
                  100.0 * result.expected_rel_difference, result.within ? "within" : "above",
                  100.0 * tolerance);
    result.reason = head;
    result.reason.append(worst);
    return result;
}

}  // namespace paintlab
