// Sparkle statistics (sparkle.h has the definitions and equations (1)-(4)).
//
// The paint at each band is the full model's PaintStack (montecarlo/mc_stack.h):
// the same slices, flake kinds (reflectance at the local cosine, collision
// rate, transmittance of interference flakes) and extinction of the
// unscattered beam that the fast model uses, and the same exit chain, which
// carries radiance from a slice to the ambient through every smooth
// interface (Fresnel, attenuation by the slices above, the multiple
// reflections between parallel interfaces). By reciprocity the chain of the
// light's direction gives the flux that reaches a slice from the light.

#include "paintlab/engine/sparkle/sparkle.h"

#include "montecarlo/mc_stack.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_validation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

namespace paintlab {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kReferenceNm = 560.0;  // where the eye's luminous efficiency peaks (V(lambda) ~ 555 nm)

// A flake kind present in one slice, in the order of the slice's FlakeKinds
// (mc_stack.cpp: mirror flakes first, then interference flakes, each present
// one in component order).
struct SliceFlake {
    int component = 0;
    double diameter_um = 0.0;
};

struct SliceInfo {
    int layer = 0;
    int slice = 0;
    std::vector<SliceFlake> flakes;
};

std::vector<SliceFlake> presentFlakes(const Layer& layer, double z0, double z1) {
    std::vector<SliceFlake> mirrors;
    std::vector<SliceFlake> pearls;
    for (std::size_t c = 0; c < layer.components.size(); ++c) {
        const Component& component = layer.components[c];
        // The same presence test as layer_optics.cpp's SlabBuilder (area density > 0).
        if (const auto* m = std::get_if<MirrorFlake>(&component)) {
            if (m->volume_fraction * meanRelativeConcentration(m->depth_profile, z0, z1) / m->thickness_um >
                0.0)
                mirrors.push_back({static_cast<int>(c), m->diameter_um});
        } else if (const auto* p = std::get_if<InterferenceFlake>(&component)) {
            const double t_um = (p->mica_thickness_nm + 2.0 * p->tio2_thickness_nm) * 1e-3;
            if (t_um > 0.0 &&
                p->volume_fraction * meanRelativeConcentration(p->depth_profile, z0, z1) / t_um > 0.0)
                pearls.push_back({static_cast<int>(c), p->diameter_um});
        }
    }
    mirrors.insert(mirrors.end(), pearls.begin(), pearls.end());
    return mirrors;
}

// Reflectance of a mirror or metal flake at the local cosine, tabulated:
// the complex Fresnel equations cost more than the rest of a pixel's
// statistics. Linear in the cosine on 1025 points: the reflectance is smooth
// there (its second derivative in the cosine is O(1) even near grazing for
// aluminium), so the error is ~ 1e-7 of R.
constexpr int kReflectanceTable = 1025;

struct Band {
    double wavelength_nm = 550.0;
    mc::PaintStack stack;
    // Per chain node k (ambient theta_k = pi/2 k / (nodes - 1)) and slice j:
    // the chain's radiance factor up[j] and the slice's extinction at its cosine.
    std::vector<double> up;
    std::vector<double> extinction;
    // Per slice and flake kind: R on cos = i / (kReflectanceTable - 1) for
    // mirror and metal flakes; empty for interference flakes (their R is
    // already a table, FlakeKind::R).
    std::vector<std::vector<std::vector<double>>> reflectance;

    double R(std::size_t slice, std::size_t kind, double cos_local) const {
        const std::vector<double>& table = reflectance[slice][kind];
        if (table.empty()) return stack.slices[slice].flakes[kind].R(cos_local);
        const double x = std::clamp(cos_local, 0.0, 1.0) * static_cast<double>(kReflectanceTable - 1);
        const auto i = std::min(static_cast<std::size_t>(x), static_cast<std::size_t>(kReflectanceTable - 2));
        const double t = x - static_cast<double>(i);
        return (1.0 - t) * table[i] + t * table[i + 1];
    }
};

}  // namespace

