#include "slab_operator.h"

#include "paintlab/engine/flake_orientation.h"
#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/thin_film.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::fast {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Cell boundaries in mu of the quadrature (cumulative weights, normalised):
// a reflected direction is credited to the node whose cell holds its cosine.
std::vector<double> cellBoundaries(const layered::Quadrature& q) {
    std::vector<double> b{0.0};
    double total = 0.0;
    for (double w : q.weight) total += w;
    for (double w : q.weight) b.push_back(b.back() + w / total);
    b.back() = 1.0;
    return b;
}

int cellOf(const std::vector<double>& bounds, double mu) {
    const auto it = std::upper_bound(bounds.begin(), bounds.end(), mu);
    const int i = static_cast<int>(it - bounds.begin()) - 1;
    return std::clamp(i, 0, static_cast<int>(bounds.size()) - 2);
}

// Reflectance and transmittance of one kind of flake as a function of the
// local cosine, tabulated on a uniform grid (interpolated linearly).
struct FlakeTable {
    static constexpr int kSize = 129;
    std::vector<double> R = std::vector<double>(kSize);
    std::vector<double> T = std::vector<double>(kSize, 0.0);
    double at(const std::vector<double>& v, double cos_theta) const {
        const double x = std::clamp(cos_theta, 0.0, 1.0) * (kSize - 1);
        const int i = std::min(static_cast<int>(x), kSize - 2);
        const double t = x - i;
        return v[static_cast<std::size_t>(i)] * (1.0 - t) + v[static_cast<std::size_t>(i) + 1] * t;
    }
};

std::vector<double> tableCosines() {
    std::vector<double> c(FlakeTable::kSize);
    for (int i = 0; i < FlakeTable::kSize; ++i)
        c[static_cast<std::size_t>(i)] = double(i) / (FlakeTable::kSize - 1);
    return c;
}

struct FlakeKind {
    double area_density_per_um;
    double spread_deg;
    FlakeTable table;
};

std::vector<FlakeKind> flakeKinds(const SlabOptics& slab, double wavelength_nm) {
    std::vector<FlakeKind> kinds;
    const auto cosines = tableCosines();
    for (const auto& f : slab.mirror_flakes) {
        FlakeKind k{f.area_density_per_um, f.orientation_spread_deg, {}};
        for (int i = 0; i < FlakeTable::kSize; ++i) {
            const double c = cosines[static_cast<std::size_t>(i)];
            k.table.R[static_cast<std::size_t>(i)] =
                f.metal_index ? metalFlakeReflectance(c, *f.metal_index, slab.binder_index)
                              : mirrorFlakeReflectanceFromNormal(c, f.reflectance.value_or(0.0));
        }
        kinds.push_back(std::move(k));
    }
    for (const auto& f : slab.interference_flakes) {
        FlakeKind k{f.area_density_per_um, f.orientation_spread_deg, {}};
        InterferenceFlakeOptics optics;
        optics.binder_n = slab.binder_index;
        optics.mica_n = f.mica_index;
        optics.tio2_n = f.tio2_index;
        optics.mica_thickness_nm = f.mica_thickness_nm;
        optics.mica_thickness_spread_nm = f.mica_thickness_spread_nm;
        optics.tio2_thickness_nm = f.tio2_thickness_nm;
        optics.tio2_thickness_spread_nm = f.tio2_thickness_spread_nm;
        tabulateInterferenceFlake(optics, wavelength_nm, cosines, k.table.R, k.table.T);
        kinds.push_back(std::move(k));
    }
    return kinds;
}

