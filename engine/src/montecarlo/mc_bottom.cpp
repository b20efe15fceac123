#include "mc_bottom.h"

#include "../fast_model/slab_operator.h"
#include "../fast_model/stack_assembly.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/layer_optics.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kPi = std::numbers::pi;
// Floors of the sampling densities (shares of the cosine-weighted uniform
// density of the same total), so that every direction f reaches has a
// density: the weight f cos / pdf stays bounded.
constexpr double kCellFloor = 1e-3;
constexpr double kAzimuthFloor = 1e-2;

}  // namespace

BottomOperator::BottomOperator(const Recipe& recipe, std::size_t first_layer, double n, double wavelength_nm,
                               int slices, int nodes) {
    // The bottom alone, seen from a medium of its own index: no interface on top.
    Recipe bottom;
    bottom.name = recipe.name;
    bottom.ambient_refractive_index = n;
    bottom.layers.assign(recipe.layers.begin() + static_cast<std::ptrdiff_t>(first_layer),
                         recipe.layers.end());
    bottom.substrate = recipe.substrate;
    FastModelSettings fs;
    fs.nodes = nodes;
    fs.orders = kOrders;
    fs.slices = slices;
    const fast::BandStack stack = fast::buildBandStack(bottom, wavelength_nm, fs);
    const fast::MediumNodes medium = stack.grid.medium(n);
    const auto count = medium.node.size();
    if (count < 2) throw Error("bottom operator: fewer than 2 quadrature nodes");
    const int nn = static_cast<int>(count);
    m_mu = medium.quadrature.mu;
    m_f.assign(static_cast<std::size_t>(kOrders) * count * count, 0.0);
    m_albedo.assign(count, 0.0);
    double f0_max = 0.0;
    // The orders are independent: a block of them at a time in parallel (the
    // bands are built before their jobs, BandsInTurn), read in order so that
    // the series ends where it did order by order.
    constexpr int kOrderBlock = 4;
    std::vector<Eigen::MatrixXd> block(kOrderBlock);
    for (int m = 0; m < kOrders && !m_series_converged; ++m) {
        if (m % kOrderBlock == 0)
            tbb::parallel_for(m, std::min(kOrders, m + kOrderBlock), [&](int order) {
                block[static_cast<std::size_t>(order % kOrderBlock)] =
                    fast::stackReflection(stack, order, fs);
            });
        const Eigen::MatrixXd& R = block[static_cast<std::size_t>(m % kOrderBlock)];
        double largest = 0.0;
        for (int o = 0; o < nn; ++o) {
            const double to_brdf = 1.0 / (kPi * medium.quadrature.fluxWeight(o));
            for (int i = 0; i < nn; ++i) {
                const double value =
                    R(medium.node[static_cast<std::size_t>(o)], medium.node[static_cast<std::size_t>(i)]) *
                    to_brdf;
                m_f[(static_cast<std::size_t>(m) * count + static_cast<std::size_t>(o)) * count +
                    static_cast<std::size_t>(i)] = value;
                largest = std::max(largest, std::abs(value));
            }
            if (m == 0)  // the column sums: the flux reflected per incident node
                for (int i = 0; i < nn; ++i)
                    m_albedo[static_cast<std::size_t>(i)] +=
                        R(medium.node[static_cast<std::size_t>(o)], medium.node[static_cast<std::size_t>(i)]);
        }
        if (m == 0) f0_max = largest;
        m_orders = m + 1;
        // The coefficients fall monotonically with m (HG's g^m): the first negligible order ends the series.
        if (m > 0 && largest <= 1e-7 * f0_max) m_series_converged = true;
    }
    m_f.resize(static_cast<std::size_t>(m_orders) * count * count);

    // Tabulated as g = f (mu_o + mu_i): single scattering is p / (mu_o + mu_i)
    // times a smooth factor, so g interpolates far better than f near grazing.
    for (int m = 0; m < m_orders; ++m)
        for (std::size_t o = 0; o < count; ++o)
            for (std::size_t i = 0; i < count; ++i)
                m_f[(static_cast<std::size_t>(m) * count + o) * count + i] *= m_mu[o] + m_mu[i];
    for (int i = 0; i < nn; ++i) {
        // int f^0 2 pi mu dmu of the interpolant: midpoint rule in mu^2 (kinks only at the nodes).
        constexpr int kSteps = 4096;
        double reflected = 0.0;
        for (int k = 0; k < kSteps; ++k) reflected += kPi * nodeF0(i, std::sqrt((k + 0.5) / kSteps)) / kSteps;
        if (!(reflected > 0.0)) continue;
        const double scale = m_albedo[static_cast<std::size_t>(i)] / reflected;
        m_largest_rescale = std::max(m_largest_rescale, std::abs(scale - 1.0));
        for (int m = 0; m < m_orders; ++m)
            for (int o = 0; o < nn; ++o)
                m_f[(static_cast<std::size_t>(m) * count + static_cast<std::size_t>(o)) * count +
                    static_cast<std::size_t>(i)] *= scale;
    }

    // Sampling: cells around the nodes, chosen by the node's reflected flux.
    m_edges.assign(count + 1, 0.0);
    for (std::size_t k = 1; k < count; ++k) m_edges[k] = 0.5 * (m_mu[k - 1] + m_mu[k]);
    m_edges[count] = 1.0;
    m_cell_cdf.assign(count * (count + 1), 0.0);
    for (int i = 0; i < nn; ++i) {
        std::vector<double> q(count);
        double total = 0.0;
        for (std::size_t o = 0; o < count; ++o) {
            const double area = m_edges[o + 1] * m_edges[o + 1] - m_edges[o] * m_edges[o];
            q[o] = area * std::max(0.0, at(0, static_cast<int>(o), i) /
                                            (m_mu[o] + m_mu[static_cast<std::size_t>(i)]));
            total += q[o];
        }
        double* cdf = &m_cell_cdf[static_cast<std::size_t>(i) * (count + 1)];
        for (std::size_t o = 0; o < count; ++o) {
            const double area = m_edges[o + 1] * m_edges[o + 1] - m_edges[o] * m_edges[o];
            cdf[o + 1] = cdf[o] + q[o] + kCellFloor * area * std::max(total, 1e-300);
        }
        for (std::size_t o = 1; o <= count; ++o) cdf[o] /= cdf[count];
    }
    // Azimuth: per (node, cell) the Fourier series at bin centres over [0, pi],
    // floored; the cosines tabulated once, the incident nodes in parallel.
    const std::size_t bins = kAzimuthBins;
    const auto orders = static_cast<std::size_t>(m_orders);
    std::vector<double> cosines(bins * orders);
    for (std::size_t b = 0; b < bins; ++b) {
        const double phi = (static_cast<double>(b) + 0.5) * kPi / static_cast<double>(bins);
        for (int m = 1; m < m_orders; ++m)
            cosines[b * orders + static_cast<std::size_t>(m)] = std::cos(m * phi);
    }
    m_azimuth_cdf.assign(count * count * (bins + 1), 0.0);
    tbb::parallel_for(0, nn, [&](int i) {
        std::vector<double> g(bins);
        for (int o = 0; o < nn; ++o) {
            double mean = 0.0;
            for (std::size_t b = 0; b < bins; ++b) {
                double value = at(0, o, i);
                for (int m = 1; m < m_orders; ++m)
                    value += 2.0 * at(m, o, i) * cosines[b * orders + static_cast<std::size_t>(m)];
                g[b] = std::max(0.0, value);
                mean += g[b] / static_cast<double>(bins);
            }
            double* cdf = &m_azimuth_cdf[(static_cast<std::size_t>(i) * count + static_cast<std::size_t>(o)) *
                                         (bins + 1)];
            for (std::size_t b = 0; b < bins; ++b)
                cdf[b + 1] = cdf[b] + g[b] + kAzimuthFloor * std::max(mean, 1e-300);
            for (std::size_t b = 1; b <= bins; ++b) cdf[b] /= cdf[bins];
        }
    });
}

