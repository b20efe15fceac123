#include "chain_promise.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kPi = std::numbers::pi;

// Normals of the flake that turns an upward branch down: a fixed midpoint
// grid of the orientation law's inverse CDF (FlakeOrientation::sample),
// 16 tilt quantiles x 8 azimuths. Coarse on purpose: the promise only steers
// the roulette.
constexpr int kTiltSamples = 16;
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

}  // namespace

ChainPromise::ChainPromise(std::span<const Vec3> cones_in_film, double kappa, double reflectance) {
    const std::vector<Vec3> normals = orientationSamples(kappa);
    const std::size_t cells = static_cast<std::size_t>(kCosBins) * kAzimuthBins;
    m_per_cone.assign(cones_in_film.size(), std::vector<float>(cells, 0.0F));
    for (int iz = 0; iz < kCosBins; ++iz) {
        const double z = -1.0 + (iz + 0.5) * 2.0 / kCosBins;
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int ia = 0; ia < kAzimuthBins; ++ia) {
            const double phi = -kPi + (ia + 0.5) * 2.0 * kPi / kAzimuthBins;
            const Vec3 d{s * std::cos(phi), s * std::sin(phi), z};
            const std::size_t c = static_cast<std::size_t>(iz) * kAzimuthBins + static_cast<std::size_t>(ia);
            for (std::size_t k = 0; k < cones_in_film.size(); ++k) {
                const Vec3& u = cones_in_film[k];
                double value = 0.0;
                if (z < 0.0) {
                    value = peakRelativeD(d, u, kappa);
                } else {
                    // Upward: the flakes it meets, |d.n| their share, turn it down, then D at C.
                    double sum = 0.0;
                    double projected = 0.0;
                    for (const Vec3& n : normals) {
                        const double dn = dot(d, n);
                        projected += std::abs(dn);
                        const Vec3 r{d.x - 2.0 * dn * n.x, d.y - 2.0 * dn * n.y, d.z - 2.0 * dn * n.z};
                        if (r.z < 0.0) sum += std::abs(dn) * peakRelativeD(r, u, kappa);
                    }
                    value = projected > 0.0 ? reflectance * sum / projected : 0.0;
                }
                m_per_cone[k][c] = static_cast<float>(value);
            }
        }
    }
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

std::size_t ChainPromise::cell(const Vec3& d, double bx, double by) const {
    const int iz = std::clamp(static_cast<int>((d.z + 1.0) * 0.5 * kCosBins), 0, kCosBins - 1);
    const double phi = std::atan2(d.y * bx - d.x * by, d.x * bx + d.y * by);
    const int ia =
        std::clamp(static_cast<int>((phi + kPi) / (2.0 * kPi) * kAzimuthBins), 0, kAzimuthBins - 1);
    return static_cast<std::size_t>(iz) * kAzimuthBins + static_cast<std::size_t>(ia);
}

double ChainPromise::at(const Vec3& d, double bx, double by) const {
    return static_cast<double>(m_combined[cell(d, bx, by)]);
}

}  // namespace paintlab::mc
