#include "paintlab/engine/montecarlo/cone_average.h"

#include "mc_stack.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

std::vector<double> coneAverage(const LayeredBrdf& fast, const Direction& wi, const Direction& axis,
                                double cone_deg) {
    if (!(cone_deg > 0.0)) return fast.eval(wi, axis);
    const double alpha = cone_deg * std::numbers::pi / 180.0;
    Vec3 b1;
    Vec3 b2;
    orthonormalBasis({axis.x, axis.y, axis.z}, b1, b2);
    std::vector<double> sum(fast.wavelengthsNm().size(), 0.0);
    double weight_sum = 0.0;
    const int n_beta = 8;
    const int n_psi = 24;
    for (int i = 0; i < n_beta; ++i) {
        const double beta = (i + 0.5) / n_beta * alpha;
        for (int j = 0; j < n_psi; ++j) {
            const double psi = (j + 0.5) / n_psi * 2.0 * std::numbers::pi;
            const double s = std::sin(beta) * std::cos(psi);
            const double t = std::sin(beta) * std::sin(psi);
            const Direction w{std::cos(beta) * axis.x + s * b1.x + t * b2.x,
                              std::cos(beta) * axis.y + s * b1.y + t * b2.y,
                              std::cos(beta) * axis.z + s * b1.z + t * b2.z};
            const double weight = std::sin(beta) * std::max(w.z, 0.0);
            const auto f = fast.eval(wi, w);
            for (std::size_t k = 0; k < f.size(); ++k) sum[k] += weight * f[k];
            weight_sum += weight;
        }
    }
    for (auto& v : sum) v /= weight_sum;
    return sum;
}

}  // namespace paintlab::mc
