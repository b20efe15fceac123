#include "environment_moments.h"

#include <algorithm>

namespace paintlab::raymaps {

EnvironmentMoments::EnvironmentMoments(const EnvironmentMap& environment, int points) {
    const auto n = static_cast<std::size_t>(std::max(points, 1));
    m_direction.reserve(n);
    m_weight.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const EnvironmentMap::Sample s =
            environment.sample((static_cast<double>(i) + 0.5) / static_cast<double>(n),
                               radicalInverse2(static_cast<std::uint32_t>(i)));
        if (!(s.pdf_sr > 0.0)) continue;
        m_direction.push_back(s.direction);
        m_weight.emplace_back(s.radiance / (static_cast<double>(n) * s.pdf_sr));
    }
}

void EnvironmentMoments::add(const Frame& frame, int cells, int orders, std::vector<Rgb3>& moments) const {
    const auto order_count = static_cast<std::size_t>(orders);
    for (std::size_t k = 0; k < m_direction.size(); ++k) {
        const Vec3 w = frame.toLocal(m_direction[k]);
        const double mu = w.z();
        if (!(mu > 0.0)) continue;
        const auto j = static_cast<std::size_t>(std::min(cells - 1, static_cast<int>(mu * mu * cells)));
        const double sin_theta = std::hypot(w.x(), w.y());
        // cos(m phi) by the Chebyshev recurrence from cos(phi).
        const double c1 = sin_theta > 1e-12 ? w.x() / sin_theta : 1.0;
        const Rgb3 base = m_weight[k] * mu;
        double previous = 1.0;
        double current = c1;
        moments[j * order_count] += base;
        for (std::size_t m = 1; m < order_count; ++m) {
            moments[j * order_count + m] += base * current;
            const double next = 2.0 * c1 * current - previous;
            previous = current;
            current = next;
        }
    }
}

}  // namespace paintlab::raymaps