void BottomOperator::locate(double mu, int& k, double& t, bool extrapolate) const {
    const auto it = std::upper_bound(m_mu.begin(), m_mu.end(), mu);
    if (it == m_mu.begin()) {
        k = 0;
        t = 0.0;
        return;
    }
    if (it == m_mu.end() && extrapolate) {
        const std::size_t last = m_mu.size() - 1;
        k = static_cast<int>(last) - 1;
        t = (mu - m_mu[last - 1]) / (m_mu[last] - m_mu[last - 1]);
        return;
    }
    if (it == m_mu.end()) {
        k = static_cast<int>(m_mu.size()) - 1;
        t = 0.0;
        return;
    }
    k = static_cast<int>(it - m_mu.begin()) - 1;
    const auto kk = static_cast<std::size_t>(k);
    t = (mu - m_mu[kk]) / (m_mu[kk + 1] - m_mu[kk]);
}

int BottomOperator::cellOf(double mu) const {
    const auto it = std::upper_bound(m_edges.begin() + 1, m_edges.end() - 1, mu);
    return static_cast<int>(it - m_edges.begin()) - 1;
}

double BottomOperator::nodeF0(int i, double mu_o) const {
    int k = 0;
    double t = 0.0;
    locate(mu_o, k, t, true);
    const int k1 = std::min(k + 1, static_cast<int>(m_mu.size()) - 1);
    return ((1.0 - t) * at(0, k, i) + t * at(0, k1, i)) /
           denominator(mu_o, m_mu[static_cast<std::size_t>(i)]);
}