struct SparkleModel::Impl {
    SparkleSettings settings;
    std::vector<double> wavelengths;
    std::vector<Band> bands;
    std::vector<SliceInfo> slices;  // parallel to each band's stack.slices
    std::size_t reference_band = 0;
    bool has_flakes = false;

    // Where an ambient cosine falls on the chain tables' polar grid.
    struct ChainPoint {
        std::size_t k = 0;
        double t = 0.0;
    };
    ChainPoint chainPoint(double mu_ambient) const {
        const int nodes = settings.chain_nodes;
        const double x = std::clamp(std::acos(std::clamp(mu_ambient, 0.0, 1.0)) / (0.5 * kPi), 0.0, 1.0) *
                         static_cast<double>(nodes - 1);
        const auto k = std::min(static_cast<std::size_t>(x), static_cast<std::size_t>(nodes - 2));
        return {k, x - static_cast<double>(k)};
    }
    // Linear interpolation of a chain table in the ambient polar angle.
    double chainAt(const std::vector<double>& table, const ChainPoint& p, std::size_t slice) const {
        const std::size_t count = slices.size();
        return (1.0 - p.t) * table[p.k * count + slice] + p.t * table[(p.k + 1) * count + slice];
    }
};

double SparkleTerm::relativeVariance() const {
    if (!(mean_glints > 0.0)) return 0.0;  // nothing is drawn: the element shows the mean
    return mean_weight_sq / (mean_glints * mean_weight * mean_weight);
}

double eyeElementAreaUm2(double distance_m, double mu_o, double acuity_arcmin) {
    const double side_um = distance_m * 1e6 * acuity_arcmin * kPi / (180.0 * 60.0);
    return mu_o > 0.0 ? side_um * side_um / mu_o : 0.0;
}

double viewApertureSr(double distance_m, double aperture_mm) {
    if (!(distance_m > 0.0)) return 0.0;
    const double r_m = 0.5e-3 * aperture_mm;
    return kPi * r_m * r_m / (distance_m * distance_m);
}

double expectedGlints(double flakes_per_um3, double element_area_um2, double height_um,
                      double normal_pdf_per_sr, double window_sr) {
    return flakes_per_um3 * element_area_um2 * height_um * normal_pdf_per_sr * window_sr;
}

