#pragma once
// The relight tables' grids (relight.h, RelightTables), shared by the tables,
// the decoding of the records (relight_input.cpp) and the kernel.

#include "sampling.h"

#include "paintlab/raymaps/relight.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace paintlab::raymaps::grid {

constexpr int kN = RelightTables::kMuNodes;
constexpr int kC = RelightTables::kPhiNodes;
constexpr int kF = RelightTables::kFineNodes;
// Float offsets between neighbouring nodes of the light table (4 floats a node).
constexpr std::size_t kStepPhi = 4;
constexpr std::size_t kStepI = 4 * static_cast<std::size_t>(kC);
constexpr std::size_t kStepO = 4 * static_cast<std::size_t>(kC) * static_cast<std::size_t>(kN);

// The grid is uniform in the polar angle: the odd Fourier orders of f go as
// sin(theta) near the normal, which no grid in mu = cos(theta) follows. At
// the horizon eval() is 0 by definition, so that node takes mu = 0.002.
inline double muNode(int k) { return std::max(0.002, std::cos(0.5 * kPi * k / (kN - 1))); }

// Continuous index on the theta grid of a cosine, clamped to its ends:
// node k and fraction t towards node k + 1.
inline void muIndex(double mu, int& k, float& t) {
    const double x = std::clamp(std::acos(std::clamp(mu, -1.0, 1.0)) * ((kN - 1) / (0.5 * kPi)), 0.0,
                                static_cast<double>(kN - 1) - 1e-4);
    k = static_cast<int>(x);
    t = static_cast<float>(x - k);
}

// Continuous index on the azimuth grid (dphi = pi p / (kC - 1)) of cos(dphi).
inline void phiIndex(double cos_dphi, int& p, float& t) {
    const double x = std::clamp(std::acos(std::clamp(cos_dphi, -1.0, 1.0)) * ((kC - 1) / kPi), 0.0,
                                static_cast<double>(kC - 1) - 1e-4);
    p = static_cast<int>(x);
    t = static_cast<float>(x - p);
}

// The nearest fine-grid node of a position (k, t) on the coarse theta grid.
inline std::size_t fineIndex(int k, float t) {
    constexpr double kRatio = static_cast<double>(kF - 1) / static_cast<double>(kN - 1);
    return static_cast<std::size_t>(std::lround((k + static_cast<double>(t)) * kRatio));
}

// Float offset of light-table node (o, i, p).
inline std::size_t lightNode(int o, int i, int p) {
    return static_cast<std::size_t>(o) * kStepO + static_cast<std::size_t>(i) * kStepI +
           static_cast<std::size_t>(p) * kStepPhi;
}

// Trilinear interpolation in the light table from corner `at` (lightNode)
// with fractions t_o, t_i, t_phi: 4 lanes (RGB and the zero pad), no branch.
inline void trilinear(const float* at, float t_o, float t_i, float t_phi, float out[4]) {
    for (std::size_t c = 0; c < 4; ++c) {
        const float* e = at + c;
        const float a = e[0] + t_phi * (e[kStepPhi] - e[0]);
        const float b = e[kStepI] + t_phi * (e[kStepI + kStepPhi] - e[kStepI]);
        const float d = e[kStepO] + t_phi * (e[kStepO + kStepPhi] - e[kStepO]);
        const float g = e[kStepO + kStepI] + t_phi * (e[kStepO + kStepI + kStepPhi] - e[kStepO + kStepI]);
        const float lo = a + t_i * (b - a);
        const float hi = d + t_i * (g - d);
        out[c] = lo + t_o * (hi - lo);
    }
}

}  // namespace paintlab::raymaps::grid