double BottomOperator::eval(const Vec3& v, const Vec3& u) const {
    const double sin_i = std::sqrt(std::max(0.0, 1.0 - v.z * v.z));
    const double sin_o = std::sqrt(std::max(0.0, 1.0 - u.z * u.z));
    const double c =
        sin_i * sin_o > 1e-12 ? std::clamp((v.x * u.x + v.y * u.y) / (sin_i * sin_o), -1.0, 1.0) : 1.0;
    return evalAt(std::clamp(-v.z, 0.0, 1.0), std::clamp(u.z, 0.0, 1.0), c);
}

double BottomOperator::evalAt(double mu_i, double mu_o, double c) const {
    if (!(mu_o > 0.0)) return 0.0;
    int ki = 0;
    int ko = 0;
    double ti = 0.0;
    double to = 0.0;
    locate(mu_i, ki, ti, true);
    locate(mu_o, ko, to, true);
    const int ki1 = std::min(ki + 1, static_cast<int>(m_mu.size()) - 1);
    const int ko1 = std::min(ko + 1, static_cast<int>(m_mu.size()) - 1);
    // cos(m dphi) by the Chebyshev recurrence.
    double previous = 1.0;
    double current = c;
    double f = 0.0;
    for (int m = 0; m < m_orders; ++m) {
        const double value = (1.0 - to) * ((1.0 - ti) * at(m, ko, ki) + ti * at(m, ko, ki1)) +
                             to * ((1.0 - ti) * at(m, ko1, ki) + ti * at(m, ko1, ki1));
        if (m == 0) {
            f += value;
            continue;
        }
        f += 2.0 * value * current;
        const double next = 2.0 * c * current - previous;
        previous = current;
        current = next;
    }
    return std::max(0.0, f / denominator(mu_o, mu_i));
}

double BottomOperator::nodePdf(int i, int cell, double mu_o, std::size_t bin) const {
    const std::size_t count = m_mu.size();
    const auto o = static_cast<std::size_t>(cell);
    const double* cells = &m_cell_cdf[static_cast<std::size_t>(i) * (count + 1)];
    const double area = m_edges[o + 1] * m_edges[o + 1] - m_edges[o] * m_edges[o];
    const std::size_t bins = kAzimuthBins;
    const double* az = &m_azimuth_cdf[(static_cast<std::size_t>(i) * count + o) * (bins + 1)];
    // Cell probability, mu in it by 2 mu / area, the azimuth bin's density over [0, pi] halved (both signs).
    return (cells[o + 1] - cells[o]) * 2.0 * mu_o / area * (az[bin + 1] - az[bin]) *
           static_cast<double>(bins) / kPi * 0.5;
}

double BottomOperator::pdf(const Vec3& v, const Vec3& u) const {
    if (!(u.z > 0.0)) return 0.0;
    int ki = 0;
    double ti = 0.0;
    locate(std::clamp(-v.z, 0.0, 1.0), ki, ti);
    const int cell = cellOf(u.z);
    const double phi_v = std::atan2(v.y, v.x);
    double dphi = std::abs(std::remainder(std::atan2(u.y, u.x) - phi_v, 2.0 * kPi));
    if (std::sqrt(std::max(0.0, 1.0 - v.z * v.z)) < 1e-12) dphi = std::abs(std::atan2(u.y, u.x));
    const std::size_t bins = kAzimuthBins;
    const auto bin = std::min(bins - 1, static_cast<std::size_t>(dphi / kPi * static_cast<double>(bins)));
    double p = (1.0 - ti) * nodePdf(ki, cell, u.z, bin);
    if (ti > 0.0) p += ti * nodePdf(ki + 1, cell, u.z, bin);
    return p;
}

