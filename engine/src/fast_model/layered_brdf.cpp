#include "paintlab/engine/layered_brdf.h"

#include "stack_assembly.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/fresnel.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numbers>

namespace paintlab {

Preset presetFromName(std::string_view name) {
    if (name == "preview") return Preset::Preview;
    if (name == "standard") return Preset::Standard;
    if (name == "reference") return Preset::Reference;
    throw InputError("<argument>", "preset",
                     "unknown preset '" + std::string(name) + "' (expected preview, standard or reference)");
}

std::string_view presetName(Preset preset) {
    switch (preset) {
    case Preset::Preview:
        return "preview";
    case Preset::Standard:
        return "standard";
    case Preset::Reference:
        return "reference";
    }
    return "standard";
}

FastModelSettings presetSettings(Preset preset) {
    // Points on the accuracy-vs-time curves (docs/PERFORMANCE.md).
    switch (preset) {
    case Preset::Preview:
        return {.nodes = 12,
                .orders = 8,
                .bands = 8,
                .max_start_tau = 1.0 / 64.0,
                .slices = 2,
                .flake_polar = 12,
                .flake_azimuth = 24};
    case Preset::Standard:
        return {.nodes = 24,
                .orders = 16,
                .bands = 16,
                .max_start_tau = 1.0 / 256.0,
                .slices = 4,
                .flake_polar = 24,
                .flake_azimuth = 48};
    case Preset::Reference:
        return {.nodes = 48,
                .orders = 48,
                .bands = 41,
                .max_start_tau = 1.0 / 4096.0,
                .slices = 8,
                .flake_polar = 64,
                .flake_azimuth = 128};
    }
    return {};
}

namespace {

LayeredBrdf::BandTable tabulateBand(const Recipe& recipe, double wavelength_nm,
                                    const FastModelSettings& settings) {
    const fast::BandStack stack = fast::buildBandStack(recipe, wavelength_nm, settings);
    const fast::MediumNodes air = stack.grid.medium(stack.ambient_index);
    const int na = static_cast<int>(air.node.size());
    LayeredBrdf::BandTable table;
    table.mu = air.quadrature.mu;
    table.flux_weight.resize(na);
    for (int i = 0; i < na; ++i) table.flux_weight(i) = air.quadrature.fluxWeight(i);
    // The top interface's mirror term, reported apart from the BRDF.
    const double n_top = recipe.layers.front().binder.refractive_index(wavelength_nm);
    table.specular.resize(na);
    for (int i = 0; i < na; ++i)
        table.specular(i) =
            fresnelDielectric(table.mu[static_cast<std::size_t>(i)], n_top / stack.ambient_index);
    for (int m = 0; m < settings.orders; ++m) {
        const Eigen::MatrixXd R = fast::stackReflection(stack, m, settings);
        Eigen::MatrixXd f(na, na);
        for (int i = 0; i < na; ++i)
            for (int j = 0; j < na; ++j)
                f(i, j) = R(air.node[static_cast<std::size_t>(i)], air.node[static_cast<std::size_t>(j)]);
        if (m == 0) table.albedo = f.colwise().sum().transpose();
        if (std::abs(n_top - stack.ambient_index) > 1e-9) f.diagonal() -= table.specular;
        // Flux-to-flux G to BRDF: f = G / (pi c_out) (a Lambertian G = rho c gives rho / pi).
        // Stored divided by the top interface's transmittance in and out: everything
        // below the coat leaves through it, and (1 - r(mu)) is what varies fast near
        // grazing, so the quotient is smooth and interpolates well in mu.
        for (int i = 0; i < na; ++i) {
            f.row(i) /= std::numbers::pi * table.flux_weight(i) * (1.0 - table.specular(i));
            f.col(i) /= 1.0 - table.specular(i);
        }
        table.f.push_back(std::move(f));
    }
    return table;
}

// Linear interpolation weights of x on an ascending grid, held constant beyond the ends.
struct Lerp {
    int i0 = 0;
    int i1 = 0;
    double t = 0.0;
};

Lerp lerpOn(const std::vector<double>& grid, double x) {
    const int n = static_cast<int>(grid.size());
    if (n == 1 || x <= grid.front()) return {0, 0, 0.0};
    if (x >= grid.back()) return {n - 1, n - 1, 0.0};
    const auto it = std::upper_bound(grid.begin(), grid.end(), x);
    const int i1 = static_cast<int>(it - grid.begin());
    const int i0 = i1 - 1;
    return {i0, i1,
            (x - grid[static_cast<std::size_t>(i0)]) /
                (grid[static_cast<std::size_t>(i1)] - grid[static_cast<std::size_t>(i0)])};
}

double bilinear(const Eigen::MatrixXd& f, const Lerp& a, const Lerp& b) {
    return (1 - a.t) * ((1 - b.t) * f(a.i0, b.i0) + b.t * f(a.i0, b.i1)) +
           a.t * ((1 - b.t) * f(a.i1, b.i0) + b.t * f(a.i1, b.i1));
}

}  // namespace

LayeredBrdf computeLayeredBrdf(const Recipe& recipe, const FastModelSettings& settings,
                               const ProgressCallback& progress) {
    const auto start = std::chrono::steady_clock::now();
    LayeredBrdf brdf;
    brdf.m_settings = settings;
    brdf.m_wavelengths_nm = visibleBands(static_cast<std::size_t>(std::max(2, settings.bands)));
    brdf.m_ambient_index = recipe.ambient_refractive_index;
    brdf.m_bands.resize(brdf.m_wavelengths_nm.size());
    std::atomic<bool> cancelled{false};
    std::atomic<int> done{0};
    std::mutex progress_mutex;
    const auto count = static_cast<int>(brdf.m_wavelengths_nm.size());
    // Bands are independent: one task each (Eigen runs single-threaded inside).
    tbb::parallel_for(0, count, [&](int b) {
        if (cancelled.load()) return;
        brdf.m_bands[static_cast<std::size_t>(b)] =
            tabulateBand(recipe, brdf.m_wavelengths_nm[static_cast<std::size_t>(b)], settings);
        const int finished = ++done;
        if (progress) {
            const std::lock_guard lock(progress_mutex);
            if (!progress(double(finished) / count)) cancelled = true;
        }
    });
    if (cancelled) throw Error("fast model: cancelled");
    for (double nm : brdf.m_wavelengths_nm)
        brdf.m_top_index_per_band.push_back(recipe.layers.front().binder.refractive_index(nm));
    brdf.m_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return brdf;
}

void LayeredBrdf::eval(const Direction& wi, const Direction& wo, std::span<double> out) const {
    std::fill(out.begin(), out.end(), 0.0);
    if (!(wi.z > 0.0) || !(wo.z > 0.0)) return;
    // Azimuth difference of the propagation directions: the light travels along
    // -wi (azimuth phi_i + pi), so delta = phi_o - phi_i - pi and cos(m delta) = (-1)^m cos(m (phi_o -
    // phi_i)).
    const double phi_i = std::atan2(wi.y, wi.x);
    const double phi_o = std::atan2(wo.y, wo.x);
    const double dphi = phi_o - phi_i;
    for (std::size_t b = 0; b < m_bands.size() && b < out.size(); ++b) {
        const BandTable& t = m_bands[b];
        const Lerp a = lerpOn(t.mu, std::min(1.0, wo.z));
        const Lerp c = lerpOn(t.mu, std::min(1.0, wi.z));
        const double eta = m_top_index_per_band[b] / m_ambient_index;
        const double transmit = (1.0 - fresnelDielectric(wi.z, eta)) * (1.0 - fresnelDielectric(wo.z, eta));
        double value = 0.0;
        for (std::size_t m = 0; m < t.f.size(); ++m) {
            const double sign = (m % 2 == 0) ? 1.0 : -1.0;
            const double weight = m == 0 ? 1.0 : 2.0 * sign * std::cos(double(m) * dphi);
            value += weight * bilinear(t.f[m], a, c);
        }
        out[b] = std::max(0.0, transmit * value);  // a truncated Fourier series can ring slightly below zero
    }
}

std::vector<double> LayeredBrdf::specularReflectance(double cos_theta) const {
    std::vector<double> r;
    for (double n_top : m_top_index_per_band)
        r.push_back(fresnelDielectric(cos_theta, n_top / m_ambient_index));
    return r;
}

std::vector<double> LayeredBrdf::albedo(const Direction& wi) const {
    std::vector<double> a;
    for (const auto& t : m_bands) {
        const Lerp l = lerpOn(t.mu, std::clamp(wi.z, 0.0, 1.0));
        a.push_back((1 - l.t) * t.albedo(l.i0) + l.t * t.albedo(l.i1));
    }
    return a;
}

std::vector<double> LayeredBrdf::diffuseAlbedo() const {
    std::vector<double> a;
    for (const auto& t : m_bands) a.push_back(t.albedo.dot(t.flux_weight));
    return a;
}

}  // namespace paintlab
