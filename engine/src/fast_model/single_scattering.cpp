#include "single_scattering.h"

#include "slab_operator.h"

#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace paintlab::fast {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kFlakeCosines = 17;  // the flakes' extinction is smooth in the cosine (linear in between)

// A slab whose truncated phase function differs from the true one by less
// than this (in units of the phase function, whose average is 1) needs no
// correction: the pigments of most paints (g below ~0.3 at the standard
// preset's 8 orders), whose tables are exact to far better than the rest.
constexpr double kNegligible = 1e-6;

// A bound on |p - (1 - f) p*_{N,M}| for N moments and M table orders: the
// moments the azimuthal truncation drops, sum_{l >= M} (2l + 1) |chi_l| (the
// true chi_l; those below N also hold the delta-M shift f, added as f N^2).
double truncationBound(const PathSlab& slab, int table_orders) {
    const auto n = static_cast<int>(slab.chi.size());
    double bound = slab.truncated * double(n) * double(n);
    for (const PhaseLobe& lobe : slab.lobes) {
        const double g = std::abs(lobe.g);
        if (g >= 1.0) return 1.0;
        // sum_{l >= M} (2l + 1) g^l = g^M ((2M + 1) (1 - g) + 2 g) / (1 - g)^2
        const int M = std::max(0, table_orders);
        bound +=
            lobe.weight * std::pow(g, M) * ((2.0 * M + 1.0) * (1.0 - g) + 2.0 * g) / ((1.0 - g) * (1.0 - g));
    }
    return bound;
}

double henyeyGreensteinMixture(const std::vector<PhaseLobe>& lobes, double cos_theta) {
    double p = 0.0;
    for (const PhaseLobe& lobe : lobes) {
        const double d = 1.0 + lobe.g * lobe.g - 2.0 * lobe.g * cos_theta;
        p += lobe.weight * (1.0 - lobe.g * lobe.g) / (d * std::sqrt(d));
    }
    return lobes.empty() ? 1.0 : p;  // no lobe: isotropic, as the kernels take it
}

// Where one ambient direction runs in every slab: its cosine there and the
// fraction of its flux that reaches the slab's top (or leaves through the
// top from there), Fresnel transmissions and the extinction of the slabs above.
struct Leg {
    std::vector<double> mu;        // per slab; 0: the direction does not exist there
    std::vector<double> transmit;  // per slab
};

Leg legThrough(const std::vector<PathSlab>& slabs, double ambient_index, double mu_ambient) {
    Leg leg{std::vector<double>(slabs.size(), 0.0), std::vector<double>(slabs.size(), 0.0)};
    const double s = ambient_index * std::sqrt(std::max(0.0, 1.0 - mu_ambient * mu_ambient));  // n sin(theta)
    double n_above = ambient_index;
    double mu_above = mu_ambient;
    double transmit = 1.0;
    for (std::size_t k = 0; k < slabs.size(); ++k) {
        const PathSlab& slab = slabs[k];
        if (s >= slab.index) return leg;  // totally reflected above: nothing reaches this or deeper slabs
        const double mu = std::sqrt(1.0 - (s / slab.index) * (s / slab.index));
        if (std::abs(slab.index - n_above) > 1e-9)
            transmit *= 1.0 - fresnelDielectric(mu_above, slab.index / n_above);
        leg.mu[k] = mu;
        leg.transmit[k] = transmit;
        transmit *= std::exp(-slab.extinctionPerUm(mu) * slab.thickness_um / mu);
        n_above = slab.index;
        mu_above = mu;
    }
    return leg;
}

// One slab's part of the once-scattered light between two ambient directions:
// the weight of its phase value and the cosines and sines there.
struct SlabScattering {
    std::size_t slab = 0;
    double weight = 0.0;  // 1/sr per unit of the normalised phase function
    double mu_i = 0.0, mu_o = 0.0, sin_i = 0.0, sin_o = 0.0;

    // Between the propagation directions (down along -wi, up along wo, azimuths dphi - pi apart).
    double cosTheta(double cos_dphi) const { return -sin_i * sin_o * cos_dphi - mu_i * mu_o; }
};

std::vector<SlabScattering> scatteringSlabs(const std::vector<PathSlab>& slabs, double ambient_index,
                                            double mu_i, double mu_o) {
    std::vector<SlabScattering> out;
    if (!(mu_i > 0.0) || !(mu_o > 0.0)) return out;
    const Leg in = legThrough(slabs, ambient_index, mu_i);
    const Leg up = legThrough(slabs, ambient_index, mu_o);
    for (std::size_t k = 0; k < slabs.size(); ++k) {
        const PathSlab& slab = slabs[k];
        const double mi = in.mu[k];
        const double mo = up.mu[k];
        if (!(slab.sigma_s_per_um > 0.0) || !(mi > 0.0) || !(mo > 0.0)) continue;
        const double K = slab.extinctionPerUm(mi) / mi + slab.extinctionPerUm(mo) / mo;
        const double path = K > 0.0 ? -std::expm1(-slab.thickness_um * K) / K : slab.thickness_um;
        const double radiance = (ambient_index / slab.index) * (ambient_index / slab.index);
        out.push_back({k,
                       in.transmit[k] * up.transmit[k] * radiance * slab.sigma_s_per_um / (4.0 * kPi) * path /
                           (mi * mo),
                       mi, mo, std::sqrt(std::max(0.0, 1.0 - mi * mi)),
                       std::sqrt(std::max(0.0, 1.0 - mo * mo))});
    }
    return out;
}

}  // namespace

