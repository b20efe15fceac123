#include "paintlab/engine/layer_optics.h"

#include <algorithm>
#include <cmath>

namespace paintlab {

double SlabOptics::albedo() const noexcept {
    const double t = sigmaT();
    return t > 0.0 ? sigma_s_per_um / t : 0.0;
}

double SlabOptics::opticalThickness() const noexcept { return sigmaT() * thickness_um; }

double SlabOptics::meanCosine() const noexcept {
    double g = 0.0;
    for (const auto& lobe : lobes) g += lobe.weight * lobe.g;
    return g;
}

double meanRelativeConcentration(const std::optional<DepthProfile>& profile, double z0, double z1) {
    if (!profile || !(z1 > z0)) return 1.0;
    const double mean = profile->meanWeight();
    if (!(mean > 0.0)) return 0.0;
    // Integrate the piecewise-linear w over [z0, z1]: trapezoids between the
    // slab ends and every profile node inside, exact for a piecewise-linear function.
    std::vector<double> nodes{z0};
    for (double z : profile->depth)
        if (z > z0 && z < z1) nodes.push_back(z);
    nodes.push_back(z1);
    double integral = 0.0;
    for (std::size_t i = 1; i < nodes.size(); ++i)
        integral +=
            0.5 * (profile->weightAt(nodes[i - 1]) + profile->weightAt(nodes[i])) * (nodes[i] - nodes[i - 1]);
    return integral / (z1 - z0) / mean;
}

std::vector<double> sliceBoundaries(const Layer& layer, int slice_count) {
    const bool varies = std::any_of(layer.components.begin(), layer.components.end(), [](const Component& c) {
        const auto* p = componentDepthProfile(c);
        return p != nullptr && p->has_value();
    });
    const int count = varies ? std::max(1, slice_count) : 1;
    std::vector<double> bounds(static_cast<std::size_t>(count) + 1);
    for (int i = 0; i <= count; ++i) bounds[static_cast<std::size_t>(i)] = static_cast<double>(i) / count;
    return bounds;
}

namespace {

struct SlabBuilder {
    SlabOptics& slab;
    double wavelength_nm;
    double z0;
    double z1;
    std::vector<std::pair<double, double>> scattering;  // (sigma_s, g) per scatterer

    void operator()(const Pigment& p) {
        const double c = p.volume_fraction * meanRelativeConcentration(p.depth_profile, z0, z1);
        slab.sigma_a_per_um += c * p.sigma_a_per_um(wavelength_nm);
        const double s = c * p.sigma_s_per_um(wavelength_nm);
        slab.sigma_s_per_um += s;
        if (s > 0.0) scattering.emplace_back(s, p.hg_g);
    }

    void operator()(const RawMedium& r) {
        // The raw medium's optical thickness belongs to the whole layer; this
        // slab holds its share (z1 - z0) of it.
        const double tau = r.optical_thickness(wavelength_nm) * (z1 - z0);
        const double sigma_t = slab.thickness_um > 0.0 ? tau / slab.thickness_um : 0.0;
        const double a = r.albedo(wavelength_nm);
        slab.sigma_a_per_um += (1.0 - a) * sigma_t;
        slab.sigma_s_per_um += a * sigma_t;
        if (a * sigma_t > 0.0) scattering.emplace_back(a * sigma_t, r.hg_g);
    }

    void operator()(const MirrorFlake& f) {
        MirrorFlakeContent o;
        // A flake of thickness t occupies t per unit area of one face: volume
        // fraction c gives c / t of flake area per unit volume.
        const double c = f.volume_fraction * meanRelativeConcentration(f.depth_profile, z0, z1);
        o.area_density_per_um = c / f.thickness_um;
        o.orientation_spread_deg = f.orientation_spread_deg;
        o.diameter_um = f.diameter_um;
        if (f.reflectance) o.reflectance = (*f.reflectance)(wavelength_nm);
        if (f.metal_n && f.metal_k)
            o.metal_index = std::complex<double>((*f.metal_n)(wavelength_nm), (*f.metal_k)(wavelength_nm));
        if (o.area_density_per_um > 0.0) slab.mirror_flakes.push_back(o);
    }

    void operator()(const InterferenceFlake& f) {
        InterferenceFlakeContent o;
        const double thickness_um = (f.mica_thickness_nm + 2.0 * f.tio2_thickness_nm) * 1e-3;
        const double c = f.volume_fraction * meanRelativeConcentration(f.depth_profile, z0, z1);
        o.area_density_per_um = thickness_um > 0.0 ? c / thickness_um : 0.0;
        o.orientation_spread_deg = f.orientation_spread_deg;
        o.diameter_um = f.diameter_um;
        o.mica_thickness_nm = f.mica_thickness_nm;
        o.mica_thickness_spread_nm = f.mica_thickness_spread_nm;
        o.tio2_thickness_nm = f.tio2_thickness_nm;
        o.tio2_thickness_spread_nm = f.tio2_thickness_spread_nm;
        o.mica_index = f.mica_refractive_index(wavelength_nm);
        o.tio2_index = f.tio2_refractive_index(wavelength_nm);
        if (o.area_density_per_um > 0.0) slab.interference_flakes.push_back(o);
    }
};

}  // namespace

SlabOptics slabOptics(const Layer& layer, double wavelength_nm, double z0, double z1) {
    SlabOptics slab;
    slab.thickness_um = layer.thickness_um * (z1 - z0);
    slab.binder_index = layer.binder.refractive_index(wavelength_nm);
    slab.sigma_a_per_um = layer.binder.absorption_per_um(wavelength_nm);
    SlabBuilder builder{slab, wavelength_nm, z0, z1, {}};
    for (const auto& component : layer.components) std::visit(builder, component);
    for (const auto& [s, g] : builder.scattering) slab.lobes.push_back({s / slab.sigma_s_per_um, g});
    return slab;
}

}  // namespace paintlab