SparkleModel::SparkleModel(const Recipe& recipe, const SparkleSettings& settings)
    : m_impl(std::make_unique<Impl>()) {
    validateRecipe(recipe, recipe.name);
    if (settings.bands < 1 || settings.bands > 81)
        throw InputError("<argument>", "sparkle bands",
                         std::to_string(settings.bands) + " is not in [1, 81]");
    if (settings.slices_per_profiled_layer < 1 || settings.slices_per_profiled_layer > 64)
        throw InputError("<argument>", "sparkle slices_per_profiled_layer",
                         std::to_string(settings.slices_per_profiled_layer) + " is not in [1, 64]");
    if (!(settings.flake_lobe_deg >= 0.0 && settings.flake_lobe_deg <= 10.0))
        throw InputError("<argument>", "sparkle flake_lobe_deg",
                         std::to_string(settings.flake_lobe_deg) + " is not in [0, 10]");
    if (settings.chain_nodes < 3 || settings.chain_nodes > 1025)
        throw InputError("<argument>", "sparkle chain_nodes",
                         std::to_string(settings.chain_nodes) + " is not in [3, 1025]");
    if (settings.flake_table_cosines < 9 || settings.flake_table_cosines > 4097)
        throw InputError("<argument>", "sparkle flake_table_cosines",
                         std::to_string(settings.flake_table_cosines) + " is not in [9, 4097]");
    Impl& m = *m_impl;
    m.settings = settings;

    // Layers of zero thickness hold nothing (the Monte Carlo stack refuses them).
    Recipe paint = recipe;
    std::vector<int> layer_of;
    paint.layers.clear();
    for (std::size_t l = 0; l < recipe.layers.size(); ++l)
        if (recipe.layers[l].thickness_um > 0.0) {
            paint.layers.push_back(recipe.layers[l]);
            layer_of.push_back(static_cast<int>(l));
        }
    if (paint.layers.empty()) return;
    for (std::size_t l = 0; l < paint.layers.size(); ++l) {
        const auto bounds = sliceBoundaries(paint.layers[l], settings.slices_per_profiled_layer);
        for (std::size_t s = 1; s < bounds.size(); ++s)
            m.slices.push_back({layer_of[l], static_cast<int>(s - 1),
                                presentFlakes(paint.layers[l], bounds[s - 1], bounds[s])});
    }

    const int count = settings.bands;
    double best = 1e30;
    for (int b = 0; b < count; ++b) {
        const double nm = count == 1 ? kReferenceNm : 380.0 + 400.0 * b / (count - 1);
        m.wavelengths.push_back(nm);
        if (std::abs(nm - kReferenceNm) < best) {
            best = std::abs(nm - kReferenceNm);
            m.reference_band = static_cast<std::size_t>(b);
        }
    }
    const std::size_t slice_count = m.slices.size();
    // Band 0 first: the others reuse its flakes' geometry-only tables
    // (buildPaintStack's same_recipe), then every band in parallel (each is
    // independent: the result does not depend on the thread count).
    m.bands.resize(static_cast<std::size_t>(count));
    const auto build = [&](std::size_t b) {
        Band& band = m.bands[b];
        band.wavelength_nm = m.wavelengths[b];
        band.stack = mc::buildPaintStack(paint, band.wavelength_nm, settings.slices_per_profiled_layer,
                                         b == 0 ? nullptr : &m.bands[0].stack, settings.flake_table_cosines);
        const auto nodes = static_cast<std::size_t>(settings.chain_nodes);
        band.up.assign(nodes * slice_count, 0.0);
        band.extinction.assign(nodes * slice_count, 0.0);
        for (std::size_t k = 0; k < nodes; ++k) {
            const double theta = 0.5 * kPi * static_cast<double>(k) / static_cast<double>(nodes - 1);
            // The horizon itself carries nothing; its node takes a grazing 89.99 deg.
            const double mu = std::max(std::cos(theta), 1.7e-4);
            const double s = std::sqrt(1.0 - mu * mu);
            const mc::ExitChain chain = mc::exitChain(band.stack, Direction{s, 0.0, mu});
            for (std::size_t j = 0; j < slice_count; ++j) {
                band.up[k * slice_count + j] = chain.up[j];
                band.extinction[k * slice_count + j] = chain.extinction[j];
            }
        }
        band.reflectance.resize(band.stack.slices.size());
        for (std::size_t j = 0; j < band.stack.slices.size(); ++j) {
            const auto& flakes = band.stack.slices[j].flakes;
            band.reflectance[j].resize(flakes.size());
            for (std::size_t k = 0; k < flakes.size(); ++k) {
                if (flakes[k].interference || flakes[k].orientation.isDelta()) continue;
                std::vector<double>& table = band.reflectance[j][k];
                table.resize(kReflectanceTable);
                for (int i = 0; i < kReflectanceTable; ++i)
                    table[static_cast<std::size_t>(i)] =
                        flakes[k].R(static_cast<double>(i) / (kReflectanceTable - 1));
            }
        }
    };
    build(0);
    tbb::parallel_for(std::size_t{1}, static_cast<std::size_t>(count), build);
    for (const auto& slice : m.bands.front().stack.slices)
        for (const auto& kind : slice.flakes)
            if (!kind.orientation.isDelta()) m.has_flakes = true;
}

SparkleModel::~SparkleModel() = default;
SparkleModel::SparkleModel(SparkleModel&&) noexcept = default;
SparkleModel& SparkleModel::operator=(SparkleModel&&) noexcept = default;

std::span<const double> SparkleModel::wavelengthsNm() const { return m_impl->wavelengths; }

bool SparkleModel::hasFlakes() const { return m_impl->has_flakes; }

SparkleStats SparkleModel::evaluate(const SparkleGeometry& g) const {
    SparkleStats stats;
    evaluate(g, stats);
    return stats;
}