double PathSlab::extinctionPerUm(double mu) const {
    if (flake_extinction_per_um.empty()) return pigment_extinction_per_um;
    const double x = std::clamp(mu, 0.0, 1.0) * static_cast<double>(flake_extinction_per_um.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(x), flake_extinction_per_um.size() - 2);
    const double t = x - static_cast<double>(i);
    return pigment_extinction_per_um + (1.0 - t) * flake_extinction_per_um[i] +
           t * flake_extinction_per_um[i + 1];
}

SingleScatteringCorrection::SingleScatteringCorrection(const Recipe& recipe, double wavelength_nm,
                                                       const FastModelSettings& settings, int table_orders)
    : m_ambient_index(recipe.ambient_refractive_index), m_table_orders(table_orders) {
    // The slabs exactly as buildBandStack (stack_assembly.cpp) makes them, down
    // to the deepest one whose correction matters; the flakes' extinction
    // (thin-film tables) only for those.
    std::vector<std::pair<SlabOptics, PathSlab>> slabs;
    std::size_t needed = 0;
    for (const auto& layer : recipe.layers) {
        const auto bounds = sliceBoundaries(layer, settings.slices);
        for (std::size_t s = 1; s < bounds.size(); ++s) {
            SlabOptics optics = slabOptics(layer, wavelength_nm, bounds[s - 1], bounds[s]);
            const ScaledMedium medium = scaledMedium(optics, settings.nodes);
            PathSlab slab;
            slab.index = optics.binder_index;
            slab.thickness_um = optics.thickness_um;
            slab.sigma_s_per_um = optics.sigma_s_per_um;
            slab.pigment_extinction_per_um = medium.sigma_a + medium.sigma_s;
            slab.lobes = optics.lobes;
            slab.chi = medium.chi;
            slab.truncated = medium.f;
            if (slab.sigma_s_per_um > 0.0 && truncationBound(slab, table_orders) > kNegligible)
                needed = slabs.size() + 1;
            slabs.emplace_back(std::move(optics), std::move(slab));
        }
    }
    std::vector<double> cosines(kFlakeCosines);
    for (int k = 0; k < kFlakeCosines; ++k)
        cosines[static_cast<std::size_t>(k)] = double(k) / (kFlakeCosines - 1);
    // A coarser flake table than the kernels': the extinction only attenuates
    // the correction, a small term, and the thin-film tables are the cost.
    const FlakeSampling sampling{settings.flake_polar, settings.flake_azimuth,
                                 std::min(settings.flake_table, 9), settings.flake_kernel_points_per_spread};
    for (std::size_t k = 0; k < needed; ++k) {
        auto& [optics, slab] = slabs[k];
        if (!optics.mirror_flakes.empty() || !optics.interference_flakes.empty())
            slab.flake_extinction_per_um = flakeExtinction(optics, wavelength_nm, cosines, sampling);
        m_slabs.push_back(std::move(slab));
    }
}

double SingleScatteringCorrection::operator()(double mu_i, double mu_o, double dphi) const {
    double sum = 0.0;
    for (const SlabScattering& at : scatteringSlabs(m_slabs, m_ambient_index, mu_i, mu_o)) {
        const PathSlab& slab = m_slabs[at.slab];
        const double exact = henyeyGreensteinMixture(slab.lobes, at.cosTheta(std::cos(dphi)));
        const double truncated =
            (1.0 - slab.truncated) *
            layered::phaseFourierSum(at.mu_o, -at.mu_i, -std::cos(dphi), slab.chi, m_table_orders);
        sum += at.weight * (exact - truncated);
    }
    return sum;
}

void SingleScatteringCorrection::fourierCoefficients(double mu_i, double mu_o, std::span<double> out) const {
    std::fill(out.begin(), out.end(), 0.0);
    const std::size_t orders = out.size();
    // Midpoint rule over dphi in [0, pi] (the correction is even in dphi): the
    // exact lobe's orders above `points` alias onto order 2 points - m and up.
    const int points = std::max(64, 4 * static_cast<int>(orders));
    std::vector<double> truncated(orders);
    for (const SlabScattering& at : scatteringSlabs(m_slabs, m_ambient_index, mu_i, mu_o)) {
        const PathSlab& slab = m_slabs[at.slab];
        // The truncated series' terms are in the propagation azimuth dphi - pi: (-1)^m in dphi.
        layered::phaseFourierOrders(at.mu_o, -at.mu_i, slab.chi, truncated);
        for (std::size_t m = 0; m < orders && static_cast<int>(m) < m_table_orders; ++m)
            out[m] -= at.weight * (1.0 - slab.truncated) * (m % 2 == 0 ? 1.0 : -1.0) * truncated[m];
        for (int p = 0; p < points; ++p) {
            const double c = std::cos((p + 0.5) * kPi / points);
            const double exact = at.weight * henyeyGreensteinMixture(slab.lobes, at.cosTheta(c)) / points;
            // cos(m dphi) by the Chebyshev recurrence.
            double c_prev = c;
            double c_now = 1.0;
            for (std::size_t m = 0; m < orders; ++m) {
                out[m] += (m == 0 ? 1.0 : 2.0) * exact * c_now;
                const double c_next = 2.0 * c * c_now - c_prev;
                c_prev = c_now;
                c_now = c_next;
            }
        }
    }
}

}  // namespace paintlab::fast
