#pragma once
// The reflection/transmission operators of one homogeneous slab of paint
// (binder + pigments + flakes, SlabOptics at one wavelength) per Fourier order,
// on the nodes that exist in the slab's medium.
//
// The thin-sublayer physics (shared/ARCHITECTURE.md): per unit length, a
// direction i loses radiance at the rate e_i (pigment extinction plus the
// flakes' projected area, direction dependent) and gains K_ij w_j L_j from
// every node j, where K = pigment scattering (delta-M Henyey-Greenstein lobes)
// + flake reflection (oriented two-sided mirrors, reflection through the half
// vector). A starting layer thin enough for single scattering is written by
// the diamond scheme with exponential fitting, then doubled to the slab.

#include "paintlab/engine/layer_optics.h"
#include "paintlab/engine/layered/layer_operator.h"
#include "paintlab/engine/layered/quadrature.h"

#include <Eigen/Dense>

#include <vector>

namespace paintlab::fast {

// Sources per unit length (1/µm) for one Fourier order: K_same (i, j) couples
// directions in the same hemisphere, K_opp (i, j) reflects (j in the other one).
struct OrderKernel {
    Eigen::MatrixXd same;
    Eigen::MatrixXd opposite;
};

struct SlabKernels {
    Eigen::VectorXd extinction_per_um;  // e_i
    Eigen::VectorXd
        scattering_per_um;  // what direction j scatters in all, sum_i w_i (K_same + K_opp)_ij at m = 0
    std::vector<OrderKernel> orders;  // m = 0 .. M
    double max_extinction_per_um = 0.0;
};

struct FlakeSampling {
    int polar = 24;                         // Gauss nodes in the flake normal's tilt (per smooth piece)
    int azimuth = 48;                       // and azimuth (per smooth piece of [0, pi])
    int table = 129;                        // cosines of the flakes' R(cos), T(cos) table
    double kernel_points_per_spread = 4.0;  // azimuth points per spread sigma in the kernel's Fourier sums
};

// The pigments' phase function as the kernels use it: Legendre moments of the
// HG mixture with the delta-M truncation (Wiscombe 1977), which moves the
// fraction f = chi_N of the forward peak into the unscattered beam.
struct ScaledMedium {
    std::vector<double> chi;  // chi*_l, l < n_moments
    double f = 0.0;
    double sigma_s = 0.0;  // (1 - f) sigma_s, 1/µm
    double sigma_a = 0.0;
};
ScaledMedium scaledMedium(const SlabOptics& slab, int n_moments);

// The flakes' extinction (1/µm: projected area of all kinds) for directions
// with these cosines in the slab's medium, as the kernels compute it at nodes.
std::vector<double> flakeExtinction(const SlabOptics& slab, double wavelength_nm,
                                    const std::vector<double>& cosines, const FlakeSampling& sampling);

// Kernels of the slab for orders 0..max_order on the medium quadrature q
// (cosines and weights in the slab's medium). n_moments: Legendre moments kept
// for the pigment phase functions (delta-M beyond them).
SlabKernels slabKernels(const SlabOptics& slab, const layered::Quadrature& q, double wavelength_nm,
                        int max_order, int n_moments, const FlakeSampling& sampling);

// Operator of the slab (thickness slab_thickness_um) for one order by
// diamond start + doubling; max_start_tau bounds the starting layer's largest
// optical thickness e_i * d. Flux-to-flux, as layer_operator.h.
layered::LayerOperator slabOperator(const SlabKernels& kernels, const layered::Quadrature& q, int m,
                                    double thickness_um, double max_start_tau);

}  // namespace paintlab::fast
