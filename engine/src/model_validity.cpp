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
// x = d sqrt(1/H^2 + 1/ell^2), a smooth d / min(H, ell). The report fits
// the hiding factor
//   1 + h = 1 + A * E(tau, T) * x^p / (x^p + x0^p).
//
// Surface depletion (model_validity.h). The full model's tile keeps a flake
// of radius r and tilt theta inside its film of thickness H: the centre is
// uniform in [delta, H - delta], delta = r sin(theta) (flake_tile.cpp), and
// a ray meets the flake at a point uniform over the disk, whose depth is the
// centre's plus delta u, u distributed by the semicircle law
// (2/pi) sqrt(1 - u^2) on [-1, 1]. The continuum has the reflecting depth
// uniform in [0, H]. A reflection at depth z reaches the viewer weighted by
// exp(-kappa z), kappa = sigma (1/mu_i + 1/mu_o) along the refracted ways in
// and out (sigma: the continuous medium's extinction; the flakes' own is
// left out: a fitted share of it came out at 0 to 0.09 and did not lower the
// residuals, the hiding factor already carries the flakes' correlation), so
// the full model's flake signal is the continuum's times
//   F = [(e^(-kappa delta) - e^(-kappa (H - delta))) / (kappa (H - 2 delta))]
//       * [2 I1(kappa delta) / (kappa delta)] / [(1 - e^(-kappa H)) / (kappa H)],
// the second factor being E[exp(-kappa delta u)] for the semicircle law (I1
// the modified Bessel function). F -> 1 as delta -> 0 (horizontal flakes, the
// exact two-stream case) or kappa -> 0 (a clear film sees all depths alike).
// The flakes that reflect at a geometry are tilted by the half vector's
// angle theta_h, so at each of the six multi-angle geometries
//   expected = (1 + h) F(theta_h) - 1,
// and the paint's figure is their mean weighted by the flakes' signal
// D(theta_h) there (the demo pearlescent's fast-model f follows D within
// 10 %). F has no constant of its own; with the hiding's three fitted over
// the whole report, the absorbing-film series (grey absorber 0.05-0.5 /µm,
// flakes 5-50 µm: measured 0 to -78 %) is this to 1.2 points RMS for the
// pearl and 3.5 for metal (largest residual 8 points, 50 µm metal).

#include "paintlab/engine/model_validity.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/number_format.h"
#include "paintlab/engine/layer_optics.h"
#include "paintlab/engine/multiangle.h"
#include "paintlab/engine/optics/flake_orientation.h"
#include "paintlab/engine/optics/thin_film.h"
#include "paintlab/engine/recipe_validation.h"

#include "montecarlo/flake_polygon.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

