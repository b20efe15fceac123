#pragma once
// The paint as a stack of operators on one angular grid (stack_quadrature.h):
// Fresnel interfaces where the index changes, one slab per (slice of a)
// layer, the substrate at the bottom. Reflection of the whole stack is added
// bottom-up per Fourier order with LU solves (never an inverse).

#include "slab_operator.h"
#include "stack_quadrature.h"

#include "paintlab/engine/fast_model/layered_brdf.h"

#include <Eigen/Dense>

#include <variant>
#include <vector>

namespace paintlab::fast {

// A smooth dielectric interface: diagonal, the same for every Fourier order.
struct InterfaceElement {
    Eigen::VectorXd R01, T01, R10, T10;
};

struct SlabElement {
    MediumNodes medium;
    SlabKernels kernels;
    double thickness_um = 0.0;
};

struct BandStack {
    double wavelength_nm = 0.0;
    StackQuadrature grid;
    double ambient_index = 1.0;
    std::vector<std::variant<InterfaceElement, SlabElement>> elements;  // top first
    // Substrate reflection from above: per-order matrices (Lambertian: order 0 only).
    std::vector<Eigen::MatrixXd> substrate;
};

BandStack buildBandStack(const Recipe& recipe, double wavelength_nm, const FastModelSettings& settings);

// Reflection of the whole stack from above, for order m (flux-to-flux, full grid).
Eigen::MatrixXd stackReflection(const BandStack& stack, int m, const FastModelSettings& settings);

}  // namespace paintlab::fast
