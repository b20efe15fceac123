#include "mc_stack.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/optics/fresnel.h"
#include "paintlab/engine/optics/thin_film.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace paintlab::mc {

namespace {

constexpr int kNormalPolar = 32;  // stratified flake normals for E_D[(1 - T)|v.n|]
constexpr int kNormalAzimuth = 64;
constexpr int kRateTableSize = 1025;  // flake collision rate in |cos| (smooth; linear error ~1e-7)

double interpolate(const std::vector<double>& table, double cos_local) {
    const double x = std::clamp(cos_local, 0.0, 1.0) * static_cast<double>(table.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(x), table.size() - 2);
    const double t = x - static_cast<double>(i);
    return (1.0 - t) * table[i] + t * table[i + 1];
}

// The geometry-only tables of a flake kind: copied from `same` (the same
// flakes at another wavelength) when its area density and orientation match.
void tabulateRate(FlakeKind& k, const FlakeKind* same) {
    if (same != nullptr && same->area_density_per_um == k.area_density_per_um &&
        same->orientation.spreadDeg() == k.orientation.spreadDeg() &&
        same->rate_table.size() == static_cast<std::size_t>(kRateTableSize)) {
        k.rate_table = same->rate_table;
        return;
    }
    k.rate_table.resize(kRateTableSize);
    for (int i = 0; i < kRateTableSize; ++i)
        k.rate_table[static_cast<std::size_t>(i)] =
            k.area_density_per_um *
            k.orientation.meanProjectedCos(static_cast<double>(i) / (kRateTableSize - 1));
}

void stratifyNormals(FlakeKind& k, const FlakeKind* same) {
    if (same != nullptr && same->orientation.spreadDeg() == k.orientation.spreadDeg() &&
        !same->normals.empty()) {
        k.normals = same->normals;
        return;
    }
    const int np = k.orientation.isDelta() ? 1 : kNormalPolar;
    const int na = k.orientation.isDelta() ? 1 : kNormalAzimuth;
    k.normals.clear();
    k.normals.reserve(static_cast<std::size_t>(np) * static_cast<std::size_t>(na));
    for (int a = 0; a < np; ++a)
        for (int b = 0; b < na; ++b)
            k.normals.push_back(k.orientation.sample((a + 0.5) / np, (b + 0.5) / na));
}

FlakeKind mirrorKind(const MirrorFlakeContent& f, double binder_n, const FlakeKind* same = nullptr) {
    FlakeKind k;
    k.area_density_per_um = f.area_density_per_um;
    k.orientation = FlakeOrientation(f.orientation_spread_deg);
    k.binder_n = binder_n;
    k.has_metal_index = f.metal_index.has_value();
    if (f.metal_index) k.metal_index = *f.metal_index;
    k.reflectance_normal = f.reflectance.value_or(0.0);
    // R from a table: the complex Fresnel (csqrt, complex division) is costly
    // in the walk's inner loops; linear on 1024 intervals it is within ~1e-6
    // of the formula (FlakeKindTest), and 8 kB stay in cache.
    k.table_R.resize(static_cast<std::size_t>(kMirrorTableSize));
    for (int i = 0; i < kMirrorTableSize; ++i) {
        const double c = static_cast<double>(i) / (kMirrorTableSize - 1);
        k.table_R[static_cast<std::size_t>(i)] =
            k.has_metal_index ? metalFlakeReflectance(c, k.metal_index, binder_n)
                              : mirrorFlakeReflectanceFromNormal(c, k.reflectance_normal);
    }
    tabulateRate(k, same);
    return k;
}

FlakeKind interferenceKind(const InterferenceFlakeContent& f, double binder_n, double wavelength_nm,
                           int table_cosines, const FlakeKind* same = nullptr) {
    FlakeKind k;
    k.area_density_per_um = f.area_density_per_um;
    k.orientation = FlakeOrientation(f.orientation_spread_deg);
    k.binder_n = binder_n;
    k.interference = true;
    InterferenceFlakeOptics optics;
    optics.binder_n = binder_n;
    optics.mica_n = f.mica_index;
    optics.tio2_n = f.tio2_index;
    optics.mica_thickness_nm = f.mica_thickness_nm;
    optics.mica_thickness_spread_nm = f.mica_thickness_spread_nm;
    optics.tio2_thickness_nm = f.tio2_thickness_nm;
    optics.tio2_thickness_spread_nm = f.tio2_thickness_spread_nm;
    const int size = std::max(table_cosines, 2);
    std::vector<double> cosines(static_cast<std::size_t>(size));
    for (int i = 0; i < size; ++i) cosines[static_cast<std::size_t>(i)] = static_cast<double>(i) / (size - 1);
    k.table_R.assign(cosines.size(), 0.0);
    k.table_T.assign(cosines.size(), 0.0);
    tabulateInterferenceFlake(optics, wavelength_nm, cosines, k.table_R, k.table_T);
    tabulateRate(k, same);
    stratifyNormals(k, same);
    return k;
}

}  // namespace