// Adds the flakes' reflection kernels and projected-area extinction by
// deterministic stratified sampling of the flake normals: every sampled
// normal reflects node j's direction into some cell, so the m = 0 kernel
// scatters exactly the flux the flakes intercept times their reflectance
// (energy is conserved by construction, for any orientation spread).
void addFlakes(const std::vector<FlakeKind>& kinds, const layered::Quadrature& q,
               const FlakeSampling& sampling, SlabKernels& k) {
    const int n = q.size();
    const auto bounds = cellBoundaries(q);
    const int orders = static_cast<int>(k.orders.size());
    std::vector<double> cos_m(static_cast<std::size_t>(orders));
    for (const auto& kind : kinds) {
        const FlakeOrientation orientation(kind.spread_deg);
        const int np = orientation.isDelta() ? 1 : sampling.polar;
        const int na = orientation.isDelta() ? 1 : sampling.azimuth;
        const double sample_weight = kind.area_density_per_um / (np * na);
        for (int j = 0; j < n; ++j) {
            const double mu_j = q.mu[static_cast<std::size_t>(j)];
            const double sin_j = std::sqrt(std::max(0.0, 1.0 - mu_j * mu_j));
            // Downward propagation at azimuth 0; upward incidence is the mirror image.
            const double vx = sin_j;
            const double vz = -mu_j;
            double extinction = 0.0;
            for (int a = 0; a < np; ++a) {
                for (int b = 0; b < na; ++b) {
                    const FlakeNormal nrm = orientation.sample((a + 0.5) / np, (b + 0.5) / na);
                    const double cos_n = vx * nrm.x + vz * nrm.z;  // v . n
                    const double hit = std::abs(cos_n);            // projected area seen by the ray
                    const double R = kind.table.at(kind.table.R, hit);
                    const double T = kind.table.at(kind.table.T, hit);
                    extinction += (1.0 - T) * hit;  // what is transmitted goes straight on
                    if (R <= 0.0 || hit <= 0.0) continue;
                    const double rx = vx - 2.0 * cos_n * nrm.x;
                    const double ry = -2.0 * cos_n * nrm.y;
                    const double rz = vz - 2.0 * cos_n * nrm.z;
                    const int i = cellOf(bounds, std::min(1.0, std::abs(rz)));
                    const double dphi = std::atan2(ry, rx);
                    // cos(m dphi) by the Chebyshev recurrence.
                    const double c1 = std::cos(dphi);
                    cos_m[0] = 1.0;
                    if (orders > 1) cos_m[1] = c1;
                    for (int m = 2; m < orders; ++m)
                        cos_m[static_cast<std::size_t>(m)] =
                            2.0 * c1 * cos_m[static_cast<std::size_t>(m) - 1] -
                            cos_m[static_cast<std::size_t>(m) - 2];
                    const double power = sample_weight * R * hit / q.weight[static_cast<std::size_t>(i)];
                    for (int m = 0; m < orders; ++m) {
                        auto& target = rz < 0.0 ? k.orders[static_cast<std::size_t>(m)].same
                                                : k.orders[static_cast<std::size_t>(m)].opposite;
                        target(i, j) += power * cos_m[static_cast<std::size_t>(m)];
                    }
                }
            }
            k.extinction_per_um(j) += sample_weight * extinction;
        }
    }
}

// The pigments' phase function: Legendre moments of the HG mixture, with the
// delta-M truncation (Wiscombe 1977) moving f = chi_N into the unscattered beam.
struct ScaledMedium {
    std::vector<double> chi;
    double sigma_s = 0.0;
    double sigma_a = 0.0;
};

ScaledMedium scaledMedium(const SlabOptics& slab, int n_moments) {
    ScaledMedium s;
    std::vector<double> chi(static_cast<std::size_t>(n_moments) + 1, 0.0);
    for (const auto& lobe : slab.lobes)
        for (int l = 0; l <= n_moments; ++l)
            chi[static_cast<std::size_t>(l)] += lobe.weight * std::pow(lobe.g, l);
    if (slab.lobes.empty()) chi[0] = 1.0;
    const double f = std::clamp(chi.back(), 0.0, 0.999999);
    s.chi.resize(static_cast<std::size_t>(n_moments));
    for (int l = 0; l < n_moments; ++l)
        s.chi[static_cast<std::size_t>(l)] = (chi[static_cast<std::size_t>(l)] - f) / (1.0 - f);
    s.sigma_s = slab.sigma_s_per_um * (1.0 - f);
    s.sigma_a = slab.sigma_a_per_um;
    return s;
}

}  // namespace

SlabKernels slabKernels(const SlabOptics& slab, const layered::Quadrature& q, double wavelength_nm,
                        int max_order, int n_moments, const FlakeSampling& sampling) {
    const int n = q.size();
    SlabKernels k;
    const ScaledMedium medium = scaledMedium(slab, n_moments);
    k.extinction_per_um = VectorXd::Constant(n, medium.sigma_a + medium.sigma_s);
    VectorXd w(n);
    for (int i = 0; i < n; ++i) w(i) = q.weight[static_cast<std::size_t>(i)];
    for (int m = 0; m <= max_order; ++m) {
        OrderKernel order{MatrixXd::Zero(n, n), MatrixXd::Zero(n, n)};
        if (medium.sigma_s > 0.0) {
            const layered::PhaseMatrices h = layered::phaseMatrices(q.mu, medium.chi, m);
            MatrixXd same = h.same;
            if (m == 0) {
                // Each column must scatter exactly sigma_s: the quadrature's
                // normalisation error goes to the forward direction (as Prahl does).
                for (int j = 0; j < n; ++j) {
                    double s = 0.0;
                    for (int i = 0; i < n; ++i) s += 0.5 * w(i) * (same(i, j) + h.opposite(i, j));
                    same(j, j) += 2.0 * (1.0 - s) / w(j);
                }
            }
            order.same = (0.5 * medium.sigma_s) * same;
            order.opposite = (0.5 * medium.sigma_s) * h.opposite;
        }
        k.orders.push_back(std::move(order));
    }
    const auto kinds = flakeKinds(slab, wavelength_nm);
    if (!kinds.empty()) addFlakes(kinds, q, sampling, k);
    // The exact scattering rate of every direction, kept before symmetrising.
    k.scattering_per_um =
        (w.asDiagonal() * (k.orders[0].same + k.orders[0].opposite)).colwise().sum().transpose();
    if (!kinds.empty()) {
        // Reciprocity: the flake kernel A R(|w'.h|) D(h) / 4 is symmetric in
        // (w', w), but binning outgoing directions into cells while sampling
        // incident ones at the nodes is not; symmetrise (the m = 0 energy is
        // restored on the diagonal in the starting layer).
        for (auto& order : k.orders) {
            order.same = 0.5 * (order.same + order.same.transpose()).eval();
            order.opposite = 0.5 * (order.opposite + order.opposite.transpose()).eval();
        }
    }
    k.max_extinction_per_um = k.extinction_per_um.maxCoeff();
    return k;
}