Vec3 BottomOperator::sample(const Vec3& v, PathRng& rng, double& factor) const {
    factor = 0.0;
    const std::size_t count = m_mu.size();
    int ki = 0;
    double ti = 0.0;
    locate(std::clamp(-v.z, 0.0, 1.0), ki, ti);
    const int i = rng.uniform() < ti ? ki + 1 : ki;
    const double* cells = &m_cell_cdf[static_cast<std::size_t>(i) * (count + 1)];
    const double uc = rng.uniform();
    const auto o = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(std::upper_bound(cells + 1, cells + count + 1, uc) - cells - 1, 0,
                                   static_cast<std::ptrdiff_t>(count) - 1));
    const double lo2 = m_edges[o] * m_edges[o];
    const double hi2 = m_edges[o + 1] * m_edges[o + 1];
    const double mu_o = std::sqrt(lo2 + rng.uniform() * (hi2 - lo2));
    const std::size_t bins = kAzimuthBins;
    const double* az = &m_azimuth_cdf[(static_cast<std::size_t>(i) * count + o) * (bins + 1)];
    const double ua = rng.uniform();
    const auto b = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(
        std::upper_bound(az + 1, az + bins + 1, ua) - az - 1, 0, static_cast<std::ptrdiff_t>(bins) - 1));
    const double width = az[b + 1] - az[b];
    const double within = width > 0.0 ? (ua - az[b]) / width : 0.5;
    const double dphi =
        (static_cast<double>(b) + std::clamp(within, 0.0, 1.0)) * kPi / static_cast<double>(bins);
    const double sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
    // u at azimuth +-dphi from v's (x when v is vertical, as pdf() measures it).
    const double sin_v = std::sqrt(std::max(0.0, 1.0 - v.z * v.z));
    const double ax = sin_v > 1e-12 ? v.x / sin_v : 1.0;
    const double ay = sin_v > 1e-12 ? v.y / sin_v : 0.0;
    const double cos_d = std::cos(dphi);
    const double sin_d = sign * std::sin(dphi);
    const double sin_o = std::sqrt(std::max(0.0, 1.0 - mu_o * mu_o));
    const Vec3 u{sin_o * (ax * cos_d - ay * sin_d), sin_o * (ay * cos_d + ax * sin_d), mu_o};
    // pdf(v, u) and eval(v, u) from what the draw already knows (its cell and bin).
    double p = (1.0 - ti) * nodePdf(ki, static_cast<int>(o), mu_o, b);
    if (ti > 0.0) p += ti * nodePdf(ki + 1, static_cast<int>(o), mu_o, b);
    if (p > 0.0) factor = evalAt(std::clamp(-v.z, 0.0, 1.0), mu_o, cos_d) * mu_o / p;
    return u;
}

double BottomOperator::albedo(double mu_i) const {
    int k = 0;
    double t = 0.0;
    locate(std::clamp(mu_i, 0.0, 1.0), k, t);
    const auto kk = static_cast<std::size_t>(k);
    return t > 0.0 ? (1.0 - t) * m_albedo[kk] + t * m_albedo[kk + 1] : m_albedo[kk];
}

bool attachBottomOperator(PaintStack& stack, const Recipe& recipe, int slices) {
    if (stack.substrate != SubstrateKind::Lambertian && stack.substrate != SubstrateKind::Black) return false;
    // The lowest slice with flakes; the bottom begins with the next layer.
    std::size_t last_flake = stack.slices.size();
    for (std::size_t j = 0; j < stack.slices.size(); ++j)
        if (!stack.slices[j].flakes.empty()) last_flake = j;
    if (last_flake == stack.slices.size()) return false;  // no flakes: the walk is the whole model
    const auto first_layer = static_cast<std::size_t>(stack.slices[last_flake].layer) + 1;
    if (first_layer >= recipe.layers.size()) return false;
    const double n = stack.slices[last_flake].n;
    const double wavelength_nm = stack.wavelength_nm;
    for (std::size_t l = first_layer; l < recipe.layers.size(); ++l) {
        const Layer& layer = recipe.layers[l];
        if (std::abs(layer.binder.refractive_index(wavelength_nm) - n) > fast::kSameIndex) return false;
        const auto bounds = sliceBoundaries(layer, slices);
        for (std::size_t s = 1; s < bounds.size(); ++s) {
            const SlabOptics optics = slabOptics(layer, wavelength_nm, bounds[s - 1], bounds[s]);
            if (!optics.mirror_flakes.empty() || !optics.interference_flakes.empty()) return false;
            if (fast::scaledMedium(optics, BottomOperator::kNodes).f > BottomOperator::kMaxTruncation)
                return false;
        }
    }
    auto bottom = std::make_shared<const BottomOperator>(recipe, first_layer, n, wavelength_nm, slices);
    // A forward-peaked bottom whose Fourier series kOrders cannot hold: walked.
    if (!bottom->seriesConverged()) return false;
    stack.bottom = std::move(bottom);
    while (!stack.slices.empty() && static_cast<std::size_t>(stack.slices.back().layer) >= first_layer)
        stack.slices.pop_back();
    stack.substrate = SubstrateKind::Operator;
    return true;
}

}  // namespace paintlab::mc