double FlakeKind::R(double cos_local) const {
    if (!table_R.empty()) return interpolate(table_R, cos_local);
    return exactR(cos_local);
}

double FlakeKind::exactR(double cos_local) const {
    return has_metal_index ? metalFlakeReflectance(cos_local, metal_index, binder_n)
                           : mirrorFlakeReflectanceFromNormal(cos_local, reflectance_normal);
}

double FlakeKind::T(double cos_local) const { return interference ? interpolate(table_T, cos_local) : 0.0; }

double Slice::flakeRate(std::size_t k, double abs_cos) const {
    return interpolate(flakes[k].rate_table, abs_cos);
}

double Slice::chainExtinction(double abs_cos) const {
    double e = sigma_a_per_um + sigma_s_per_um;
    for (std::size_t k = 0; k < flakes.size(); ++k) {
        const FlakeKind& f = flakes[k];
        if (!f.interference) {
            e += flakeRate(k, abs_cos);
            continue;
        }
        // E_D[(1 - T)|v.n|] by stratified normals (the delta: one normal;
        // interferenceKind draws them once).
        const double sin_v = std::sqrt(std::max(0.0, 1.0 - abs_cos * abs_cos));
        double sum = 0.0;
        for (const FlakeNormal& nrm : f.normals) {
            const double c = std::abs(sin_v * nrm.x + abs_cos * nrm.z);
            sum += (1.0 - f.T(c)) * c;
        }
        e += f.area_density_per_um * sum / static_cast<double>(f.normals.size());
    }
    return e;
}

double henyeyGreenstein(double g, double cos_theta) {
    const double d = 1.0 + g * g - 2.0 * g * cos_theta;
    return (1.0 - g * g) / (4.0 * std::numbers::pi * d * std::sqrt(d));
}

double Slice::kernel(const Vec3& v, const Vec3& v_out) const {
    double k = 0.0;
    if (sigma_s_per_um > 0.0) {
        const double c = dot(v, v_out);
        for (const auto& lobe : lobes) k += sigma_s_per_um * lobe.weight * henyeyGreenstein(lobe.g, c);
    }
    for (const auto& f : flakes) {
        if (f.orientation.isDelta()) continue;  // a delta has no density: reached only by the walk
        // Two-sided mirrors reflect v into v_out through the half vector h
        // (Walter et al., EGSR 2007, eq. 14; the fast model's slab_operator.cpp).
        Vec3 h{v_out.x - v.x, v_out.y - v.y, v_out.z - v.z};
        const double len = std::sqrt(dot(h, h));
        if (len < 1e-12) continue;
        h = {h.x / len, h.y / len, h.z / len};
        k += 0.25 * f.area_density_per_um * f.R(std::abs(dot(v, h))) * f.orientation.pdf(h.z);
    }
    return k;
}

