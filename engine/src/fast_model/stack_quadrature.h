#pragma once
// The angular grid of a whole paint stack at one wavelength.
//
// Every direction is labelled by the Snell invariant s = n sin(theta), which
// refraction through plane interfaces conserves. The nodes are chosen in the
// medium of highest index n_ref (where every direction that exists anywhere
// in the stack exists), and the quadrature in mu_ref is split at the critical
// cosine of every lower index in the stack, so that in each medium the nodes
// that exist there (s < n) fill its whole hemisphere and no node straddles a
// total internal reflection (shared/ARCHITECTURE.md, "The fast model").
//
// Flux is conserved by refraction and n^2 mu dmu is invariant, so one
// flux-to-flux matrix on this node set describes a layer in any medium: in a
// medium of index n the node k has cosine mu_k(n) = sqrt(1 - s_k^2 / n^2)
// and flux weight (n_ref / n)^2 c_k.

#include "paintlab/engine/layered/quadrature.h"

#include <vector>

namespace paintlab::fast {

// Refractive indices closer than this are one medium: no interface between
// them and no split of the quadrature (the stack assembly, the Monte Carlo
// bottom operator).
inline constexpr double kSameIndex = 1e-9;

struct MediumNodes {
    double index = 1.0;
    std::vector<int> node;           // indices (into the stack grid) of the nodes that exist here
    layered::Quadrature quadrature;  // those nodes' cosines and weights in this medium
};

class StackQuadrature {
public:
    // n_nodes per hemisphere (>= 4); indices: every refractive index in the
    // stack (ambient, binders, medium below), all >= 1.
    StackQuadrature(int n_nodes, const std::vector<double>& indices);

    int size() const { return static_cast<int>(m_mu_ref.size()); }
    double referenceIndex() const { return m_n_ref; }
    const std::vector<double>& muRef() const { return m_mu_ref; }
    const std::vector<double>& weightRef() const { return m_weight_ref; }
    // sin(theta) in the reference medium times n_ref.
    double invariant(int k) const;
    // Index of the split interval node k lies in (ascending with mu), and the
    // lower end in mu_ref of interval i: the nodes of one interval are one
    // Gauss rule, so a function smooth there interpolates spectrally.
    int interval(int k) const { return m_interval[static_cast<std::size_t>(k)]; }
    double intervalLow(int i) const { return m_interval_low[static_cast<std::size_t>(i)]; }
    // The nodes that exist in a medium of this index, with their cosines and weights there.
    MediumNodes medium(double index) const;

private:
    double m_n_ref = 1.0;
    std::vector<double> m_mu_ref;
    std::vector<double> m_weight_ref;
    std::vector<int> m_interval;
    std::vector<double> m_interval_low;
};

}  // namespace paintlab::fast
