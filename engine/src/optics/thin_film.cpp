#include "paintlab/engine/optics/thin_film.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace paintlab {
namespace {

using C = std::complex<double>;

// sin(beta) / beta, accurate near 0 (Taylor to beta^4: the next term is
// beta^6 / 5040 < 1e-19 for |beta| < 1e-3).
C sinc(C beta) {
    if (std::norm(beta) < 1e-6) {  // |beta| < 1e-3
        const C b2 = beta * beta;
        return 1.0 - b2 / 6.0 + b2 * b2 / 120.0;
    }
    return std::sin(beta) / beta;
}

// Characteristic matrix of Born & Wolf sec. 1.6.2, stored as a 2x2 complex
// matrix for TE and TM at once: both share beta = k0 d n cos and differ only
// in the "admittance" Y (p = n cos for TE, q = cos / n for TM).
struct Mat2 {
    C m11, m12, m21, m22;
};

Mat2 mul(const Mat2& a, const Mat2& b) {
    return {a.m11 * b.m11 + a.m12 * b.m21, a.m11 * b.m12 + a.m12 * b.m22, a.m21 * b.m11 + a.m22 * b.m21,
            a.m21 * b.m12 + a.m22 * b.m22};
}

// One layer's matrices for TE and TM. P = n cos (either branch: the matrix is
// even in P), n2 = n^2, k0d = 2 pi d / lambda. sin(beta)/Y is written as
// k0 d sinc(beta) (TE) or n^2 k0 d sinc(beta) (TM) so that no division by
// cos occurs: a layer traversed at grazing angle stays finite.
struct LayerPair {
    Mat2 te, tm;
};

LayerPair layerMatrices(C P, C n2, double k0d) {
    const C beta = k0d * P;
    const C cb = std::cos(beta);
    const C sb = std::sin(beta);
    const C sc = k0d * sinc(beta);
    const C i(0.0, 1.0);
    const C q = P / n2;
    LayerPair out;
    out.te = {cb, -i * sc, -i * P * sb, cb};
    out.tm = {cb, -i * n2 * sc, -i * q * sb, cb};
    return out;
}

// Born & Wolf sec. 1.6.3: amplitude coefficients and power ratios for one
// polarisation: Y1 admittance of the (real) incident medium, Yl of the exit one.
struct PolResult {
    C r;
    double R, T;
};

PolResult terminate(const Mat2& m, double Y1, C Yl) {
    const C a = (m.m11 + m.m12 * Yl) * Y1;
    const C b = m.m21 + m.m22 * Yl;
    const C den = a + b;
    PolResult out{C(-1.0), 1.0, 0.0};
    if (!(std::abs(den) > 0.0) || !(Y1 > 0.0)) return out;
    const C r = (a - b) / den;
    const C t = 2.0 * Y1 / den;
    out.r = r;
    out.R = std::clamp(std::norm(r), 0.0, 1.0);
    out.T = std::clamp(std::max(0.0, Yl.real()) / Y1 * std::norm(t), 0.0, 1.0);
    return out;
}

// n cos(theta) in a medium of index n for the invariant s = n0 sin(theta0)
// (Snell): sqrt(n^2 - s^2), principal branch, so Im >= 0: the decaying wave
// in an absorbing medium or beyond total internal reflection.
C normalIndex(C n, double s2) { return std::sqrt(n * n - s2); }

// The active quadrature nodes of one layer's thickness average at one angle:
// the layer's characteristic matrices and their normalised weights.
struct LayerNodes {
    std::vector<LayerPair> mats;
    std::vector<double> w;
    void reserve(std::size_t n) {
        mats.reserve(n);
        w.reserve(n);
    }
};

constexpr int kMaxPeriodNodes = 1024;
// Trapezoid nodes needed to resolve the wrapped Gaussian: the aliasing term of
// harmonic K/2 is exp(-K^2 sigma_beta^2 / 2) (Fourier coefficients of the
// wrapped normal for period pi are exp(-2 n^2 sigma_beta^2)); <= 1e-9 needs
// K sigma_beta >= 6.44.
constexpr double kResolveGaussian = 6.44;
constexpr double kDropWeight = 1e-15;
// Fourier moments of the mica phase beyond which the analytic average hands over
// to the 2-D quadrature (mica spreads below ~0.5 nm).
constexpr int kMaxMicaMoments = 256;
// Beyond this many thickness nodes for an absorbing layer, fall back to Gauss-Hermite.
constexpr double kMaxAbsorbingNodes = 4096.0;  // nodes lighter than this change R by less

void addNode(LayerNodes& out, C P, C n2, double k0, double d_nm, double w) {
    out.mats.push_back(layerMatrices(P, n2, k0 * d_nm));
    out.w.push_back(w);
}

// Gauss-Hermite on N(mean, spread^2) truncated to d > 0: d = mean + sqrt(2)
// spread x, nodes with d <= 0 dropped and the rest renormalised (conditioning
// on d > 0; accurate while spread < mean / 3).
void gaussHermiteNodes(LayerNodes& out, C P, C n2, double k0, double mean_nm, double spread_nm, int nodes) {
    const GaussHermiteRule rule = gaussHermiteRule(nodes);
    double total = 0.0;
    for (std::size_t i = 0; i < rule.x.size(); ++i) {
        const double d = mean_nm + std::numbers::sqrt2 * spread_nm * rule.x[i];
        if (d > 0.0) total += rule.w[i];
    }
    if (!(total > 0.0)) {
        addNode(out, P, n2, k0, std::max(0.0, mean_nm), 1.0);
        return;
    }
    for (std::size_t i = 0; i < rule.x.size(); ++i) {
        const double d = mean_nm + std::numbers::sqrt2 * spread_nm * rule.x[i];
        if (d > 0.0) addNode(out, P, n2, k0, d, rule.w[i] / total);
    }
}

// Weights of the Gaussian N(mean, spread^2), truncated to d > 0, folded onto
// one period Lambda at the K phases d_j = (j + 1/2) Lambda / K: w_j is the sum
// of the density over the images d_j + k Lambda > 0 (unnormalised; returns the sum).
double foldedWeights(std::vector<double>& w, double mean_nm, double spread_nm, double Lambda, int K) {
    const double lo = std::max(0.0, mean_nm - 12.0 * spread_nm);  // exp(-72): negligible beyond
    const double hi = mean_nm + 12.0 * spread_nm;
    w.clear();
    double total = 0.0;
    for (int j = 0; j < K; ++j) {
        const double d_j = (j + 0.5) * Lambda / K;
        double wj = 0.0;
        const double k_lo = std::max(0.0, std::ceil((lo - d_j) / Lambda));
        for (double k = k_lo; d_j + k * Lambda <= hi; k += 1.0) {
            const double z = (d_j + k * Lambda - mean_nm) / spread_nm;
            wj += std::exp(-0.5 * z * z);
        }
        w.push_back(wj);
        total += wj;
    }
    return total;
}

// Fills `out` for a layer of index n whose thickness is N(mean, spread^2)
// truncated to d > 0, at the angle given by s2 = (n0 sin theta0)^2.
// `copies`: how many layers share this thickness (2 for the TiO2 coatings),
// which multiplies the phase spread the Gauss-Hermite rule must resolve.
void buildLayerNodes(LayerNodes& out, C n, double mean_nm, double spread_nm, double s2, double k0, int copies,
                     int min_nodes, const ThicknessQuadrature& q) {
    out.mats.clear();
    out.w.clear();
    const C P = normalIndex(n, s2);
    const C n2 = n * n;
    mean_nm = std::max(0.0, mean_nm);
    if (!(spread_nm > 0.0)) {
        addNode(out, P, n2, k0, mean_nm, 1.0);
        return;
    }
    const double sigma_beta = k0 * std::abs(P) * spread_nm;  // phase spread of one pass
    // Lossless: R is exactly periodic in d. Weakly absorbing (|Im P| <= 0.1 Re P,
    // e.g. TiO2 near its band edge): periodic times a slow decay, handled by
    // the same trapezoid spacing without folding the images together.
    const bool lossless = n.imag() == 0.0 && P.real() > 0.0 && std::abs(P.imag()) <= 1e-12 * P.real();
    const bool weak_loss = P.real() > 0.0 && std::abs(P.imag()) <= 0.1 * P.real();
    const double k_needed = kResolveGaussian / sigma_beta;
    const int k_max = std::clamp(q.max_period_nodes, 1, kMaxPeriodNodes);
    const double lo = std::max(0.0, mean_nm - 12.0 * spread_nm);  // exp(-72): negligible beyond
    const double hi = mean_nm + 12.0 * spread_nm;
    if ((lossless || weak_loss) && !q.force_gauss_hermite && k_needed <= k_max) {
        const int K =
            std::min(k_max, std::max({q.min_period_nodes, min_nodes, static_cast<int>(std::ceil(k_needed))}));
        const double Lambda = std::numbers::pi / (k0 * P.real());
        const double h = Lambda / K;
        if (lossless) {
            // R and T are pi-periodic in beta = k0 d P, i.e. periodic in d
            // with period Lambda = pi / (k0 P) = lambda / (2 n cos). The
            // average of a periodic function over a density equals its
            // average over one period against the wrapped density
            // sum_k rho(d + k Lambda), and for a smooth periodic integrand the
            // trapezoid rule on K equispaced points is spectrally accurate
            // (Trefethen & Weideman, The exponentially convergent trapezoidal rule,
            // SIAM Rev. 56 (2014) 385). Summing only
            // images d + k Lambda > 0 makes the truncation at d > 0 exact.
            const double total = foldedWeights(out.w, mean_nm, spread_nm, Lambda, K);
            // Renormalise, then keep only nodes that matter (for narrow
            // spreads most of the K phases carry no weight).
            std::size_t kept = 0;
            double kept_total = 0.0;
            for (int j = 0; j < K; ++j) {
                const double w = out.w[static_cast<std::size_t>(j)] / total;
                if (w < kDropWeight) continue;
                out.w[kept++] = w;
                kept_total += w;
                out.mats.push_back(layerMatrices(P, n2, k0 * (j + 0.5) * h));
            }
            out.w.resize(kept);
            for (double& w : out.w) w /= kept_total;
            return;
        }
        // Weak loss: trapezoid on the same grid over the whole support
        // (a smooth integrand times a Gaussian on the line, again spectrally
        // accurate), each image its own node.
        const double i_lo = std::floor(lo / h), i_hi = std::ceil(hi / h);
        if (i_hi - i_lo < kMaxAbsorbingNodes) {
            double total = 0.0;
            for (double i = i_lo; i <= i_hi; i += 1.0) {
                const double z = ((i + 0.5) * h - mean_nm) / spread_nm;
                total += std::exp(-0.5 * z * z);
            }
            double kept_total = 0.0;
            for (double i = i_lo; i <= i_hi; i += 1.0) {
                const double d = (i + 0.5) * h;
                const double z = (d - mean_nm) / spread_nm;
                const double w = std::exp(-0.5 * z * z) / total;
                if (w < kDropWeight || d <= 0.0) continue;
                addNode(out, P, n2, k0, d, w);
                kept_total += w;
            }
            for (double& w : out.w) w /= kept_total;
            return;
        }
    }
    const int nodes = q.gauss_hermite_nodes > 0 ? q.gauss_hermite_nodes
                                                : gaussHermiteNodesForPhaseSpread(2.0 * copies * sigma_beta);
    gaussHermiteNodes(out, P, n2, k0, mean_nm, spread_nm, nodes);
}

struct FlakeWorkspace {
    LayerNodes mica, tio2;
    std::vector<double> fold;  // folded mica weights
    std::vector<C> moments;    // E[exp(2 i k beta_mica)], k = 0..M+1
    FlakeWorkspace() {
        fold.reserve(kMaxPeriodNodes);
        moments.reserve(kMaxMicaMoments + 2);
        mica.reserve(static_cast<std::size_t>(kMaxAbsorbingNodes) + 2);
        tio2.reserve(static_cast<std::size_t>(kMaxAbsorbingNodes) + 2);
    }
};

// Analytic average over a lossless mica layer. Its characteristic matrix is
// M(beta) = e^{i beta} U + e^{-i beta} V with U = (1/2)[[1, -1/Y], [-Y, 1]],
// V = (1/2)[[1, 1/Y], [Y, 1]], so for the whole flake A M A (A: one TiO2
// coating) the numerator and denominator of Born & Wolf's r are
// e^{-i beta} (N_U z + N_V) and e^{-i beta} (D_U z + D_V), z = e^{2 i beta}.
// On |z| = 1, 1 / |D_U z + D_V|^2 = G sum_m g_m z^m with g_m = p^m, g_{-m} =
// conj(p)^m (the Poisson kernel: p = -D_U / D_V if |D_U| < |D_V|, else
// conj(-D_V / D_U); G = 1 / (|D_big|^2 (1 - |p|^2))). With the moments
// mu_k = E[z^k] of the thickness distribution,
//   E[R] = G (n0 S0 + 2 Re(n1 S1)),  E[T] = 4 Y1^2 G S0,
//   S0 = 1 + 2 Re sum_{m>=1} p^m mu_m,  S1 = sum_m g_m mu_{m+1},
//   |N_U z + N_V|^2 = n0 + n1 z + conj(n1 z), n0 = |N_U|^2 + |N_V|^2, n1 = N_U conj(N_V).
// The series converge geometrically (|p| < 1) and mu_m decays like
// exp(-2 m^2 sigma_beta^2), so a few terms suffice for typical spreads; cost
// per TiO2 node is O(terms) instead of O(mica nodes).
bool averageOverMica(const Mat2& A, C Y_mica, double Y1, const std::vector<C>& mu, double tol, double& R,
                     double& T) {
    const C inv = 1.0 / Y_mica;
    const Mat2 U{C(0.5), -0.5 * inv, -0.5 * Y_mica, C(0.5)};
    const Mat2 V{C(0.5), 0.5 * inv, 0.5 * Y_mica, C(0.5)};
    const Mat2 AUA = mul(mul(A, U), A);
    const Mat2 AVA = mul(mul(A, V), A);
    // terminate(): a = (m11 + m12 Yl) Y1, b = m21 + m22 Yl with Yl = Y1 (binder).
    const C aU = (AUA.m11 + AUA.m12 * Y1) * Y1, bU = AUA.m21 + AUA.m22 * Y1;
    const C aV = (AVA.m11 + AVA.m12 * Y1) * Y1, bV = AVA.m21 + AVA.m22 * Y1;
    const C D_U = aU + bU, D_V = aV + bV, N_U = aU - bU, N_V = aV - bV;
    C p;
    double G = 0.0;
    if (std::norm(D_U) < std::norm(D_V)) {  // norm: |z|^2 without hypot's cost
        p = -D_U / D_V;
        G = 1.0 / (std::norm(D_V) * (1.0 - std::norm(p)));
    } else {
        p = std::conj(-D_V / D_U);
        G = 1.0 / (std::norm(D_U) * (1.0 - std::norm(p)));
    }
    const double abs_p = std::abs(p);
    if (!(abs_p < 1.0 - 1e-9) || !std::isfinite(G)) return false;
    // Terms smaller than tail_tol leave a geometric tail below 1e-3 tol.
    const double tail_tol = 1e-3 * tol * (1.0 - abs_p);
    const double tail_tol2 = tail_tol * tail_tol;  // compared with |p^m|^2: no square root per term
    const std::size_t M = mu.size() - 2;
    C sum0(0.0), sum1 = mu[1];
    C pm(1.0);
    const C cp = std::conj(p);
    C cpm = cp;
    sum1 += cp;  // m = -1: conj(p) mu_0
    for (std::size_t m = 1; m <= M; ++m) {
        pm *= p;
        sum0 += pm * mu[m];
        sum1 += pm * mu[m + 1];
        if (m >= 2) {
            cpm *= cp;
            sum1 += cpm * std::conj(mu[m - 1]);  // g_{-m} mu_{1-m}
        }
        if (std::norm(pm) < tail_tol2) break;
    }
    const double S0 = 1.0 + 2.0 * sum0.real();
    const double n0 = std::norm(N_U) + std::norm(N_V);
    const C n1 = N_U * std::conj(N_V);
    R = G * (n0 * S0 + 2.0 * (n1 * sum1).real());
    T = 4.0 * Y1 * Y1 * G * S0;
    return std::isfinite(R) && std::isfinite(T);
}

// Moments mu_k = E[exp(2 i k beta)], k = 0..M+1, of the mica phase beta =
// k0 P d over the truncated Gaussian, by the folded trapezoid rule (exact up
// to aliasing of order mu_{K-k}); false when the spread is too narrow for
// kMaxMicaMoments moments (then the 2-D quadrature is used).
// Moments mu_k = E[exp(2 i k beta)], k = 0..M+1, of the mica phase beta =
// k0 P d over the Gaussian, from the folded weights at K phases
// beta_j = pi (j + 1/2) / K: mu_k = sum_j w_j exp(2 pi i k (j + 1/2) / K).
// mu_m ~ exp(-2 m^2 sigma_beta^2), so M is where that falls below 1e-3 tol,
// and K = 2M + 4 keeps the aliased mu_{K-k} below it too. false (use the 2-D
// quadrature) when the spread is too narrow for kMaxMicaMoments moments, or
// when the truncation at d = 0 matters (mean < ~6.4 spread): its jump in the
// wrapped density makes mu_m decay only like 1/m, and then the 2-D folded
// quadrature was measured to be faster than summing hundreds of moments.
bool micaMoments(FlakeWorkspace& ws, double mean_nm, double spread_nm, double k0, double P_re, double tol) {
    if (mean_nm < spread_nm * std::sqrt(2.0 * std::log(1e3 / tol))) return false;
    const double sigma_beta = k0 * P_re * spread_nm;
    const double M_d = std::ceil(std::sqrt(0.5 * std::log(1e3 / tol)) / sigma_beta) + 2.0;
    if (!(M_d <= kMaxMicaMoments)) return false;
    const int M = static_cast<int>(M_d);
    const int K = std::max(16, 2 * M + 4);
    const double Lambda = std::numbers::pi / (k0 * P_re);
    const double total = foldedWeights(ws.fold, mean_nm, spread_nm, Lambda, K);
    if (!(total > 0.0)) return false;
    ws.moments.assign(static_cast<std::size_t>(M) + 2, C(0.0));
    for (int j = 0; j < K; ++j) {
        const double w = ws.fold[static_cast<std::size_t>(j)] / total;
        if (w < kDropWeight) continue;
        const double phase = 2.0 * std::numbers::pi * (j + 0.5) / K;  // 2 beta_j
        const C z(std::cos(phase), std::sin(phase));
        C zk(w);
        for (C& m : ws.moments) {
            m += zk;
            zk *= z;
        }
    }
    return true;
}

FlakeRT flakeAt(const InterferenceFlakeOptics& f, FlakeWorkspace& ws, double cos_theta, double wavelength_nm,
                const ThicknessQuadrature& q) {
    cos_theta = std::clamp(cos_theta, 0.0, 1.0);
    if (!(cos_theta > 0.0)) return {1.0, 0.0};  // grazing: Born & Wolf r -> -1
    const double n0 = f.binder_n;
    const double s2 = n0 * n0 * (1.0 - cos_theta * cos_theta);
    const double k0 = 2.0 * std::numbers::pi / wavelength_nm;
    // Harmonics of R in a layer's phase decay like rho^m, rho ~ the largest
    // interface reflection amplitude (s-polarised, which is the larger): it
    // tends to 1 at grazing incidence, where the flake becomes a high-finesse
    // cavity. The trapezoid rule on K phases aliases harmonic K, so
    // K >= ln(tolerance) / ln(rho). Measured decay per harmonic (40/10 nm spreads,
    // cos 0.1 / 0.2 / 0.3): 0.81 / 0.75 / 0.67, against |r_s| = 0.87 / 0.76 / 0.66.
    const C P0(n0 * cos_theta);
    const C P_t = normalIndex(f.tio2_n, s2);
    const C P_m = normalIndex(f.mica_n, s2);
    const double rho = std::max(std::abs((P0 - P_t) / (P0 + P_t)), std::abs((P_t - P_m) / (P_t + P_m)));
    const double tol = std::clamp(q.tolerance, 1e-15, 0.5);
    int min_nodes = kMaxPeriodNodes;  // rho >= 1: capped by max_period_nodes
    if (rho < 1.0) {
        min_nodes = rho > 0.0 ? static_cast<int>(std::min(static_cast<double>(kMaxPeriodNodes),
                                                          std::ceil(std::log(tol) / std::log(rho))))
                              : 1;
    }
    buildLayerNodes(ws.tio2, f.tio2_n, f.tio2_thickness_nm, f.tio2_thickness_spread_nm, s2, k0, 2, min_nodes,
                    q);
    // Incident and exit medium are both the binder.
    const double Y1_te = n0 * cos_theta;
    const double Y1_tm = cos_theta / n0;
    const bool mica_lossless = f.mica_n.imag() == 0.0 && P_m.real() > 0.0 && P_m.imag() == 0.0;
    if (q.analytic_mica && !q.force_gauss_hermite && mica_lossless && f.mica_thickness_spread_nm > 0.0 &&
        micaMoments(ws, f.mica_thickness_nm, f.mica_thickness_spread_nm, k0, P_m.real(), tol)) {
        const C Y_te = P_m, Y_tm = P_m / (f.mica_n * f.mica_n);
        double Rs = 0.0, Rp = 0.0, Ts = 0.0, Tp = 0.0;
        bool ok = true;
        for (std::size_t i = 0; i < ws.tio2.w.size() && ok; ++i) {
            const LayerPair& t = ws.tio2.mats[i];
            double rs = 0.0, ts = 0.0, rp = 0.0, tp = 0.0;
            ok = averageOverMica(t.te, Y_te, Y1_te, ws.moments, tol, rs, ts) &&
                 averageOverMica(t.tm, Y_tm, Y1_tm, ws.moments, tol, rp, tp);
            const double w = ws.tio2.w[i];
            Rs += w * rs;
            Ts += w * ts;
            Rp += w * rp;
            Tp += w * tp;
        }
        if (ok) return {std::clamp(0.5 * (Rs + Rp), 0.0, 1.0), std::clamp(0.5 * (Ts + Tp), 0.0, 1.0)};
    }
    buildLayerNodes(ws.mica, f.mica_n, f.mica_thickness_nm, f.mica_thickness_spread_nm, s2, k0, 1, min_nodes,
                    q);
    double Rs = 0.0, Rp = 0.0, Ts = 0.0, Tp = 0.0;
    for (std::size_t i = 0; i < ws.tio2.w.size(); ++i) {
        const LayerPair& t = ws.tio2.mats[i];
        for (std::size_t j = 0; j < ws.mica.w.size(); ++j) {
            const LayerPair& m = ws.mica.mats[j];
            const PolResult s = terminate(mul(mul(t.te, m.te), t.te), Y1_te, C(Y1_te));
            const PolResult p = terminate(mul(mul(t.tm, m.tm), t.tm), Y1_tm, C(Y1_tm));
            const double w = ws.tio2.w[i] * ws.mica.w[j];
            Rs += w * s.R;
            Ts += w * s.T;
            Rp += w * p.R;
            Tp += w * p.T;
        }
    }
    return {std::clamp(0.5 * (Rs + Rp), 0.0, 1.0), std::clamp(0.5 * (Ts + Tp), 0.0, 1.0)};
}

}  // namespace

