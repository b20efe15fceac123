#include "stack_assembly.h"

#include "paintlab/engine/layer_optics.h"
#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace paintlab::fast {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

InterfaceElement interfaceBetween(const StackQuadrature& grid, double n_above, double n_below) {
    const int n = grid.size();
    InterfaceElement e{VectorXd::Zero(n), VectorXd::Ones(n), VectorXd::Zero(n), VectorXd::Ones(n)};
    for (int k = 0; k < n; ++k) {
        const double s = grid.invariant(k);
        const bool above = s < n_above * (1.0 - 1e-12);
        const bool below = s < n_below * (1.0 - 1e-12);
        if (above && below) {
            const double mu_above = std::sqrt(1.0 - (s / n_above) * (s / n_above));
            const double r =
                fresnelDielectric(mu_above, n_below / n_above);  // the same from below (reciprocity)
            e.R01(k) = e.R10(k) = r;
            e.T01(k) = e.T10(k) = 1.0 - r;
        } else if (above) {  // total internal reflection on the upper side
            e.R01(k) = 1.0;
            e.T01(k) = e.R10(k) = e.T10(k) = 0.0;
        } else if (below) {
            e.R10(k) = 1.0;
            e.T10(k) = e.R01(k) = e.T01(k) = 0.0;
        }
        // In neither medium: carries no flux; left as a pass-through so no loop is singular.
    }
    return e;
}

double substrateIndexBelow(const Substrate& s) {
    if (const auto* t = std::get_if<TransparentSubstrate>(&s)) return t->refractive_index;
    return 0.0;
}

std::vector<MatrixXd> substrateReflection(const Recipe& recipe, const StackQuadrature& grid, double n_last,
                                          double wavelength_nm, int orders) {
    const int n = grid.size();
    std::vector<MatrixXd> R(static_cast<std::size_t>(orders), MatrixXd::Zero(n, n));
    const MediumNodes last = grid.medium(n_last);
    if (const auto* lambert = std::get_if<LambertianSubstrate>(&recipe.substrate)) {
        // A Lambertian surface in the binder sends reflected flux into each
        // direction cell in proportion to its flux weight; azimuth-independent (order 0).
        const double rho = lambert->albedo(wavelength_nm);
        for (std::size_t a = 0; a < last.node.size(); ++a)
            for (std::size_t b = 0; b < last.node.size(); ++b)
                R[0](last.node[a], last.node[b]) = rho * last.quadrature.fluxWeight(static_cast<int>(a));
    } else if (const auto* metal = std::get_if<MetalSubstrate>(&recipe.substrate)) {
        // A polished metal is a mirror: diagonal in every order.
        const std::complex<double> n_metal(metal->n(wavelength_nm), metal->k(wavelength_nm));
        for (std::size_t a = 0; a < last.node.size(); ++a) {
            const double r = fresnelReflectance(last.quadrature.mu[a], n_last, n_metal);
            for (auto& Rm : R) Rm(last.node[a], last.node[a]) = r;
        }
    } else if (const auto* transparent = std::get_if<TransparentSubstrate>(&recipe.substrate)) {
        // Light crossing into the medium below is gone (two-sided measurements).
        const InterfaceElement e = interfaceBetween(grid, n_last, transparent->refractive_index);
        for (auto& Rm : R) Rm.diagonal() = e.R01;
    }
    return R;  // black: nothing comes back
}

// X = (I - B)^-1 Y with B = R_below R10_above, guarding decoupled modes: a
// node trapped between two totally reflecting faces of a clear layer gets no
// light (Y's row is zero) but makes (I - B) singular; its equation is
// replaced by X_k = 0.
MatrixXd solveLoop(const MatrixXd& B, const MatrixXd& Y) {
    const auto n = B.rows();
    MatrixXd M = MatrixXd::Identity(n, n) - B;
    for (Eigen::Index k = 0; k < n; ++k) {
        if (std::abs(M(k, k)) > 1e-12) continue;
        const double coupling =
            M.row(k).cwiseAbs().sum() + M.col(k).cwiseAbs().sum() - 2.0 * std::abs(M(k, k));
        if (coupling < 1e-12) M(k, k) = 1.0;
    }
    return M.partialPivLu().solve(Y);
}

}  // namespace

