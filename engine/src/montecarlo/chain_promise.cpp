#include "chain_promise.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kPi = std::numbers::pi;

// Normals of the flake that turns an upward branch down: a fixed midpoint
// grid of the orientation law's inverse CDF (FlakeOrientation::sample),
// 8 tilt quantiles x 8 azimuths. Coarse on purpose: the promise only steers
// the roulette.
constexpr int kTiltSamples = 8;
constexpr int kAzimuthSamples = 8;

std::vector<Vec3> orientationSamples(double kappa) {
    std::vector<Vec3> normals;
    normals.reserve(static_cast<std::size_t>(kTiltSamples) * kAzimuthSamples);
    for (int i = 0; i < kTiltSamples; ++i) {
        const double u1 = (i + 0.5) / kTiltSamples;
        // P(1 - mu <= t) = (1 - e^(-kappa t)) / (1 - e^(-kappa)) = u1.
        const double t =
            kappa > 1e-6 ? std::clamp(-std::log1p(u1 * std::expm1(-kappa)) / kappa, 0.0, 1.0) : u1;
        const double mu = 1.0 - t;
        const double sin_alpha = std::sqrt(std::max(0.0, t * (2.0 - t)));
        for (int a = 0; a < kAzimuthSamples; ++a) {
            const double phi = 2.0 * kPi * (a + 0.5) / kAzimuthSamples;
            normals.push_back({sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), mu});
        }
    }
    return normals;
}

// D(h) / D(1) for the half-vector h that mirrors `down` (unit, downward) into `up` (unit, upward).
double peakRelativeD(const Vec3& down, const Vec3& up, double kappa) {
    const Vec3 h{up.x - down.x, up.y - down.y, up.z - down.z};
    const double length = std::sqrt(dot(h, h));
    if (!(length > 0.0)) return 0.0;
    return std::exp(-kappa * (1.0 - std::abs(h.z) / length));
}

// The direction at the centre of cell (ix, iy) of a bins x bins grid of
// lateral components (outside the unit disk: its nearest point on the rim).
Vec3 cellDirection(int ix, int iy, int bins, bool up) {
    double x = -1.0 + (ix + 0.5) * 2.0 / bins;
    double y = -1.0 + (iy + 0.5) * 2.0 / bins;
    const double r = std::hypot(x, y);
    if (r > 1.0) {
        x /= r;
        y /= r;
    }
    const double z = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
    return {x, y, up ? z : -z};
}

// Upward d: the flakes it meets (|d.n| their share) turn it down, then D at the next flake.
double upwardPromise(const Vec3& d, const Vec3& cone, const std::vector<Vec3>& normals, double kappa) {
    double sum = 0.0;
    double projected = 0.0;
    for (const Vec3& n : normals) {
        const double dn = dot(d, n);
        projected += std::abs(dn);
        const Vec3 reflected{d.x - 2.0 * dn * n.x, d.y - 2.0 * dn * n.y, d.z - 2.0 * dn * n.z};
        if (reflected.z < 0.0) sum += std::abs(dn) * peakRelativeD(reflected, cone, kappa);
    }
    return projected > 0.0 ? sum / projected : 0.0;
}

constexpr std::size_t kDownCells =
    static_cast<std::size_t>(ChainPromise::kDownBins) * ChainPromise::kDownBins;
constexpr std::size_t kUpCells = static_cast<std::size_t>(ChainPromise::kUpBins) * ChainPromise::kUpBins;

}  // namespace

ChainPromise::ChainPromise(std::span<const Vec3> cones_in_film, double kappa, double reflectance) {
    const std::vector<Vec3> normals = orientationSamples(kappa);
    m_per_cone.assign(cones_in_film.size(), std::vector<float>(kDownCells + kUpCells, 0.0F));
    tbb::parallel_for(std::size_t{0}, kDownCells + kUpCells, [&](std::size_t c) {
        const bool up = c >= kDownCells;
        const int bins = up ? kUpBins : kDownBins;
        const auto i = static_cast<int>(up ? c - kDownCells : c);
        const Vec3 d = cellDirection(i % bins, i / bins, bins, up);
        for (std::size_t k = 0; k < cones_in_film.size(); ++k) {
            const double value = up ? reflectance * upwardPromise(d, cones_in_film[k], normals, kappa)
                                    : peakRelativeD(d, cones_in_film[k], kappa);
            m_per_cone[k][c] = static_cast<float>(value);
        }
    });
}

void ChainPromise::setConeWeights(std::span<const double> weights) {
    if (weights.size() != m_per_cone.size() || m_per_cone.empty()) {
        m_combined.clear();
        return;
    }
    m_combined.assign(m_per_cone.front().size(), 0.0F);
    for (std::size_t k = 0; k < weights.size(); ++k)
        for (std::size_t c = 0; c < m_combined.size(); ++c)
            m_combined[c] += static_cast<float>(weights[k]) * m_per_cone[k][c];
}

double ChainPromise::at(const Vec3& d, double bx, double by) const {
    const bool up = d.z > 0.0;
    const int bins = up ? kUpBins : kDownBins;
    const double half = 0.5 * bins;
    const int ix = std::clamp(static_cast<int>((d.x * bx + d.y * by + 1.0) * half), 0, bins - 1);
    const int iy = std::clamp(static_cast<int>((d.y * bx - d.x * by + 1.0) * half), 0, bins - 1);
    const std::size_t cell = (up ? kDownCells : 0) + static_cast<std::size_t>(iy * bins + ix);
    return static_cast<double>(m_combined[cell]);
}

}  // namespace paintlab::mc
