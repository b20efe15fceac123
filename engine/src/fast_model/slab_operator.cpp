#include "slab_operator.h"

#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/optics/flake_orientation.h"
#include "paintlab/engine/optics/thin_film.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace paintlab::fast {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

VectorXd wVector(const layered::Quadrature& q) {
    VectorXd w(q.size());
    for (int i = 0; i < q.size(); ++i) w(i) = q.weight[static_cast<std::size_t>(i)];
    return w;
}

// Azimuth points for the Fourier coefficients of a flake kernel over [0, pi]
// (the kernel is even in the azimuth difference): the midpoint rule is exact
// for cos(m phi) below 2 N and spectrally accurate for a smooth periodic lobe
// once its spacing is below the lobe's azimuthal width, ~2 sigma / sin(theta)
// >= 2 sigma; points_per_spread points per sigma (4 by default), capped (a
// narrower lobe is the deficit's).
int azimuthPoints(double spread_deg, int orders, double points_per_spread) {
    const double sigma = std::max(spread_deg, 0.1) * std::numbers::pi / 180.0;
    const int resolve =
        static_cast<int>(std::ceil(std::clamp(points_per_spread, 0.25, 16.0) * std::numbers::pi / sigma));
    return std::max(orders + 8, std::min(resolve, 256));
}

