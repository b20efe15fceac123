#include "stack_quadrature.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace paintlab::fast {

StackQuadrature::StackQuadrature(int n_nodes, const std::vector<double>& indices) {
    m_n_ref = *std::max_element(indices.begin(), indices.end());
    // Split points: the critical cosines of the lower indices seen from n_ref.
    std::vector<double> splits{0.0, 1.0};
    for (double n : indices) {
        if (n < m_n_ref - kSameIndex) splits.push_back(std::sqrt(1.0 - (n / m_n_ref) * (n / m_n_ref)));
    }
    std::sort(splits.begin(), splits.end());
    splits.erase(std::unique(splits.begin(), splits.end(), [](double a, double b) { return b - a < 1e-12; }),
                 splits.end());
    const int intervals = static_cast<int>(splits.size()) - 1;
    // Nodes in proportion to the flux each interval carries, b^2 - a^2 (as the
    // slab quadrature does, quadrature.h), at least two per interval, by
    // largest remainders. The interval towards the normal is the escape cone of
    // the lowest index (the ambient's, in a paint): the only directions the
    // outside sees, where the BRDF is evaluated and its lobes are.
    std::vector<int> counts(static_cast<std::size_t>(intervals), 2);
    const int spare = std::max(0, n_nodes - 2 * intervals);
    std::vector<std::pair<double, int>> remainders;
    int given = 0;
    for (int i = 0; i < intervals; ++i) {
        const double a = splits[static_cast<std::size_t>(i)];
        const double b = splits[static_cast<std::size_t>(i) + 1];
        const double share = (b * b - a * a) * spare;
        const int whole = static_cast<int>(std::floor(share));
        counts[static_cast<std::size_t>(i)] += whole;
        given += whole;
        remainders.emplace_back(share - whole, i);
    }
    std::sort(remainders.begin(), remainders.end(), [](const auto& x, const auto& y) {
        return x.first > y.first || (x.first == y.first && x.second > y.second);
    });
    for (std::size_t r = 0; given < spare && r < remainders.size(); ++r, ++given)
        ++counts[static_cast<std::size_t>(remainders[r].second)];
    counts.back() += spare - given;  // intervals >= 1: splits holds 0 and 1
    // Gauss-Legendre per interval; the last (towards the normal) Gauss-Radau
    // with a node at mu = 1 so that normal incidence and exit are on the grid
    // (Prahl's choice).
    for (int i = 0; i < intervals; ++i) {
        std::vector<double> x;
        std::vector<double> w;
        const double a = splits[static_cast<std::size_t>(i)];
        const double b = splits[static_cast<std::size_t>(i) + 1];
        if (i + 1 == intervals)
            layered::gaussRadauRight(counts[static_cast<std::size_t>(i)], a, b, x, w);
        else
            layered::gaussLegendre(counts[static_cast<std::size_t>(i)], a, b, x, w);
        m_mu_ref.insert(m_mu_ref.end(), x.begin(), x.end());
        m_weight_ref.insert(m_weight_ref.end(), w.begin(), w.end());
        m_interval.insert(m_interval.end(), x.size(), i);
        m_interval_low.push_back(a);
    }
}

double StackQuadrature::invariant(int k) const {
    const double mu = m_mu_ref[static_cast<std::size_t>(k)];
    return m_n_ref * std::sqrt(std::max(0.0, 1.0 - mu * mu));
}

MediumNodes StackQuadrature::medium(double index) const {
    MediumNodes m;
    m.index = index;
    const double scale = (m_n_ref / index) * (m_n_ref / index);  // (n_ref / n)^2
    for (int k = 0; k < size(); ++k) {
        const double s = invariant(k) / index;  // sin(theta) in this medium
        if (s >= 1.0 - 1e-12) continue;         // evanescent here
        const double mu = std::sqrt(1.0 - s * s);
        const double c =
            scale * 2.0 * m_mu_ref[static_cast<std::size_t>(k)] * m_weight_ref[static_cast<std::size_t>(k)];
        m.node.push_back(k);
        m.quadrature.mu.push_back(mu);
        m.quadrature.weight.push_back(c / (2.0 * mu));  // flux weight c = 2 mu w is what is conserved
    }
    m.quadrature.collimated = static_cast<int>(m.node.size()) - 1;
    return m;
}

}  // namespace paintlab::fast