double PaintStack::substrateMirrorReflectance(double mu) const {
    const double n_last = slices.back().n;
    switch (substrate) {
    case SubstrateKind::Metal:
        return fresnelReflectance(mu, n_last, metal_index);
    case SubstrateKind::Transparent:
        return fresnelDielectric(mu, below_n / n_last);
    case SubstrateKind::Lambertian:
    case SubstrateKind::Black:
    case SubstrateKind::Operator:  // smooth: no mirror part (mc_bottom.h)
        break;
    }
    return 0.0;
}

std::vector<FlakeKind> layerFlakeKinds(const Layer& layer, double wavelength_nm) {
    const SlabOptics o = slabOptics(layer, wavelength_nm, 0.0, 1.0);
    std::vector<FlakeKind> kinds;
    for (const auto& f : o.mirror_flakes) kinds.push_back(mirrorKind(f, o.binder_index));
    for (const auto& f : o.interference_flakes)
        kinds.push_back(interferenceKind(f, o.binder_index, wavelength_nm, kFlakeTableCosines));
    return kinds;
}

PaintStack buildPaintStack(const Recipe& recipe, double wavelength_nm, int slices_per_profiled_layer,
                           const PaintStack* same_recipe, int flake_table_cosines) {
    PaintStack stack;
    stack.wavelength_nm = wavelength_nm;
    stack.ambient_n = recipe.ambient_refractive_index;
    double depth = 0.0;
    for (std::size_t l = 0; l < recipe.layers.size(); ++l) {
        const Layer& layer = recipe.layers[l];
        if (!(layer.thickness_um > 0.0))
            throw InputError("", "layers[" + std::to_string(l) + "] '" + layer.name + "'.thickness_um",
                             "the Monte Carlo model needs a positive thickness");
        const auto bounds = sliceBoundaries(layer, slices_per_profiled_layer);
        for (std::size_t s = 1; s < bounds.size(); ++s) {
            const SlabOptics o = slabOptics(layer, wavelength_nm, bounds[s - 1], bounds[s]);
            Slice slice;
            slice.top_um = depth + layer.thickness_um * bounds[s - 1];
            slice.bottom_um = depth + layer.thickness_um * bounds[s];
            slice.layer = static_cast<int>(l);
            slice.n = o.binder_index;
            slice.sigma_a_per_um = o.sigma_a_per_um;
            slice.sigma_s_per_um = o.sigma_s_per_um;
            slice.lobes = o.lobes;
            // The same slice of the same recipe at another wavelength, if given.
            const std::size_t index = stack.slices.size();
            const Slice* same = same_recipe != nullptr && index < same_recipe->slices.size()
                                    ? &same_recipe->slices[index]
                                    : nullptr;
            const auto sameKind = [&](std::size_t k) -> const FlakeKind* {
                return same != nullptr && k < same->flakes.size() ? &same->flakes[k] : nullptr;
            };
            for (const auto& f : o.mirror_flakes)
                slice.flakes.push_back(mirrorKind(f, o.binder_index, sameKind(slice.flakes.size())));
            for (const auto& f : o.interference_flakes)
                slice.flakes.push_back(interferenceKind(f, o.binder_index, wavelength_nm, flake_table_cosines,
                                                        sameKind(slice.flakes.size())));
            stack.slices.push_back(std::move(slice));
        }
        depth += layer.thickness_um;
    }
    if (const auto* lambert = std::get_if<LambertianSubstrate>(&recipe.substrate)) {
        stack.substrate = SubstrateKind::Lambertian;
        stack.lambert_albedo = lambert->albedo(wavelength_nm);
    } else if (const auto* metal = std::get_if<MetalSubstrate>(&recipe.substrate)) {
        stack.substrate = SubstrateKind::Metal;
        stack.metal_index = {metal->n(wavelength_nm), metal->k(wavelength_nm)};
    } else if (const auto* transparent = std::get_if<TransparentSubstrate>(&recipe.substrate)) {
        stack.substrate = SubstrateKind::Transparent;
        stack.below_n = transparent->refractive_index;
    }
    if (stack.slices.empty())
        throw InputError("", "layers", "the Monte Carlo model needs at least one layer");
    return stack;
}