namespace paintlab {

namespace {

// Fitted to the points of docs/fast_vs_full.csv (every visible geometry of
// the grid, the small-flake series and the absorbing-film series, by
// tools/compare_report/fit_boundary.py: least squares weighted by
// 1 / (se^2 + 0.03^2)). Residuals of the weighted difference over the 120
// paints: RMS 6.6 points, largest 40 (metal at the maximum concentration,
// +108 % measured: correlated multiple reflections the single-scattering
// factor does not hold).
constexpr double kAmplitude = 0.725;
constexpr double kX0 = 1.719;
constexpr double kPower = 1.062;

// The report's incidence: the multi-angle illumination (45° in air), refracted into the binder.
constexpr double kIncidenceDeg = kMultiAngleIlluminationDeg;
// An interference flake's transmittance and the film's extinction are
// averaged over 400-700 nm (the report's band means) every 10 nm.
constexpr double kMinNm = 400.0;
constexpr double kStepNm = 10.0;
constexpr int kWavelengths = 31;
// A geometry where the flakes send less than this share of their brightest
// signal is a ratio of two small numbers (as in the report, VISIBLE_FRACTION).
constexpr double kVisibleFraction = 0.03;

struct FlakeTerm {
    double tau = 0.0;            // extinction optical thickness along the refracted beam
    double transmittance = 0.0;  // of one flake, straight on (0 for metal)
    double x = 0.0;              // diameter over min(film thickness, extinction free path)
    double coverage = 0.0;       // flake area per unit film area
    double diameter_um = 0.0;
    double radius_um = 0.0;  // circumradius of the full model's polygon (flake_polygon.h)
    double spread_deg = 0.0;
    std::string what;  // layer and component, for the reason
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

// The continuous medium's extinction (binder, pigments, raw media), 400-700 nm mean, 1/µm.
double mediumExtinctionPerUm(const Layer& layer) {
    double sum = 0.0;
    for (int i = 0; i < kWavelengths; ++i) sum += slabOptics(layer, kMinNm + kStepNm * i).sigmaT();
    return sum / kWavelengths;
}

std::string componentLabel(std::size_t layer_index, const Layer& layer, const Component& component) {
    std::string text = "layer ";
    text.append(std::to_string(layer_index + 1)).append(" '").append(layer.name).append("' ");
    text.append(componentKind(component)).append(" '").append(componentName(component)).append("'");
    return text;
}

FlakeTerm flakeTerm(const Layer& layer, double volume_fraction, double thickness_um, double diameter_um,
                    double spread_deg, double transmittance, double mu) {
    FlakeTerm term;
    term.transmittance = transmittance;
    const double extinction = 1.0 - transmittance;
    const double H = layer.thickness_um;
    term.coverage = volume_fraction * H / thickness_um;
    term.tau = extinction * term.coverage / mu;
    // Extinction area per volume (1/µm): the inverse free path between flakes.
    // hypot: a smooth min(H, ell), which fits the report better than min().
    term.x = diameter_um * std::hypot(1.0 / H, extinction * volume_fraction / thickness_um);
    term.diameter_um = diameter_um;
    term.radius_um = 0.5 * diameter_um * mc::flakeCircumradiusFactor();
    term.spread_deg = spread_deg;
    return term;
}

// E(tau, T) above: expm1 keeps it accurate as tau -> 0 (where it -> (1 - T) tau / 2).
double hidingExcess(double tau, double T) {
    return 2.0 / (1.0 + T) * std::expm1(-(1.0 + T) * tau) / std::expm1(-2.0 * tau) - 1.0;
}

// h above: the hiding factor's excess over 1.
double hidingDifference(double tau, double T, double x) {
    if (!(tau > 0.0) || !(x > 0.0)) return 0.0;
    const double xp = std::pow(x, kPower);
    return kAmplitude * std::max(0.0, hidingExcess(tau, T)) * xp / (xp + std::pow(kX0, kPower));
}

}  // namespace

// F above, for extinction kappa (1/µm of depth, both ways), film H and half-height delta (µm).
double tiltedFlakeSurfaceDepletion(double kappa, double H, double delta) {
    if (!(delta > 0.0) || !(kappa > 0.0) || !(H > 0.0)) return 1.0;
    const double continuum = -std::expm1(-kappa * H) / (kappa * H);
    if (!(H > 2.0 * delta)) {
        // A flake that cannot fit: the tile places its centre anywhere in the
        // film and it pokes out into the layers beside, which this film's
        // extinction does not reach; the hit depths' spread is then left out.
        return 1.0;
    }
    // centres * spread with e^(-kappa delta) folded into the Bessel function:
    // e^(-t) I1(t) stays finite for large t (I1 ~ e^t / sqrt(2 pi t)).
    const double t = kappa * delta;
    double spread_at_top = 0.0;  // e^(-t) * 2 I1(t) / t
    if (t < 1e-6)
        spread_at_top = std::exp(-t) * (1.0 + t * t / 8.0);
    else if (t < 500.0)
        spread_at_top = std::exp(-t) * 2.0 * std::cyl_bessel_i(1.0, t) / t;
    else
        spread_at_top = 2.0 / t * (1.0 - 3.0 / (8.0 * t)) / std::sqrt(2.0 * std::numbers::pi * t);
    const double span = H - 2.0 * delta;
    const double centres = -std::expm1(-kappa * span) / (kappa * span);  // over e^(-kappa delta)
    return spread_at_top * centres / continuum;
}

namespace {

struct MultiAngleBinder {
    double aspecular_deg = 0.0;
    double mu_i = 1.0;  // cosines of the refracted ways in and out
    double mu_o = 1.0;
    double tilt_rad = 0.0;  // of the half vector: the flakes that reflect here
};

// A direction in air refracted into a binder of index n (Snell: the tangential part shrinks by 1/n).
Direction refractedInto(const Direction& w, double n) {
    const double tx = w.x / n;
    const double ty = w.y / n;
    return {tx, ty, std::sqrt(std::max(0.0, 1.0 - tx * tx - ty * ty))};
}

// The six multi-angle geometries (multiangle.h: multiAngleDirections, the one
// conversion to directions) refracted into a binder of index n.
std::vector<MultiAngleBinder> multiAngleInBinder(double n) {
    std::vector<MultiAngleBinder> out;
    for (double aspecular : kAspecularAnglesDeg) {
        const MultiAngleGeometry g = multiAngleDirections(kIncidenceDeg, aspecular);
        const Direction wi = refractedInto(g.wi, n);
        const Direction wo = refractedInto(g.wo, n);
        // The half vector wi + wo: its tilt from the normal is the reflecting flakes'.
        const double h_tangential = std::hypot(wi.x + wo.x, wi.y + wo.y);
        out.push_back({aspecular, wi.z, wo.z, std::atan2(h_tangential, wi.z + wo.z)});
    }
    return out;
}

struct LayerExpectation {
    double weighted = 0.0;
    double largest = 0.0;
    double largest_at_deg = 0.0;
    double x = 0.0;  // the flakes' x, weighted by their optical thickness
};

// Expected difference of one layer's flakes at the six geometries.
LayerExpectation layerExpectation(const Layer& layer, const std::vector<FlakeTerm>& terms, double n_layer) {
    double tau = 0.0;
    double x_weighted = 0.0;
    double T_weighted = 0.0;
    for (const auto& term : terms) {
        tau += term.tau;
        x_weighted += term.tau * term.x;
        T_weighted += term.tau * term.transmittance;
    }
    LayerExpectation e;
    e.x = x_weighted / tau;
    const double h = hidingDifference(tau, T_weighted / tau, e.x);
    const double sigma = mediumExtinctionPerUm(layer);
    struct AtGeometry {
        double aspecular_deg;
        double weight;
        double expected;
    };
    std::vector<AtGeometry> at;
    for (const MultiAngleBinder& g : multiAngleInBinder(n_layer)) {
        const double kappa = sigma * (1.0 / g.mu_i + 1.0 / g.mu_o);
        // The flakes of one layer: their depletions weighted by their share of the signal here.
        double weight = 0.0;
        double depleted = 0.0;
        for (const auto& term : terms) {
            const double w = term.tau * FlakeOrientation(term.spread_deg).pdf(std::cos(g.tilt_rad));
            weight += w;
            depleted += w * tiltedFlakeSurfaceDepletion(kappa, layer.thickness_um,
                                                        term.radius_um * std::sin(g.tilt_rad));
        }
        const double F = weight > 0.0 ? depleted / weight : 1.0;
        at.push_back({g.aspecular_deg, weight, (1.0 + h) * F - 1.0});
    }
    double peak = 0.0;
    double total = 0.0;
    for (const auto& a : at) {
        peak = std::max(peak, a.weight);
        total += a.weight;
    }
    if (!(total > 0.0)) {
        // Perfectly aligned flakes (spread 0) reflect at none of the six
        // geometries: only the hiding factor remains (the two-stream case).
        e.weighted = e.largest = h;
        return e;
    }
    for (const auto& a : at) {
        e.weighted += a.weight * a.expected / total;
        if (a.weight >= kVisibleFraction * peak && std::abs(a.expected) > std::abs(e.largest)) {
            e.largest = a.expected;
            e.largest_at_deg = a.aspecular_deg;
        }
    }
    return e;
}

}  // namespace

FastModelValidity fastModelValidity(const Recipe& recipe, double tolerance) {
    if (!(tolerance > 0.0 && tolerance <= 1.0))
        throw InputError("<argument>", "tolerance", std::to_string(tolerance) + " must be in (0, 1]");
    validateRecipe(recipe, recipe.name);

    FastModelValidity result;
    result.tolerance = tolerance;
    const Direction incidence = multiAngleDirections(kIncidenceDeg, 0.0).wi;
    std::string worst;
    bool any_flakes = false;
    bool first = true;
    for (std::size_t l = 0; l < recipe.layers.size(); ++l) {
        const Layer& layer = recipe.layers[l];
        const double n_layer = layer.binder.refractive_index(550.0);
        const double mu = refractedInto(incidence, n_layer).z;
        std::vector<FlakeTerm> terms;
        terms.reserve(layer.components.size());
        for (const auto& component : layer.components) {
            FlakeTerm term;
            if (const auto* m = std::get_if<MirrorFlake>(&component)) {
                term = flakeTerm(layer, m->volume_fraction, m->thickness_um, m->diameter_um,
                                 m->orientation_spread_deg, 0.0, mu);
            } else if (const auto* p = std::get_if<InterferenceFlake>(&component)) {
                const double t_um = (p->mica_thickness_nm + 2.0 * p->tio2_thickness_nm) * 1e-3;
                term = flakeTerm(layer, p->volume_fraction, t_um, p->diameter_um, p->orientation_spread_deg,
                                 flakeTransmittance(*p, layer), mu);
            } else {
                continue;
            }
            if (!(term.tau > 0.0)) continue;
            any_flakes = true;
            term.what = componentLabel(l, layer, component);
            terms.push_back(std::move(term));
        }
        if (terms.empty()) continue;
        const LayerExpectation e = layerExpectation(layer, terms, n_layer);
        // The layer with the largest expected difference speaks for the paint.
        if (first || std::abs(e.weighted) > std::abs(result.expected_rel_difference)) {
            first = false;
            result.expected_rel_difference = e.weighted;
            result.largest_rel_difference = e.largest;
            result.largest_at_aspecular_deg = e.largest_at_deg;
            const FlakeTerm* dominant = &terms.front();
            for (const auto& term : terms)
                if (term.tau * term.x > dominant->tau * dominant->x) dominant = &term;
            worst = dominant->what;
            worst.append(io::formatText(
                ": coverage %.3g flake layers, diameter over film and free path %.3g, diameter / "
                "film %.3g; at 45as%.0f %+.1f %%",
                dominant->coverage, e.x, dominant->diameter_um / layer.thickness_um, e.largest_at_deg,
                100.0 * e.largest));
        }
    }
    result.within = std::abs(result.expected_rel_difference) <= tolerance;
    if (!any_flakes) {
        result.reason = "no flakes that take light out of the beam: both models solve the same "
                        "radiative-transfer equation";
        return result;
    }
    result.reason = io::formatText("expected difference %+.1f %% (%s %.0f %%; %s) from ",
                                   100.0 * result.expected_rel_difference, result.within ? "within" : "above",
                                   100.0 * tolerance,
                                   result.expected_rel_difference >= 0.0
                                       ? "the full model brighter: flakes hide one another"
                                       : "the full model darker: tilted flakes cannot reach the film's top");
    result.reason.append(worst);
    return result;
}

}  // namespace paintlab
