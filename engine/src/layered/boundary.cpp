#include "paintlab/engine/layered/boundary.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>

namespace paintlab::layered {

namespace {

// Reflectance of the interface between media of indices n_a and n_b for the
// Snell invariant s = n sin(theta); 1 when the direction cannot exist in the
// lower-index medium (total internal reflection seen from the other side).
double interfaceReflectance(double s, double n_a, double n_b) {
    if (n_a == n_b) return 0.0;
    if (s >= std::min(n_a, n_b)) return 1.0;
    const double sin_a = s / n_a;
    const double cos_a = std::sqrt(std::max(0.0, 1.0 - sin_a * sin_a));
    return fresnelDielectric(cos_a, n_b / n_a);
}

}  // namespace

BoundaryReflectance boundaryReflectance(double mu_slab, double n_slab, double n_slide) {
    const double s = n_slab * std::sqrt(std::max(0.0, 1.0 - mu_slab * mu_slab));
    BoundaryReflectance b;
    if (s >= 1.0) {  // cannot reach the air: totally reflected, whatever the slide does
        b.outside = 0.0;
        b.inside = 1.0;
        b.transmitted = 0.0;
        return b;
    }
    const double r1 = interfaceReflectance(s, 1.0, n_slide);
    const double r2 = interfaceReflectance(s, n_slide, n_slab);
    const double denom = 1.0 - r1 * r2;
    b.outside = r1 + (1.0 - r1) * (1.0 - r1) * r2 / denom;
    b.inside = r2 + (1.0 - r2) * (1.0 - r2) * r1 / denom;
    b.transmitted = (1.0 - r1) * (1.0 - r2) / denom;
    return b;
}

LayerOperator topBoundary(const Quadrature& q, double n_slab, double n_slide) {
    const int n = q.size();
    LayerOperator op{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n),
                     Eigen::MatrixXd::Zero(n, n)};
    for (int k = 0; k < n; ++k) {
        const BoundaryReflectance b = boundaryReflectance(q.mu[static_cast<std::size_t>(k)], n_slab, n_slide);
        op.R01(k, k) = b.outside;
        op.T01(k, k) = b.transmitted;
        op.R10(k, k) = b.inside;
        op.T10(k, k) = b.transmitted;
    }
    return op;
}

LayerOperator bottomBoundary(const Quadrature& q, double n_slab, double n_slide) {
    LayerOperator top = topBoundary(q, n_slab, n_slide);
    // The same interface seen upside down: inside is now on top.
    return {top.R10, top.T10, top.R01, top.T01};
}

Eigen::VectorXd outsideFluxWeights(const Quadrature& q, double n_slab) {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(q.size());
    for (int k = q.n_trapped; k < q.size(); ++k) c(k) = n_slab * n_slab * q.fluxWeight(k);
    return c;
}

}  // namespace paintlab::layered