// Reflectance and transmittance of one kind of flake as a function of the
// local cosine, tabulated on a uniform grid of `size` cosines and interpolated
// by Catmull-Rom cubics (third order: the thin-film table is the costliest
// part of an interference-flake band, so it is kept short), clamped so that
// 0 <= R, T and R + T <= 1 (no energy is created by the interpolation).
struct FlakeTable {
    std::vector<double> R;
    std::vector<double> T;
    struct Value {
        double R = 0.0;
        double T = 0.0;
    };
    static double cubic(const std::vector<double>& v, int i, double t) {
        const int last = static_cast<int>(v.size()) - 1;
        const auto at = [&](int k) {
            // Beyond the ends: quadratic extrapolation (keeps the end intervals third order).
            const auto val = [&](int j) { return v[static_cast<std::size_t>(j)]; };
            if (k < 0) return 3.0 * val(0) - 3.0 * val(1) + val(2);
            if (k > last) return 3.0 * val(last) - 3.0 * val(last - 1) + val(last - 2);
            return val(k);
        };
        const double p0 = at(i - 1), p1 = at(i), p2 = at(i + 1), p3 = at(i + 2);
        return p1 +
               0.5 * t *
                   (p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
    }
    Value at(double cos_theta) const {
        const int size = static_cast<int>(R.size());
        const double x = std::clamp(cos_theta, 0.0, 1.0) * (size - 1);
        const int i = std::min(static_cast<int>(x), size - 2);
        const double t = x - i;
        const double r = std::clamp(cubic(R, i, t), 0.0, 1.0);
        return {r, std::clamp(cubic(T, i, t), 0.0, 1.0 - r)};
    }
};

std::vector<double> tableCosines(int size) {
    std::vector<double> c(static_cast<std::size_t>(size));
    for (int i = 0; i < size; ++i) c[static_cast<std::size_t>(i)] = double(i) / (size - 1);
    return c;
}

struct FlakeKind {
    double area_density_per_um;
    double spread_deg;
    FlakeTable table;
};

std::vector<FlakeKind> flakeKinds(const SlabOptics& slab, double wavelength_nm, int table_size) {
    std::vector<FlakeKind> kinds;
    const auto cosines = tableCosines(table_size);
    const auto size = cosines.size();
    for (const auto& f : slab.mirror_flakes) {
        FlakeKind k{f.area_density_per_um, f.orientation_spread_deg,
                    FlakeTable{std::vector<double>(size, 0.0), std::vector<double>(size, 0.0)}};
        for (std::size_t i = 0; i < size; ++i) {
            const double c = cosines[i];
            k.table.R[i] = f.metal_index ? metalFlakeReflectance(c, *f.metal_index, slab.binder_index)
                                         : mirrorFlakeReflectanceFromNormal(c, f.reflectance.value_or(0.0));
        }
        kinds.push_back(std::move(k));
    }
    for (const auto& f : slab.interference_flakes) {
        FlakeKind k{f.area_density_per_um, f.orientation_spread_deg,
                    FlakeTable{std::vector<double>(size, 0.0), std::vector<double>(size, 0.0)}};
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

// What one unit of flake area (per unit volume) takes out of a direction with
// cosine mu_v and reflects: E_D[|v.n| (1 - T)] and E_D[|v.n| R] over the
// normal density D, both at the local cosine |v.n|. The integrand has a kink
// where flakes are seen edge-on (v.n = 0), which exists for tilts
// alpha >= 90 deg - theta_v; stratified midpoint sampling converges slowly
// there (~1e-3 relative at 32 x 64 samples, which showed up as colour
// differences of ~0.1 dE between grids). So: Gauss-Legendre in the sampling
// variable u1 of the tilt (FlakeOrientation::sample), split where the kink
// appears, and in the normal's azimuth, split at the kink itself; every piece
// is smooth and converges spectrally.
struct FlakeTotals {
    double extinction = 0.0;
    double reflected = 0.0;
};

// Gauss-Legendre rule on [0, 1].
struct UnitRule {
    std::vector<double> x;
    std::vector<double> w;
    explicit UnitRule(int n) { layered::gaussLegendre(n, 0.0, 1.0, x, w); }
};

FlakeTotals flakeTotals(const FlakeOrientation& orientation, const FlakeTable& table, double mu_v,
                        const UnitRule& polar, const UnitRule& azimuth) {
    const double sin_v = std::sqrt(std::max(0.0, 1.0 - mu_v * mu_v));
    FlakeTotals totals;
    const auto accumulate = [&](const FlakeNormal& nrm, double weight) {
        const double hit = std::abs(sin_v * nrm.x - mu_v * nrm.z);
        const FlakeTable::Value rt = table.at(hit);
        totals.extinction += weight * (1.0 - rt.T) * hit;
        totals.reflected += weight * rt.R * hit;
    };
    if (orientation.isDelta()) {
        accumulate(FlakeNormal{}, 1.0);
        return totals;
    }
    // u1 at which the tilt reaches 90 deg - theta_v (mu_n = sin_v); u1 = 0 is mu_n = 1.
    const double kappa = orientation.kappa();
    const double t_kink = 1.0 - sin_v;  // 1 - mu_n
    double u_kink = t_kink;
    if (kappa > 1e-9) u_kink = std::expm1(-kappa * t_kink) / std::expm1(-kappa);
    std::vector<std::pair<double, double>> polar_pieces{{0.0, 1.0}};
    if (u_kink > 1e-12 && u_kink < 1.0 - 1e-12) polar_pieces = {{0.0, u_kink}, {u_kink, 1.0}};
    const auto& x01 = polar.x;
    const auto& w01 = polar.w;
    const auto& xa01 = azimuth.x;
    const auto& wa01 = azimuth.w;
    for (const auto& [u0, u1] : polar_pieces) {
        for (std::size_t a = 0; a < x01.size(); ++a) {
            const double u = u0 + (u1 - u0) * x01[a];
            const double wu = (u1 - u0) * w01[a];
            const FlakeNormal base = orientation.sample(u, 0.0);
            const double sin_alpha = base.x;
            const double mu_n = base.z;
            // v.n = sin_v sin_alpha cos(phi) - mu_v mu_n vanishes at phi_k (if any); by
            // symmetry phi in [0, pi], weights doubled and divided by 2 pi.
            std::vector<std::pair<double, double>> pieces{{0.0, std::numbers::pi}};
            const double denom = sin_v * sin_alpha;
            if (denom > 0.0) {
                const double c = mu_v * mu_n / denom;
                if (c > -1.0 && c < 1.0) pieces = {{0.0, std::acos(c)}, {std::acos(c), std::numbers::pi}};
            }
            for (const auto& [p0, p1] : pieces) {
                for (std::size_t b = 0; b < xa01.size(); ++b) {
                    const double phi = p0 + (p1 - p0) * xa01[b];
                    accumulate(FlakeNormal{sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), mu_n},
                               wu * (p1 - p0) * wa01[b] / std::numbers::pi);
                }
            }
        }
    }
    return totals;
}

// Adds the flakes' reflection kernels and projected-area extinction.
//
// Kernel (per steradian and unit length) of two-sided mirrors of area density
// A and normal density D (flake_orientation.h) between propagation directions
// v and v': k(v -> v') = A R(|v.h|) D(h) / 4, h = (v' - v) / |v' - v|, because
// the flakes with normals in d omega_h intercept A D |v.h| d omega_h and reflect
// into d omega' = 4 |v.h| d omega_h (the half-vector Jacobian; Walter et al.,
// EGSR 2007, eq. 14). It is symmetric in (v, v'), so it is evaluated at the
// nodes in both mu and mu' (Nystrom, like the pigments' phase matrices, and
// reciprocal by construction), and its Fourier coefficients
// K^m(i, j) = int_0^2pi k cos(m phi) dphi by the midpoint rule.
// A lobe narrower than the node spacing is missed by the nodes; the exact
// scattered power of every direction (stratified sampling of the flake
// normals, which also gives the extinction) is restored by putting the
// deficit at the mirror direction of node j (K_opposite(j, j), every order: a
// lobe too narrow to resolve reflects as horizontal flakes do). Energy is
// therefore exact for any spread, from the delta (all of it deficit) to the
// random hemisphere.
void addFlakes(const std::vector<FlakeKind>& kinds, const layered::Quadrature& q,
               const FlakeSampling& sampling, SlabKernels& k) {
    const int n = q.size();
    const int orders = static_cast<int>(k.orders.size());
    std::vector<double> sin_mu(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const double mu = q.mu[static_cast<std::size_t>(i)];
        sin_mu[static_cast<std::size_t>(i)] = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    }
    std::vector<double> cos_m(static_cast<std::size_t>(orders));
    std::vector<double> acc(2 * static_cast<std::size_t>(orders));
    for (const auto& kind : kinds) {
        const FlakeOrientation orientation(kind.spread_deg);
        // Extinction and reflected power per node (flakeTotals).
        VectorXd deficit = VectorXd::Zero(n);
        const UnitRule polar_rule(std::max(1, sampling.polar));
        const UnitRule azimuth_rule(std::max(1, sampling.azimuth));
        for (int j = 0; j < n; ++j) {
            const FlakeTotals totals = flakeTotals(orientation, kind.table, q.mu[static_cast<std::size_t>(j)],
                                                   polar_rule, azimuth_rule);
            k.extinction_per_um(j) += kind.area_density_per_um * totals.extinction;
            deficit(j) = kind.area_density_per_um * totals.reflected;
        }
        if (!orientation.isDelta()) {
            const int n_phi = azimuthPoints(kind.spread_deg, orders, sampling.kernel_points_per_spread);
            const double dphi = std::numbers::pi / n_phi;
            const double scale = 0.25 * kind.area_density_per_um * 2.0 * dphi;  // [0, pi] counted twice
            std::vector<double> cphi(static_cast<std::size_t>(n_phi));
            std::vector<double> sphi(static_cast<std::size_t>(n_phi));
            for (int p = 0; p < n_phi; ++p) {
                cphi[static_cast<std::size_t>(p)] = std::cos((p + 0.5) * dphi);
                sphi[static_cast<std::size_t>(p)] = std::sin((p + 0.5) * dphi);
            }
            std::vector<OrderKernel> own(static_cast<std::size_t>(orders),
                                         OrderKernel{MatrixXd::Zero(n, n), MatrixXd::Zero(n, n)});
            for (int j = 0; j < n; ++j) {
                const double vx = sin_mu[static_cast<std::size_t>(j)];
                const double vz = -q.mu[static_cast<std::size_t>(j)];
                for (int i = j; i < n; ++i) {
                    const double si = sin_mu[static_cast<std::size_t>(i)];
                    const double mi = q.mu[static_cast<std::size_t>(i)];
                    std::fill(acc.begin(), acc.end(), 0.0);
                    for (int p = 0; p < n_phi; ++p) {
                        const double c1 = cphi[static_cast<std::size_t>(p)];
                        const double hx = si * c1 - vx;
                        const double hy = si * sphi[static_cast<std::size_t>(p)];
                        const double hxy2 = hx * hx + hy * hy;
                        // side 0: v' upward (reflected, "opposite"); side 1: v' downward ("same").
                        for (int side = 0; side < 2; ++side) {
                            const double hz = (side == 0 ? mi : -mi) - vz;
                            const double len2 = hxy2 + hz * hz;
                            if (len2 < 1e-24) continue;  // v' = v: no reflection
                            const double inv = 1.0 / std::sqrt(len2);
                            const double cos_local = std::abs(vx * hx + vz * hz) * inv;
                            const double value =
                                orientation.pdf(std::abs(hz) * inv) * kind.table.at(cos_local).R;
                            if (value == 0.0) continue;
                            // cos(m phi) by the Chebyshev recurrence.
                            double* out = acc.data() + static_cast<std::ptrdiff_t>(side) * orders;
                            double c_prev = 1.0;
                            double c_now = c1;
                            out[0] += value;
                            if (orders > 1) out[1] += value * c1;
                            for (int m = 2; m < orders; ++m) {
                                const double c_next = 2.0 * c1 * c_now - c_prev;
                                out[m] += value * c_next;
                                c_prev = c_now;
                                c_now = c_next;
                            }
                        }
                    }
                    for (int m = 0; m < orders; ++m) {
                        auto& order = own[static_cast<std::size_t>(m)];
                        const double opp = scale * acc[static_cast<std::size_t>(m)];
                        const double same =
                            scale * acc[static_cast<std::size_t>(orders) + static_cast<std::size_t>(m)];
                        order.opposite(i, j) = opp;
                        order.same(i, j) = same;
                        order.opposite(j, i) = opp;
                        order.same(j, i) = same;
                    }
                }
            }
            // Symmetric scaling K -> D K D (every order) so that each column
            // carries the exact reflected power S_j: column j then carries
            // d_j r_j, r_j = sum_i w_i K_ij d_i, and the symmetric Sinkhorn
            // iteration d_j <- d_j sqrt(S_j / (d_j r_j)) converges to d_j r_j = S_j. For a
            // resolved lobe the nodes' share is within a fraction of a percent of
            // the exact power and d ~ 1 corrects it smoothly, keeping the lobe's
            // shape and reciprocity; the scaling is confined to [0.8, 1.25] so an
            // unresolved lobe is not blown up (its remainder is the deficit below).
            const VectorXd w = wVector(q);
            const MatrixXd total0 = own[0].same + own[0].opposite;
            VectorXd d = VectorXd::Ones(n);
            for (int iteration = 0; iteration < 50; ++iteration) {
                const VectorXd r = total0.transpose() * w.cwiseProduct(d);
                double change = 0.0;
                for (int j = 0; j < n; ++j) {
                    if (!(r(j) > 0.0) || !(deficit(j) > 0.0)) continue;
                    const double next = std::clamp(std::sqrt(d(j) * deficit(j) / r(j)), 0.8, 1.25);
                    change = std::max(change, std::abs(next - d(j)));
                    d(j) = next;
                }
                if (change < 1e-13) break;
            }
            for (auto& order : own) {
                order.same = d.asDiagonal() * order.same * d.asDiagonal();
                order.opposite = d.asDiagonal() * order.opposite * d.asDiagonal();
            }
            deficit -= (own[0].same + own[0].opposite).transpose() * w;
            for (int m = 0; m < orders; ++m) {
                k.orders[static_cast<std::size_t>(m)].same += own[static_cast<std::size_t>(m)].same;
                k.orders[static_cast<std::size_t>(m)].opposite += own[static_cast<std::size_t>(m)].opposite;
            }
        }
        // The deficit (the sampled power minus the nodes' share: a lobe too
        // narrow for the nodes, or the small quadrature and sampling errors of a
        // resolved one) goes to node j's mirror direction with the azimuthal
        // spread of the lobe there, a Gaussian of width s ~ 2 sigma / sin(theta)
        // whose Fourier weights are exp(-m^2 s^2 / 2): a delta in azimuth (every
        // order 1, as for horizontal flakes) would make the Fourier series ring
        // and grow with the order count.
        const double sigma = kind.spread_deg * std::numbers::pi / 180.0;
        const VectorXd w = wVector(q);
        for (int j = 0; j < n; ++j) {
            const double width =
                orientation.isDelta()
                    ? 0.0
                    : std::min(std::numbers::pi,
                               2.0 * sigma / std::max(sin_mu[static_cast<std::size_t>(j)], 1e-9));
            for (int m = 0; m < orders; ++m)
                k.orders[static_cast<std::size_t>(m)].opposite(j, j) +=
                    deficit(j) / w(j) * std::exp(-0.5 * double(m) * double(m) * width * width);
        }
    }
}

}  // namespace

ScaledMedium scaledMedium(const SlabOptics& slab, int n_moments) {
    ScaledMedium s;
    std::vector<double> chi(static_cast<std::size_t>(n_moments) + 1, 0.0);
    for (const auto& lobe : slab.lobes)
        for (int l = 0; l <= n_moments; ++l)
            chi[static_cast<std::size_t>(l)] += lobe.weight * std::pow(lobe.g, l);
    if (slab.lobes.empty()) chi[0] = 1.0;
    s.f = std::clamp(chi.back(), 0.0, 0.999999);
    s.chi.resize(static_cast<std::size_t>(n_moments));
    for (int l = 0; l < n_moments; ++l)
        s.chi[static_cast<std::size_t>(l)] = (chi[static_cast<std::size_t>(l)] - s.f) / (1.0 - s.f);
    s.sigma_s = slab.sigma_s_per_um * (1.0 - s.f);
    s.sigma_a = slab.sigma_a_per_um;
    return s;
}

std::vector<double> flakeExtinction(const SlabOptics& slab, double wavelength_nm,
                                    const std::vector<double>& cosines, const FlakeSampling& sampling) {
    std::vector<double> extinction(cosines.size(), 0.0);
    const UnitRule polar_rule(std::max(1, sampling.polar));
    const UnitRule azimuth_rule(std::max(1, sampling.azimuth));
    for (const auto& kind : flakeKinds(slab, wavelength_nm, std::max(5, sampling.table))) {
        const FlakeOrientation orientation(kind.spread_deg);
        for (std::size_t i = 0; i < cosines.size(); ++i)
            extinction[i] +=
                kind.area_density_per_um *
                flakeTotals(orientation, kind.table, cosines[i], polar_rule, azimuth_rule).extinction;
    }
    return extinction;
}

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
    const auto kinds = flakeKinds(slab, wavelength_nm, std::max(5, sampling.table));
    if (!kinds.empty()) addFlakes(kinds, q, sampling, k);
    // The exact scattering rate of every direction (the diamond start restores it).
    k.scattering_per_um =
        (w.asDiagonal() * (k.orders[0].same + k.orders[0].opposite)).colwise().sum().transpose();
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