BandStack buildBandStack(const Recipe& recipe, double wavelength_nm, const FastModelSettings& settings) {
    std::vector<double> indices{recipe.ambient_refractive_index};
    for (const auto& layer : recipe.layers) indices.push_back(layer.binder.refractive_index(wavelength_nm));
    if (const double below = substrateIndexBelow(recipe.substrate); below > 0.0) indices.push_back(below);
    BandStack stack{
        wavelength_nm, StackQuadrature(settings.nodes, indices), recipe.ambient_refractive_index, {}, {}};

    double n_above = recipe.ambient_refractive_index;
    const FlakeSampling sampling{settings.flake_polar, settings.flake_azimuth, settings.flake_table,
                                 settings.flake_kernel_points_per_spread};
    for (const auto& layer : recipe.layers) {
        const double n_layer = layer.binder.refractive_index(wavelength_nm);
        if (std::abs(n_layer - n_above) > kSameIndex)
            stack.elements.emplace_back(interfaceBetween(stack.grid, n_above, n_layer));
        const auto bounds = sliceBoundaries(layer, settings.slices);
        for (std::size_t s = 1; s < bounds.size(); ++s) {
            const SlabOptics optics = slabOptics(layer, wavelength_nm, bounds[s - 1], bounds[s]);
            SlabElement slab{stack.grid.medium(n_layer), {}, optics.thickness_um};
            slab.kernels = slabKernels(optics, slab.medium.quadrature, wavelength_nm, settings.orders - 1,
                                       settings.nodes, sampling);
            if (slab.kernels.max_extinction_per_um > 0.0) stack.elements.emplace_back(std::move(slab));
        }
        n_above = n_layer;
    }
    stack.substrate = substrateReflection(recipe, stack.grid, n_above, wavelength_nm, settings.orders);
    return stack;
}

MatrixXd stackReflection(const BandStack& stack, int m, const FastModelSettings& settings) {
    const int n = stack.grid.size();
    MatrixXd R = stack.substrate[static_cast<std::size_t>(m)];
    // Bottom-up (an index loop: clang 14's ranges do not accept libstdc++ 12's reverse view).
    for (std::size_t k = stack.elements.size(); k-- > 0;) {
        const auto& element = stack.elements[k];
        if (const auto* e = std::get_if<InterfaceElement>(&element)) {
            // R_new = R01 + T10 (I - R R10)^-1 R T01, all of the interface diagonal.
            const MatrixXd X = solveLoop(R * e->R10.asDiagonal(), R * e->T01.asDiagonal());
            R = MatrixXd(e->R01.asDiagonal()) + e->T10.asDiagonal() * X;
        } else {
            const auto& slab = std::get<SlabElement>(element);
            const layered::LayerOperator local = slabOperator(slab.kernels, slab.medium.quadrature, m,
                                                              slab.thickness_um, settings.max_start_tau);
            // Embed on the full grid: nodes that do not exist in this medium pass untouched.
            MatrixXd R01 = MatrixXd::Zero(n, n);
            MatrixXd T01 = MatrixXd::Identity(n, n);
            const auto& idx = slab.medium.node;
            for (std::size_t a = 0; a < idx.size(); ++a) {
                for (std::size_t b = 0; b < idx.size(); ++b) {
                    R01(idx[a], idx[b]) =
                        local.R01(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
                    T01(idx[a], idx[b]) =
                        local.T01(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
                }
            }
            // The slab is symmetric (R10 = R01, T10 = T01).
            const MatrixXd X = solveLoop(R * R01, R * T01);
            R = R01 + T01 * X;
        }
    }
    return R;
}

}  // namespace paintlab::fast