FilmResponse multilayerResponse(double n_incident, std::span<const ThinLayer> layers,
                                std::complex<double> n_exit, double cos_incident, double wavelength_nm) {
    FilmResponse out;
    cos_incident = std::clamp(cos_incident, 0.0, 1.0);
    if (!(cos_incident > 0.0) || !(n_incident > 0.0) || !(wavelength_nm > 0.0)) {
        out.Rs = out.Rp = 1.0;
        out.rs = out.rp = C(-1.0);
        return out;
    }
    const double s2 = n_incident * n_incident * (1.0 - cos_incident * cos_incident);
    const double k0 = 2.0 * std::numbers::pi / wavelength_nm;
    Mat2 te{C(1.0), C(0.0), C(0.0), C(1.0)};
    Mat2 tm = te;
    for (const ThinLayer& layer : layers) {
        const LayerPair lp = layerMatrices(normalIndex(layer.n, s2), layer.n * layer.n,
                                           k0 * std::max(0.0, layer.thickness_nm));
        te = mul(te, lp.te);
        tm = mul(tm, lp.tm);
    }
    const C P_l = normalIndex(n_exit, s2);
    const PolResult s = terminate(te, n_incident * cos_incident, P_l);
    const PolResult p = terminate(tm, cos_incident / n_incident, P_l / (n_exit * n_exit));
    out.rs = s.r;
    out.rp = p.r;
    out.Rs = s.R;
    out.Ts = s.T;
    out.Rp = p.R;
    out.Tp = p.T;
    return out;
}

