// The effect planner's decisions (plan.h). Each decision starts from the
// preset's settings and only lowers them (or skips an effect) where the
// scene and the recipe make the difference smaller than half the preset's
// colour tolerance; the error it claims is its own estimate of that
// difference, checked by the honesty tests (tests/engine/plan).

#include "paintlab/engine/plan/plan.h"

#include "plan_spectra.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/model_validity.h"
#include "paintlab/engine/recipe_validation.h"
#include "paintlab/engine/sparkle/sparkle.h"
#include "paintlab/engine/sparkle/sparkle_texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

namespace paintlab {

namespace {

constexpr double kPi = std::numbers::pi;

void checkScene(const PlanScene& s) {
    const auto check = [&](double v, const char* field) {
        if (!std::isfinite(v) || v < 0.0)
            throw InputError(s.source.empty() ? "<scene summary>" : s.source, field,
                             std::to_string(v) + " must be finite and >= 0");
    };
    check(s.environment_radiance, "environment_radiance");
    check(s.environment_sharpness_deg, "environment_sharpness_deg");
    check(s.footprint_min_um, "footprint_min_um");
    check(s.footprint_max_um, "footprint_max_um");
    check(s.viewing_distance_m, "viewing_distance_m");
    for (const auto& l : s.lights) {
        check(l.irradiance_w_m2, "lights > irradiance_w_m2");
        check(l.solid_angle_sr, "lights > solid_angle_sr");
    }
}

// The relative change whose Delta E bound is `de` (inverse of deltaEForRelativeChange).
double relativeChangeFor(double de) { return std::pow(1.0 + de / 116.0, 3.0) - 1.0; }

// --- interference -----------------------------------------------------------

PlanDecision interferenceDecision(const Recipe& recipe, EffectPlan& p) {
    PlanDecision d;
    d.effect = "interference";
    int count = 0;
    for (const Layer& layer : recipe.layers)
        for (const Component& c : layer.components)
            if (const auto* f = std::get_if<InterferenceFlake>(&c); f != nullptr && f->volume_fraction > 0.0)
                ++count;
    p.interference = count > 0;
    d.simulate = p.interference;
    d.setting = p.interference ? "thin-film optics of every interference flake, per band" : "none";
    d.reason = p.interference ? std::to_string(count) + " interference flake component(s) in the recipe"
                              : "no interference flakes: the thin-film term is absent, skipping it is exact";
    return d;
}

// --- sparkle ----------------------------------------------------------------

// The 99th percentile of |X - 1| of the texture at these statistics, from
// 4000 draws (its sampling error at the 99th percentile: ~ 5 % of the value).
double texturePercentile99(const SparkleStats& stats) {
    constexpr int kDraws = 4000;
    std::vector<double> x(stats.terms.size());
    std::vector<double> total(kDraws);
    double mean = 0.0;
    for (double f : stats.flake_brdf_per_sr) mean += f;
    if (!(mean > 0.0)) return 0.0;
    for (int i = 0; i < kDraws; ++i) {
        drawSparkle(stats, sparkleCellKey(37.0 * i, 0.0, 0.0, 1.0, 0x706c616eULL), x);
        double sum = 0.0;
        for (std::size_t t = 0; t < x.size(); ++t) {
            double m = 0.0;
            for (double f : stats.terms[t].flake_brdf_per_sr) m += f;
            sum += m * x[t];
        }
        total[static_cast<std::size_t>(i)] = std::abs(sum / mean);
    }
    std::nth_element(total.begin(), total.begin() + kDraws * 99 / 100, total.end());
    return total[static_cast<std::size_t>(kDraws * 99 / 100)];
}

PlanDecision sparkleDecision(const Recipe& recipe, const PlanScene& scene, EffectPlan& p) {
    PlanDecision d;
    d.effect = "sparkle";
    const SparkleModel model(recipe, {.bands = 3, .chain_nodes = 31, .flake_table_cosines = 65});
    if (!model.hasFlakes()) {
        d.simulate = false;
        d.setting = "none";
        d.reason = "no flakes with a spread of orientations: nothing glints, skipping is exact";
        return d;
    }
    if (scene.lights.empty()) {
        d.simulate = false;
        d.setting = "none";
        d.reason = "no compact light: the environment's broad features light thousands of flakes per "
                   "element, which average into the BRDF";
        d.accepted_error_de = 0.0;
        return d;
    }
    // The smallest element the scene shows (largest contrast): the smallest
    // footprint, else the eye's 1 arcmin at the viewing distance, else a
    // close inspection at 0.5 m.
    const double distance = scene.viewing_distance_m > 0.0 ? scene.viewing_distance_m : 0.5;
    std::string element_text;
    double element_side_um = scene.footprint_min_um;
    if (element_side_um > 0.0) {
        element_text = io::formatText("smallest pixel footprint %.3g um", element_side_um);
    } else {
        element_side_um = std::sqrt(eyeElementAreaUm2(distance, 1.0));
        element_text = io::formatText("the eye's 1 arcmin at %.3g m (%.3g um)", distance, element_side_um);
    }
    // Geometries of a multi-angle sparkle instrument (light at 15, 45 and 75
    // deg from a camera on the normal) and the mirror geometry at 30 deg.
    const std::array<std::array<double, 2>, 4> geometries{
        {{15.0, 0.0}, {45.0, 0.0}, {75.0, 0.0}, {30.0, 30.0}}};
    double worst = 0.0;
    std::string worst_text;
    for (const PlanLight& light : scene.lights) {
        for (const auto& [theta_i, theta_o] : geometries) {
            SparkleGeometry g;
            g.wi = directionFromAnglesDeg(theta_i, 0.0);
            g.wo = directionFromAnglesDeg(theta_o, 180.0);
            g.element_area_um2 = element_side_um * element_side_um / g.wo.z;
            g.light_solid_angle_sr = light.solid_angle_sr;
            g.view_solid_angle_sr = viewApertureSr(distance);
            const SparkleStats stats = model.evaluate(g);
            double f = 0.0;
            for (double v : stats.flake_brdf_per_sr)
                f += v / static_cast<double>(stats.flake_brdf_per_sr.size());
            // The flakes' light from this light against everything else the
            // pixel shows: the environment on a dark paint (albedo 0.05: the
            // clear coat's 4 % mirror reflection plus a little diffuse light).
            const double flake_radiance = f * light.irradiance_w_m2 * g.wi.z;
            const double other = 0.05 * scene.environment_radiance;
            if (!(flake_radiance > 0.0)) continue;
            const double share = flake_radiance / (flake_radiance + other);
            const double delta = share * texturePercentile99(stats);
            if (delta > worst) {
                worst = delta;
                worst_text =
                    io::formatText("light at %.0f deg, view at %.0f deg: %.3g glinting flakes per element",
                                   theta_i, theta_o, stats.expected_glints);
                worst_text.append(" from '" + light.name + "'");
            }
        }
    }
    const double skip_error = deltaEForRelativeChange(worst);
    p.sparkle = skip_error > 0.5 * p.tolerance_de;
    d.simulate = p.sparkle;
    d.accepted_error_de = p.sparkle ? 0.0 : skip_error;
    d.skip_error_de = skip_error;
    d.setting = p.sparkle ? "sparkle texture on the paint pixels" : "none";
    d.reason = (p.sparkle ? "resolvable glints: " : "glints average out: ") + worst_text + " at " +
               element_text +
               io::formatText(" (99th percentile |change| %.3g of the pixel, dE00 %.3g)", worst, skip_error);
    if (!p.sparkle) d.reason.append(": the plan accepts that difference");
    return d;
}

// --- angular resolution -----------------------------------------------------

// The truncation error of the azimuthal Fourier series, measured on a probe
// of the paint (the preview grid at the preset's orders, 4 bands): for
// directions every 20 deg, sum_{m >= M} |f^m| s_m against the lobe's peak
// max(|sum f^m s_m|, |sum (-1)^m f^m s_m|) (Delta phi = 0 or pi). s_m =
// exp(-m^2 sigma^2 / 2) is what a light of angular standard deviation sigma
// leaves of order m (a Gaussian's Fourier coefficients; in the azimuth the
// light is sigma / sin(theta) wide, wider than sigma, so this bounds it).
class TruncationProbe {
public:
    TruncationProbe(const Recipe& recipe, int orders, double sigma_rad) {
        FastModelSettings s = presetSettings(Preset::Preview);
        s.orders = orders;
        s.bands = 4;
        s.output_bands = 0;
        s.order_tolerance = 1e-9;
        const LayeredBrdf probe = computeLayeredBrdf(recipe, s);
        m_orders = probe.orders();
        const auto bands = probe.wavelengthsNm().size();
        std::vector<double> c(static_cast<std::size_t>(m_orders) * bands);
        for (int o = 0; o < 4; ++o)
            for (int i = 0; i < 4; ++i) {
                const double mu_o = std::cos((10.0 + 20.0 * o) * kPi / 180.0);
                const double mu_i = std::cos((10.0 + 20.0 * i) * kPi / 180.0);
                probe.fourierCoefficients(mu_o, mu_i, c);
                for (std::size_t b = 0; b < bands; ++b) {
                    std::vector<double> series(static_cast<std::size_t>(m_orders));
                    for (int m = 0; m < m_orders; ++m)
                        series[static_cast<std::size_t>(m)] = c[static_cast<std::size_t>(m) * bands + b] *
                                                              std::exp(-0.5 * m * m * sigma_rad * sigma_rad);
                    m_series.push_back(std::move(series));
                }
            }
    }
    // Largest relative error over the probe's directions and bands when only orders < M are kept.
    double error(int M) const {
        double worst = 0.0;
        for (const auto& series : m_series) {
            double tail = 0.0;
            double even = 0.0;
            double odd = 0.0;
            for (int m = 0; m < m_orders; ++m) {
                const double v = series[static_cast<std::size_t>(m)];
                if (m >= M) tail += std::abs(v);
                even += v;
                odd += (m % 2 == 0 ? v : -v);
            }
            const double peak = std::max({std::abs(even), std::abs(odd), std::abs(series[0])});
            if (peak > 1e-12) worst = std::max(worst, tail / peak);
        }
        return worst;
    }

private:
    int m_orders = 0;
    std::vector<std::vector<double>> m_series;
};

PlanDecision angularDecision(const Recipe& recipe, const PlanScene& scene, EffectPlan& p) {
    PlanDecision d;
    d.effect = "angular";
    // The sharpest light, as an angular standard deviation: a disk of radius
    // r has r / 2 per axis; the environment's feature width is ~1.65 of its
    // standard deviation (plan_scene.h's definition).
    double sigma = scene.environment_sharpness_deg / 1.65 * kPi / 180.0;
    std::string light_text = io::formatText("environment features %.3g deg", scene.environment_sharpness_deg);
    for (const PlanLight& l : scene.lights) {
        const double r = std::sqrt(l.solid_angle_sr / kPi);
        if (l.irradiance_w_m2 > 0.0 && 0.5 * r < sigma) {
            sigma = 0.5 * r;
            light_text = "light '" + l.name + "'" + io::formatText(" %.3g deg across", 2.0 * r * 180.0 / kPi);
        }
    }
    const int preset_orders = p.fast.orders;
    const TruncationProbe probe(recipe, preset_orders, sigma);
    int orders = preset_orders;
    const double budget = relativeChangeFor(0.5 * p.tolerance_de);
    for (int m : {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64}) {
        if (m >= preset_orders) break;
        if (probe.error(m) <= budget) {
            orders = m;
            break;
        }
    }
    const double error = orders < preset_orders ? probe.error(orders) : 0.0;
    p.fast.orders = orders;
    // The polar nodes stay the preset's: their error is not what the
    // truncation probe measures (and the order count is the fast model's
    // cost per band: one adding-doubling per order).
    d.simulate = true;
    d.setting = "orders " + std::to_string(p.fast.orders) + ", nodes " + std::to_string(p.fast.nodes);
    d.accepted_error_de = deltaEForRelativeChange(error);
    d.reason =
        "sharpest light: " + light_text +
        (orders < preset_orders
             ? io::formatText("; the paint's orders >= %.0f seen through it: %.2g %% of the lobe's peak",
                              static_cast<double>(orders), 100.0 * error)
             : std::string("; the preset's orders are needed"));
    return d;
}

// --- spectral bands ---------------------------------------------------------

PlanDecision bandsDecision(const Recipe& recipe, const PlanScene& scene, EffectPlan& p) {
    PlanDecision d;
    d.effect = "bands";
    d.simulate = true;
    const int preset_bands = p.fast.bands;
    if (p.interference || scene.spectral_lighting) {
        d.setting = std::to_string(preset_bands) + " bands (the preset's)";
        d.reason = p.interference ? "interference colours vary fast with wavelength"
                                  : "the lighting is spectral: its variation is not known to the plan";
        return d;
    }
    const double budget = relativeChangeFor(0.5 * p.tolerance_de);
    int bands = preset_bands;
    for (int b : {2, 3, 4, 6, 8, 12, 16, 24, 32}) {
        if (b >= preset_bands) break;
        if (plan_detail::spectralSamplingError(recipe, b) <= budget) {
            bands = b;
            break;
        }
    }
    const double error = bands < preset_bands ? plan_detail::spectralSamplingError(recipe, bands) : 0.0;
    p.fast.bands = bands;
    d.setting = std::to_string(bands) + " bands";
    d.accepted_error_de = deltaEForRelativeChange(error);
    d.reason =
        error == 0.0 && bands < preset_bands
            ? "every spectrum of the recipe is constant: any band count gives the same BRDF"
            : io::formatText("ingredient spectra sampled at %.0f bands are within %.2g %% of their values "
                             "(RGB lighting)",
                             static_cast<double>(bands), 100.0 * error);
    return d;
}

// --- depth slices -----------------------------------------------------------

PlanDecision slicesDecision(const Recipe& recipe, EffectPlan& p) {
    PlanDecision d;
    d.effect = "slices";
    if (!plan_detail::hasDepthProfiles(recipe)) {
        d.simulate = false;
        d.setting = "none";
        d.reason = "no depth profiles: every layer is homogeneous, slicing changes nothing";
        return d;
    }
    const double budget = relativeChangeFor(0.5 * p.tolerance_de);
    int slices = p.fast.slices;
    for (int s : {1, 2, 3, 4, 6, 8}) {
        if (s >= p.fast.slices) break;
        if (plan_detail::sliceConcentrationError(recipe, s) <= budget) {
            slices = s;
            break;
        }
    }
    // The concentration's local error changes the light scattered there by
    // the same fraction at most (first order in the optical thickness).
    const double error = plan_detail::sliceConcentrationError(recipe, slices);
    p.fast.slices = slices;
    d.simulate = true;
    d.setting = std::to_string(slices) + " slices per profiled layer";
    d.accepted_error_de = deltaEForRelativeChange(error);
    d.reason = io::formatText("the concentration varies with depth; %.0f slices hold it within %.2g %%",
                              static_cast<double>(slices), 100.0 * error);
    return d;
}

// --- full model ---------------------------------------------------------------

PlanDecision fullModelDecision(const Recipe& recipe, EffectPlan& p) {
    PlanDecision d;
    d.effect = "full_model";
    const double tolerance = p.preset == Preset::Preview    ? 0.2
                             : p.preset == Preset::Standard ? kDefaultFastModelTolerance
                                                            : 0.05;
    const FastModelValidity v = fastModelValidity(recipe, tolerance);
    p.full_model = !v.within;
    d.simulate = p.full_model;
    d.setting = p.full_model ? "Monte Carlo full model (explicit flakes)" : "fast model only";
    // The image's worst pixels see the worst of the geometries, not their mean.
    const double worst = std::abs(v.largest_rel_difference) > std::abs(v.expected_rel_difference)
                             ? v.largest_rel_difference
                             : v.expected_rel_difference;
    d.skip_error_de = deltaEForRelativeChange(worst);
    d.accepted_error_de = p.full_model ? 0.0 : d.skip_error_de;
    d.reason = v.reason + io::formatText(" (the preset allows %.0f %%)", 100.0 * tolerance);
    return d;
}

}  // namespace

double planToleranceDe(Preset preset) {
    switch (preset) {
    case Preset::Preview:
        return 2.0;
    case Preset::Standard:
        return 1.0;
    case Preset::Reference:
        break;
    }
    return 0.3;
}

double deltaEForRelativeChange(double delta) {
    if (!(delta > -1.0)) return 116.0;
    return 116.0 * std::abs(std::cbrt(1.0 + delta) - 1.0);
}

EffectPlan plan(const Recipe& recipe, const PlanScene& scene, Preset preset) {
    validateRecipe(recipe, recipe.name);
    checkScene(scene);
    EffectPlan p;
    p.preset = preset;
    p.tolerance_de = planToleranceDe(preset);
    p.fast = presetSettings(preset);
    p.decisions.push_back(interferenceDecision(recipe, p));
    p.decisions.push_back(sparkleDecision(recipe, scene, p));
    p.decisions.push_back(angularDecision(recipe, scene, p));
    p.decisions.push_back(bandsDecision(recipe, scene, p));
    p.decisions.push_back(slicesDecision(recipe, p));
    p.decisions.push_back(fullModelDecision(recipe, p));
    return p;
}

FastModelSettings applyPlan(const EffectPlan& plan, FastModelSettings settings) {
    const FastModelSettings preset = presetSettings(plan.preset);
    if (plan.fast.orders < preset.orders) settings.orders = std::min(settings.orders, plan.fast.orders);
    if (plan.fast.bands < preset.bands) settings.bands = std::min(settings.bands, plan.fast.bands);
    if (plan.fast.slices < preset.slices) settings.slices = std::min(settings.slices, plan.fast.slices);
    return settings;
}

std::vector<AppliedDecision> appliedDecisions(const EffectPlan& plan, bool full_model_available) {
    const FastModelSettings preset = presetSettings(plan.preset);
    const auto setting = [](const char* name, int from, int to) {
        return to < from ? io::formatText("%s %d -> %d", name, from, to)
                         : io::formatText("%s %d (the preset's)", name, from);
    };
    std::vector<AppliedDecision> out;
    for (const PlanDecision& d : plan.decisions) {
        std::string applied;
        bool changed = false;
        double accepted = d.accepted_error_de;
        if (d.effect == "angular") {
            applied = setting("orders", preset.orders, plan.fast.orders);
            changed = plan.fast.orders < preset.orders;
        } else if (d.effect == "bands") {
            applied = setting("bands", preset.bands, plan.fast.bands);
            changed = plan.fast.bands < preset.bands;
        } else if (d.effect == "slices") {
            applied = d.simulate ? setting("slices", preset.slices, plan.fast.slices)
                                 : std::string("skipped (exact: no depth profiles)");
            changed = d.simulate && plan.fast.slices < preset.slices;
        } else if (d.effect == "full_model") {
            if (!d.simulate)
                applied = "not needed (fast model only)";
            else if (full_model_available)
                applied = "full model";
            else {
                applied = "advised, not run (the fast model is used; its error here is above the preset's)";
                changed = true;
                accepted = d.skip_error_de;
            }
        } else {
            applied = d.simulate ? "on" : "skipped";
            changed = !d.simulate && d.accepted_error_de > 0.0;
        }
        out.push_back({d.effect, applied, changed, accepted, d.reason});
    }
    return out;
}

}  // namespace paintlab
