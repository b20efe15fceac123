#pragma once
// Smooth dielectric boundaries of a slab: a Fresnel interface to the outside
// medium (air, index 1), optionally through a non-absorbing glass slide.
//
// The operators are diagonal flux-to-flux matrices on the slab's node set (see
// layer_operator.h). The outside side uses the same indices: slab node k with
// mu_k above the critical cosine maps by Snell's law (n sin theta conserved) to
// one outside direction. Because n^2 mu dmu is conserved by refraction (radiance
// divided by n^2 is invariant along a refracted ray), the flux a uniform outside
// radiance 1 brings into that direction cell is n^2 c_k (outsideFluxWeights);
// these sum to 1 exactly since the escape cone holds 1 - mu_c^2 = 1/n^2 of the
// slab's flux weights. Nodes below mu_c have no outside direction: their outside
// entries are zero and they are totally reflected inside (exactly 1).
//
// A slide is treated incoherently, as Prahl does (Prahl 1995, boundary conditions with glass slides): with r1
// the air-glass and r2 the glass-slab reflectance at the same n sin theta,
//   R_outside = r1 + (1-r1)^2 r2 / (1 - r1 r2),  R_inside = r2 + (1-r2)^2 r1 / (1 - r1 r2),
//   T = (1-r1)(1-r2) / (1 - r1 r2),
// which is 1 for R_inside whenever either interface totally reflects.

#include "paintlab/engine/layered/layer_operator.h"
#include "paintlab/engine/layered/quadrature.h"

#include <Eigen/Dense>

namespace paintlab::layered {

struct BoundaryReflectance {
    double outside = 0.0;  // incident from the outside medium
    double inside = 0.0;   // incident from the slab
    double transmitted = 1.0;
};

// For a direction with cosine mu_slab inside a slab of index n_slab under a slide of index
// n_slide (1 = no slide) with air (index 1) outside. Never throws.
BoundaryReflectance boundaryReflectance(double mu_slab, double n_slab, double n_slide);

// Boundary above the slab (outside on top) and below it (outside at the bottom).
LayerOperator topBoundary(const Quadrature& q, double n_slab, double n_slide);
LayerOperator bottomBoundary(const Quadrature& q, double n_slab, double n_slide);

// n_slab^2 c_k for nodes in the escape cone, 0 below the critical cosine (sum 1).
Eigen::VectorXd outsideFluxWeights(const Quadrature& q, double n_slab);

}  // namespace paintlab::layered