namespace {

// Diamond start (Prahl 1995 eq. 4.31) with direction-dependent extinction and
// exponential fitting of each node's cosine so the unscattered transmission
// is exactly exp(-e_i d / mu_i), keeping the flux weights 2 mu w.
layered::LayerOperator startLayer(const SlabKernels& k, const layered::Quadrature& q, int m, double d_um) {
    const int n = q.size();
    VectorXd half_d_over_mu(n);
    VectorXd w_fit(n);
    VectorXd c(n);
    for (int i = 0; i < n; ++i) {
        const double mu = q.mu[static_cast<std::size_t>(i)];
        const double e = k.extinction_per_um(i);
        const double y = 0.5 * d_um * e / mu;
        const double ratio = y < 1e-8 ? 1.0 : y / std::tanh(y);
        half_d_over_mu(i) = 0.5 * d_um / (mu * ratio);
        w_fit(i) = q.weight[static_cast<std::size_t>(i)] / ratio;
        c(i) = 2.0 * mu * q.weight[static_cast<std::size_t>(i)];
    }
    const OrderKernel& K = k.orders[static_cast<std::size_t>(m)];
    MatrixXd same = K.same;
    if (m == 0) {
        // Exact energy bookkeeping of the diamond scheme: with the fitted
        // weights every column must scatter exactly its rate (Prahl 1995's
        // renormalisation); the difference goes to the forward direction.
        const VectorXd actual = (w_fit.asDiagonal() * (K.same + K.opposite)).colwise().sum().transpose();
        for (int j = 0; j < n; ++j) same(j, j) += (k.scattering_per_um(j) - actual(j)) / w_fit(j);
    }
    const MatrixXd I = MatrixXd::Identity(n, n);
    const MatrixXd half_alpha = half_d_over_mu.asDiagonal() *
                                (MatrixXd(k.extinction_per_um.asDiagonal()) - same * w_fit.asDiagonal());
    const MatrixXd A = I + half_alpha;
    const MatrixXd B = half_d_over_mu.asDiagonal() * (K.opposite * w_fit.asDiagonal());
    const MatrixXd C = I - half_alpha;
    const MatrixXd P = A.partialPivLu().solve(B);
    const MatrixXd Q = B * P;
    const MatrixXd T = (A - Q).partialPivLu().solve(C + Q);
    const MatrixXd R = P * (I + T);
    const VectorXd c_inv = c.cwiseInverse();
    const MatrixXd Rf = c.asDiagonal() * R * c_inv.asDiagonal();
    const MatrixXd Tf = c.asDiagonal() * T * c_inv.asDiagonal();
    return {Rf, Tf, Rf, Tf};
}

}  // namespace

layered::LayerOperator slabOperator(const SlabKernels& k, const layered::Quadrature& q, int m,
                                    double thickness_um, double max_start_tau) {
    const int n = q.size();
    const double tau_max = k.max_extinction_per_um * thickness_um;
    if (!(thickness_um > 0.0) || tau_max <= 0.0) return layered::LayerOperator::identity(n);
    const int doublings = std::max(0, static_cast<int>(std::ceil(std::log2(tau_max / max_start_tau))));
    layered::LayerOperator op = startLayer(k, q, m, std::ldexp(thickness_um, -doublings));
    const MatrixXd I = MatrixXd::Identity(n, n);
    for (int i = 0; i < doublings; ++i) {
        // Symmetric slab: R2 = R + T (I - R R)^-1 R T, T2 = T (I - R R)^-1 T (LU solves).
        const auto lu = (I - op.R01 * op.R01).partialPivLu();
        const MatrixXd R2 = op.R01 + op.T01 * lu.solve(op.R01 * op.T01);
        const MatrixXd T2 = op.T01 * lu.solve(op.T01);
        op = {R2, T2, R2, T2};
        // Once nothing gets through, more doubling changes nothing.
        if (T2.cwiseAbs().maxCoeff() < 1e-300) break;
    }
    return op;
}

}  // namespace paintlab::fast
