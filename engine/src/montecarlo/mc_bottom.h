#pragma once
// The flake-free bottom of the paint as one reflecting surface of the walk
// (McSettings::bottom_operator).
//
// Every layer below the lowest layer with flakes, with the substrate, is a
// pigment continuum in the full model as in the fast model: the walk through
// it solves the same radiative transfer equation that the fast model's adding
// and doubling solves (fast::buildBandStack, fast::stackReflection), so
// replacing that walk by the bottom's reflection operator changes the method
// (a quadrature of n nodes in mu and Fourier orders in azimuth, interpolated
// linearly in mu) and not the physics. The flake layers above are still walked
// by the Monte Carlo: the full model stays independent of the fast model
// wherever a flake is.
//
// Used only where the operator has no mirror (delta) part, which a smooth
// surface cannot carry: no index step at or inside the bottom (the binders
// all have the index of the layer above it), a Lambertian or black substrate,
// and pigment phase functions whose delta-M truncation at n moments
// (fast::scaledMedium) moves less than kMaxTruncation of their scattering.
// Elsewhere the walk goes on explicitly.
//
// The operator in the bottom's medium: f(mu_i, mu_o, dphi) (1/sr) =
// sum_m (2 - delta_m0) f^m(mu_o, mu_i) cos(m dphi), dphi the azimuth between
// the propagation directions in and out, f^m = R^m / (pi c_o) from the
// flux-to-flux matrices (layer_operator.h) at the nodes; f^m (mu_o + mu_i)
// (single scattering's 1 / (mu_o + mu_i) taken out) is bilinear in (mu_o,
// mu_i) between them and constant below the first node (the last node is
// mu = 1: the bottom is one medium, so its Gauss-Radau nodes end at the
// normal). Each incident
// node's f^m is rescaled so that the interpolated f^0 reflects exactly the
// matrices' albedo (the quadrature's column sum): a non-absorbing bottom
// reflects everything, as it does in the walk.

#include "mc_random.h"
#include "mc_stack.h"

#include "paintlab/engine/recipe.h"

#include <memory>
#include <vector>

namespace paintlab::mc {

class BottomOperator {
public:
    // Quadrature nodes per hemisphere and Fourier orders of the tabulation,
    // and the azimuth bins of the sampling tables over [0, pi].
    static constexpr int kNodes = 48;
    static constexpr int kOrders = 32;
    static constexpr int kAzimuthBins = 64;
    static constexpr double kMaxTruncation = 1e-4;

    // The operator of recipe layers [first_layer, end) and the substrate at
    // this wavelength, in a medium of index n (that of every one of those
    // layers); `slices`: per layer with a depth profile (McSettings::slices);
    // `nodes`: per hemisphere (another count only to measure the interpolation).
    BottomOperator(const Recipe& recipe, std::size_t first_layer, double n, double wavelength_nm, int slices,
                   int nodes = kNodes);

    // f (1/sr) from the downward propagation direction v into the upward u (unit vectors).
    double eval(const Vec3& v, const Vec3& u) const;
    // The density (1/sr) with which sample() draws u after v.
    double pdf(const Vec3& v, const Vec3& u) const;
    // An upward direction after v, drawn by importance (the incident node by
    // linear weights, the exit cell by its share of the reflected flux, mu in it
    // by the cosine, the azimuth from the tabulated Fourier series); `factor`
    // gets f u_z / pdf (0 when nothing is reflected).
    Vec3 sample(const Vec3& v, PathRng& rng, double& factor) const;

    // Whether the Fourier series fell below 1e-7 of order 0 within kOrders
    // (otherwise the operator would drop its tail: attachBottomOperator declines it).
    bool seriesConverged() const { return m_series_converged; }

    // Albedo of the interpolated operator at an incident cosine (the matrices' column sums, linear).
    double albedo(double mu_i) const;
    int orders() const { return m_orders; }
    const std::vector<double>& nodes() const { return m_mu; }
    // Largest |scale - 1| of the per-node rescaling to the matrices' albedo (the interpolation's
    // error in the reflected flux).
    double largestRescale() const { return m_largest_rescale; }

private:
    double at(int m, int o, int i) const {
        return m_f[(static_cast<std::size_t>(m) * m_mu.size() + static_cast<std::size_t>(o)) * m_mu.size() +
                   static_cast<std::size_t>(i)];
    }
    // Node below mu and the linear weight of the one above; beyond the ends
    // flat (`extrapolate` only matters above the last node, which is mu = 1).
    void locate(double mu, int& k, double& t, bool extrapolate = false) const;
    int cellOf(double mu) const;
    // What the tabulated g = f (mu_o + mu_i) is divided by; never below the first
    // node, so that f stays bounded beyond it (exact at every node pair).
    double denominator(double mu_o, double mu_i) const { return std::max(mu_o + mu_i, m_mu.front()); }
    // The interpolated f^0 at incident node i.
    double nodeF0(int i, double mu_o) const;
    // The density of sample() after incident node i at cell `cell`, cosine mu_o, azimuth bin `bin`.
    double nodePdf(int i, int cell, double mu_o, std::size_t bin) const;
    // f at the cosines in and out and the cosine of the azimuth between them.
    double evalAt(double mu_i, double mu_o, double cos_dphi) const;

    int m_orders = 0;
    bool m_series_converged = false;
    std::vector<double> m_mu;           // node cosines, ascending
    std::vector<double> m_f;            // g^m = f^m(mu_o, mu_i) (mu_o + mu_i), [(m * n + o) * n + i]
    std::vector<double> m_albedo;       // per incident node
    std::vector<double> m_edges;        // n + 1 sampling cells in mu (0, midpoints, 1)
    std::vector<double> m_cell_cdf;     // [i * (n + 1) + o]: P(cell < o | node i)
    std::vector<double> m_azimuth_cdf;  // [(i * n + o) * (bins + 1) + k] over [0, pi]
    double m_largest_rescale = 0.0;
};

// Replaces the slices of the flake-free bottom of `stack` (built from
// `recipe`, flakes not yet removed for tiles) by a BottomOperator when the
// conditions above hold; returns whether it did. Throws Error (from the
// fast model's stack assembly) for a recipe it cannot assemble.
bool attachBottomOperator(PaintStack& stack, const Recipe& recipe, int slices);

}  // namespace paintlab::mc