Vec3 ExitChain::direction(const PaintStack& stack, std::size_t slice, bool upward) const {
    const double n = stack.slices[slice].n;
    return {sx / n, sy / n, upward ? mu[slice] : -mu[slice]};
}

ExitChain exitChain(const PaintStack& stack, const Direction& wo) {
    ExitChain c;
    const auto count = stack.slices.size();
    const double n0 = stack.ambient_n;
    c.sx = n0 * wo.x;
    c.sy = n0 * wo.y;
    const double s2 = c.sx * c.sx + c.sy * c.sy;
    c.mu.assign(count, 0.0);
    c.extinction.assign(count, 0.0);
    c.up.assign(count, 0.0);
    c.down.assign(count, 0.0);
    if (!(wo.z > 0.0)) return c;
    std::vector<double> a(count, 0.0);  // unscattered transmittance of each slice
    std::vector<double> r(count, 0.0);  // reflectance of the interface above each slice
    for (std::size_t j = 0; j < count; ++j) {
        const Slice& slice = stack.slices[j];
        const double sin2 = s2 / (slice.n * slice.n);
        if (sin2 < 1.0) {
            c.mu[j] = std::sqrt(1.0 - sin2);
            c.extinction[j] = slice.chainExtinction(c.mu[j]);
            a[j] = std::exp(-c.extinction[j] * slice.thicknessUm() / c.mu[j]);
        }
        const double n_above = j == 0 ? n0 : stack.slices[j - 1].n;
        const double mu_above = j == 0 ? wo.z : c.mu[j - 1];
        if (std::abs(n_above - slice.n) < 1e-12)
            r[j] = 0.0;
        else
            r[j] = mu_above > 0.0 ? fresnelDielectric(mu_above, slice.n / n_above) : 1.0;
    }
    const auto loop = [](double x) { return x < 1.0 ? 1.0 / (1.0 - x) : 0.0; };
    // B[j]: reflectance below the bottom of slice j for a downward ray (scalar adding upwards).
    std::vector<double> B(count, 0.0);
    B[count - 1] = c.mu[count - 1] > 0.0 ? stack.substrateMirrorReflectance(c.mu[count - 1]) : 0.0;
    for (std::size_t j = count - 1; j-- > 0;) {
        const double below = a[j + 1] * a[j + 1] * B[j + 1];
        const double t = 1.0 - r[j + 1];
        B[j] = r[j + 1] + t * t * below * loop(r[j + 1] * below);
    }
    // Aup, Tup: reflectance and transmittance (to the ambient) of everything
    // above the top of slice j, for an upward ray (adding downwards).
    double Aup = r[0];
    double Tup = 1.0 - r[0];
    for (std::size_t j = 0; j < count; ++j) {
        if (j > 0) {
            const double t = 1.0 - r[j];
            const double aa = a[j - 1] * a[j - 1];
            Tup = t * a[j - 1] * Tup * loop(Aup * aa * r[j]);
            Aup = r[j] + t * t * aa * Aup * loop(r[j] * aa * Aup);
        }
        if (c.mu[j] <= 0.0) continue;
        const double U = Tup * loop(Aup * a[j] * a[j] * B[j]);
        const double scale = (n0 / stack.slices[j].n) * (n0 / stack.slices[j].n);
        c.up[j] = U * scale;
        c.down[j] = B[j] * a[j] * U * scale;
        if (j + 1 == count) c.lambert = a[j] * U * scale;
    }
    return c;
}

}  // namespace paintlab::mc