FlakeRT interferenceFlakeRT(const InterferenceFlakeOptics& flake, double cos_theta, double wavelength_nm,
                            ThicknessQuadrature quadrature) {
    if (!(wavelength_nm > 0.0)) return {1.0, 0.0};
    FlakeWorkspace ws;
    return flakeAt(flake, ws, cos_theta, wavelength_nm, quadrature);
}

void tabulateInterferenceFlake(const InterferenceFlakeOptics& flake, double wavelength_nm,
                               std::span<const double> cos_grid, std::span<double> R_out,
                               std::span<double> T_out, ThicknessQuadrature quadrature) {
    const std::size_t n = std::min({cos_grid.size(), R_out.size(), T_out.size()});
    FlakeWorkspace ws;
    for (std::size_t i = 0; i < n; ++i) {
        const FlakeRT rt = wavelength_nm > 0.0 ? flakeAt(flake, ws, cos_grid[i], wavelength_nm, quadrature)
                                               : FlakeRT{1.0, 0.0};
        R_out[i] = rt.R;
        T_out[i] = rt.T;
    }
}

double metalFlakeReflectance(double cos_theta, std::complex<double> metal_n, double binder_n) {
    return fresnelReflectance(cos_theta, C(binder_n), metal_n);
}

double mirrorFlakeReflectanceFromNormal(double cos_theta, double R0_normal) {
    const double R0 = std::clamp(R0_normal, 0.0, 1.0);
    if (R0 >= 1.0) return 1.0;
    if (R0 <= 0.0) return 0.0;  // index-matched effective medium: no interface
    const double k_eff = 2.0 * std::sqrt(R0 / (1.0 - R0));
    return fresnelReflectance(cos_theta, C(1.0), C(1.0, k_eff));
}

}  // namespace paintlab
