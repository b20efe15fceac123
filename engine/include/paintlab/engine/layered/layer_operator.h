#pragma once
// Reflection and transmission operators of a plane-parallel layer for one
// azimuthal Fourier order, and the adding and doubling of layers
// (van de Hulst 1980; Prahl 1995, adding and doubling).
//
// Representation: flux-to-flux matrices. Column j is the response to a unit flux
// arriving in node direction j; entry (i, j) the flux leaving in node direction i.
// With the flux weights c_i = 2 mu_i w_i of Quadrature, they relate to Prahl's
// radiance "star" matrices by G = diag(c) R_star, so his star products become
// plain matrix products and energy conservation reads: column sums of R + T = 1.
// Reciprocity reads: diag(c)^-1 R is symmetric (for one medium on both sides).
//
// Index 0 is the top side, 1 the bottom side of a layer:
//   R01: incident from above, reflected up;  T01: incident from above, transmitted down;
//   R10: incident from below, reflected down; T10: incident from below, transmitted up.

#include "paintlab/engine/layered/phase_function.h"
#include "paintlab/engine/layered/quadrature.h"

#include <Eigen/Dense>

namespace paintlab::layered {

struct LayerOperator {
    Eigen::MatrixXd R01, T01, R10, T10;

    static LayerOperator identity(int n);  // tau = 0: no reflection, full transmission
};

// Adding (Prahl 1995; van de Hulst 1980) of `top` over `bottom`, with LU solves of
// (I - R10_top R01_bottom) and (I - R01_bottom R10_top); no inverse is formed.
LayerOperator addLayers(const LayerOperator& top, const LayerOperator& bottom);

struct DoublingOptions {
    // Largest optical thickness of the starting layer; the start is tau / 2^k <= this.
    // The diamond start is second order: the doubled result errs by O(tau_start^2)
    // (the layer tests measure it; docs/CHANGELOG.md has the figures).
    double max_start_tau = 1.0 / 4096.0;
    // Semi-infinite layers are doubled until R changes by less than this and T is below it.
    double semi_infinite_tolerance = 1e-13;
    int max_doublings = 200;
    // Conservative (albedo 1) semi-infinite layers stop doubling at this thickness and
    // close the remaining transmission back into reflection (see homogeneousSlab).
    double conservative_closure_tau = 1e5;
};

// Starting layer of optical thickness d for Fourier order m: the diamond
// (trapezoidal) initialisation of Wiscombe 1976 (JQSRT 16, 637) and Prahl 1995, with the
// cosine of every node replaced by its exponentially fitted value
//   mu'_i = (d/2) / tanh(d/(2 mu_i)),  w'_i = w_i mu_i / mu'_i
// so that the unscattered transmission is exactly exp(-d/mu_i) (the plain diamond
// gives (1 - d/2mu)/(1 + d/2mu)) while the flux weights 2 mu' w' = 2 mu w, and hence
// exact energy conservation of the diamond scheme, are unchanged. For m = 0 the
// phase matrix is renormalised on its diagonal so each column scatters exactly
// the albedo (the forward direction absorbs the quadrature's normalisation error).
LayerOperator startLayer(const Quadrature& q, const PhaseMatrices& h, double albedo, double d, int m);

// Homogeneous slab of optical thickness tau (0, finite, or +infinity) and single
// scattering albedo, by doubling the starting layer. tau = 0 and albedo = 0 are
// computed in closed form (exact). tau = infinity doubles until R settles and T vanishes;
// for albedo 1 (where T only falls as 1/tau) see DoublingOptions::conservative_closure_tau.
// Never throws.
LayerOperator homogeneousSlab(const Quadrature& q, const PhaseMatrices& h, double albedo, double tau, int m,
                              const DoublingOptions& options = {});

}  // namespace paintlab::layered