void SparkleModel::evaluate(const SparkleGeometry& g, SparkleStats& stats) const {
    const Impl& m = *m_impl;
    const std::size_t band_count = m.bands.size();
    stats.flake_brdf_per_sr.assign(band_count, 0.0);
    stats.expected_glints = 0.0;
    stats.sparkle_probability = 0.0;
    stats.relative_variance = 0.0;
    if (!m.has_flakes || !(g.wi.z > 0.0) || !(g.wo.z > 0.0)) {
        stats.terms.clear();
        return;
    }

    // Terms: one per (slice, flake kind with a density of normals), fixed by
    // the recipe (the vectors of `stats` are reused: no allocation per call
    // once they have their size).
    std::size_t term_count = 0;
    for (std::size_t j = 0; j < m.slices.size(); ++j)
        for (const auto& kind : m.bands.front().stack.slices[j].flakes)
            if (!kind.orientation.isDelta()) ++term_count;
    stats.terms.resize(term_count);
    std::size_t next = 0;
    for (std::size_t j = 0; j < m.slices.size(); ++j) {
        const mc::Slice& slice = m.bands.front().stack.slices[j];
        for (std::size_t k = 0; k < slice.flakes.size(); ++k) {
            if (slice.flakes[k].orientation.isDelta()) continue;
            SparkleTerm& term = stats.terms[next++];
            term.layer = m.slices[j].layer;
            term.component = m.slices[j].flakes[k].component;
            term.slice = m.slices[j].slice;
            term.top_um = slice.top_um;
            term.bottom_um = slice.bottom_um;
            term.diameter_um = m.slices[j].flakes[k].diameter_um;
            term.mean_glints = 0.0;
            term.mean_weight = 1.0;
            term.mean_weight_sq = 1.0;
            term.sigma_e_per_um = 0.0;
            term.half_slope_x = 0.0;
            term.half_slope_y = 0.0;
            term.window_width_rad = 0.0;
            term.flake_brdf_per_sr.assign(band_count, 0.0);
            term.glint_radiance_per_irradiance.assign(band_count, 0.0);
        }
    }

    const Impl::ChainPoint at_i = m.chainPoint(g.wi.z);
    const Impl::ChainPoint at_o = m.chainPoint(g.wo.z);
    for (std::size_t b = 0; b < band_count; ++b) {
        const Band& band = m.bands[b];
        const double n0 = band.stack.ambient_n;
        std::size_t t = 0;
        for (std::size_t j = 0; j < m.slices.size(); ++j) {
            const mc::Slice& slice = band.stack.slices[j];
            std::size_t active = 0;
            for (const auto& kind : slice.flakes)
                if (!kind.orientation.isDelta()) ++active;
            if (active == 0) continue;
            const std::size_t first_term = t;
            t += active;
            const double n = slice.n;
            const double sin2_i = n0 * n0 * (1.0 - g.wi.z * g.wi.z) / (n * n);
            const double sin2_o = n0 * n0 * (1.0 - g.wo.z * g.wo.z) / (n * n);
            if (sin2_i >= 1.0 || sin2_o >= 1.0) continue;  // the direction does not reach this slice
            const double mu_i = std::sqrt(1.0 - sin2_i);
            const double mu_o = std::sqrt(1.0 - sin2_o);
            const double scale = (n0 / n) * (n0 / n);
            const double U_i = m.chainAt(band.up, at_i, j) / scale;  // flux from the ambient into the slice
            const double U_o = m.chainAt(band.up, at_o, j);          // radiance out, (n0/n)^2 included
            const double sigma_e =
                m.chainAt(band.extinction, at_i, j) / mu_i + m.chainAt(band.extinction, at_o, j) / mu_o;
            // Refracted directions (Snell: the tangential part scales by n0 / n) and their half vector.
            const double hx = n0 * (g.wi.x + g.wo.x) / n;
            const double hy = n0 * (g.wi.y + g.wo.y) / n;
            const double hz = mu_i + mu_o;
            const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
            const double h[3] = {hx / len, hy / len, hz / len};
            const double c_d = (n0 * g.wi.x / n) * h[0] + (n0 * g.wi.y / n) * h[1] + mu_i * h[2];
            const double H = slice.thicknessUm();
            const double x = sigma_e * H;
            // int_0^H w dz and int_0^H w^2 dz (expm1 keeps them exact as sigma_e -> 0).
            const double I1 = x > 1e-12 ? -std::expm1(-x) / sigma_e : H;
            // E[w^2] is the reference band's only.
            const double I2 = b != m.reference_band ? 0.0
                              : x > 1e-12           ? -std::expm1(-2.0 * x) / (2.0 * sigma_e)
                                                    : H;
            const double beta = m.settings.flake_lobe_deg * kPi / 180.0;
            const double omega_w = g.light_solid_angle_sr * g.wi.z * n0 * n0 / (n * n * mu_i) +
                                   g.view_solid_angle_sr * g.wo.z * n0 * n0 / (n * n * mu_o) +
                                   kPi * 4.0 * beta * beta;
            std::size_t local = 0;
            for (std::size_t k = 0; k < slice.flakes.size(); ++k) {
                const mc::FlakeKind& kind = slice.flakes[k];
                if (kind.orientation.isDelta()) continue;
                SparkleTerm& term = stats.terms[first_term + local];
                const double d = m.slices[j].flakes[k].diameter_um;
                ++local;
                const double R = band.R(j, k, c_d);
                const double D = kind.orientation.pdf(h[2]);
                const double A = kind.area_density_per_um;
                // Eq. (3): the kernel A R D / 4 of mc_stack.h / slab_operator.cpp, single scattering.
                const double f = U_i * U_o * 0.25 * A * R * D / (mu_i * mu_o) * I1;
                term.flake_brdf_per_sr[b] = f;
                stats.flake_brdf_per_sr[b] += f;
                const double a_f = 0.25 * kPi * d * d;
                const double element = std::max(g.element_area_um2, a_f * c_d / mu_o);
                if (omega_w > 0.0 && g.element_area_um2 > 0.0 && a_f > 0.0) {
                    // Eq. (2) at z = 0, per unit irradiance.
                    term.glint_radiance_per_irradiance[b] =
                        U_i * U_o * (g.wi.z / mu_i) * R / omega_w * a_f * c_d / (mu_o * element);
                }
                if (b != m.reference_band) continue;
                term.sigma_e_per_um = sigma_e;
                term.mean_weight = I1 / H;
                term.mean_weight_sq = I2 / H;
                const double window = omega_w / (4.0 * c_d);
                term.window_width_rad = 2.0 * std::sqrt(window / kPi);
                // Where the window sits: the tilt vector alpha (cos phi, sin phi) of h'.
                const double alpha = std::acos(std::clamp(h[2], -1.0, 1.0));
                const double s_len = std::sqrt(h[0] * h[0] + h[1] * h[1]);
                term.half_slope_x = s_len > 0.0 ? alpha * h[0] / s_len : 0.0;
                term.half_slope_y = s_len > 0.0 ? alpha * h[1] / s_len : 0.0;
                if (omega_w > 0.0 && g.element_area_um2 > 0.0 && a_f > 0.0)
                    term.mean_glints = expectedGlints(A / a_f, element, H, D, window);
            }
        }
    }

    // Totals: Lambda, the probability of at least one glint, and eq. (4) for
    // the sum of the terms with band-mean weights (the terms are independent).
    double mean = 0.0;
    double variance = 0.0;
    for (const auto& term : stats.terms) {
        stats.expected_glints += term.mean_glints;
        double m_t = 0.0;
        for (double v : term.flake_brdf_per_sr) m_t += v;
        m_t /= static_cast<double>(band_count);
        mean += m_t;
        if (m_t > 0.0) variance += m_t * m_t * term.relativeVariance();
    }
    stats.sparkle_probability = -std::expm1(-stats.expected_glints);
    stats.relative_variance = mean > 0.0 ? variance / (mean * mean) : 0.0;
}

}  // namespace paintlab
