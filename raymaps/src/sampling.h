#pragma once
// Small sampling helpers of the ray-map precompute: a counter-based random
// stream per (pixel, sample) so that images do not depend on the thread
// count, orthonormal frames, octahedral direction coding, hemisphere and cone
// sampling.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace paintlab::raymaps {

using Vec3 = Eigen::Vector3d;

constexpr double kPi = std::numbers::pi;

// SplitMix64 finaliser (Steele, Lea, Flood 2014): a good 64-bit mixer.
constexpr std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27U)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31U);
}

// PCG32 (O'Neill 2014) seeded from (seed, pixel, sample): every pixel's
// numbers depend on nothing else, so the output is the same for any thread
// count or scheduling.
class Rng {
public:
    Rng(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
        : m_state(mix64(seed ^ mix64(pixel ^ mix64(sample)))),
          m_inc((mix64(pixel + 0x51ED27ULL) << 1U) | 1U) {
        next();
    }
    std::uint32_t next() {
        const std::uint64_t old = m_state;
        m_state = old * 6364136223846793005ULL + m_inc;
        const auto xorshifted = static_cast<std::uint32_t>(((old >> 18U) ^ old) >> 27U);
        const auto rot = static_cast<std::uint32_t>(old >> 59U);
        return (xorshifted >> rot) | (xorshifted << ((32U - rot) & 31U));
    }
    // Uniform in [0, 1).
    double uniform() { return static_cast<double>(next()) * 0x1p-32; }

private:
    std::uint64_t m_state;
    std::uint64_t m_inc;
};

// An orthonormal frame with z = n; x along `tangent_hint` projected on the
// tangent plane when it is usable (the view's azimuth for the paint).
struct Frame {
    Vec3 x, y, z;
    static Frame fromNormal(const Vec3& n) {
        // Duff et al. 2017, "Building an orthonormal basis, revisited".
        const double sign = std::copysign(1.0, n.z());
        const double a = -1.0 / (sign + n.z());
        const double b = n.x() * n.y() * a;
        return {Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x()),
                Vec3(b, sign + n.y() * n.y() * a, -n.y()), n};
    }
    static Frame fromNormalAndTangent(const Vec3& n, const Vec3& tangent_hint) {
        const Vec3 t = tangent_hint - tangent_hint.dot(n) * n;
        const double len = t.norm();
        if (!(len > 1e-9)) return fromNormal(n);
        const Vec3 x = t / len;
        return {x, n.cross(x), n};
    }
    Vec3 toWorld(const Vec3& local) const { return local.x() * x + local.y() * y + local.z() * z; }
    Vec3 toLocal(const Vec3& world) const { return {world.dot(x), world.dot(y), world.dot(z)}; }
};

// Octahedral mapping of unit vectors to two 16-bit numbers (Cigolle et al.
// 2014, "A survey of efficient representations for independent unit
// vectors"); the angular error is below 1e-4 rad.
inline void encodeOctahedral(const Vec3& d, std::uint16_t out[2]) {
    const double l1 = std::abs(d.x()) + std::abs(d.y()) + std::abs(d.z());
    double u = d.x() / l1;
    double v = d.y() / l1;
    if (d.z() < 0.0) {
        const double pu = (1.0 - std::abs(v)) * std::copysign(1.0, u);
        const double pv = (1.0 - std::abs(u)) * std::copysign(1.0, v);
        u = pu;
        v = pv;
    }
    const auto quantise = [](double x) {
        return static_cast<std::uint16_t>(std::lround(std::clamp((x + 1.0) * 0.5, 0.0, 1.0) * 65535.0));
    };
    out[0] = quantise(u);
    out[1] = quantise(v);
}

inline Eigen::Vector3f decodeOctahedral(std::uint16_t qu, std::uint16_t qv) {
    const float u = static_cast<float>(qu) * (2.0F / 65535.0F) - 1.0F;
    const float v = static_cast<float>(qv) * (2.0F / 65535.0F) - 1.0F;
    Eigen::Vector3f d(u, v, 1.0F - std::abs(u) - std::abs(v));
    if (d.z() < 0.0F) {
        const float x = (1.0F - std::abs(v)) * std::copysign(1.0F, u);
        const float y = (1.0F - std::abs(u)) * std::copysign(1.0F, v);
        d.x() = x;
        d.y() = y;
    }
    return d.normalized();
}

// Cosine-weighted hemisphere direction (local, z up); pdf = cos / pi.
inline Vec3 sampleCosine(double u1, double u2) {
    const double r = std::sqrt(u1);
    const double phi = 2.0 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}

// Uniform direction in the cone of half-angle acos(cos_max) about z.
inline Vec3 sampleCone(double u1, double u2, double cos_max) {
    const double c = 1.0 - u1 * (1.0 - cos_max);
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = 2.0 * kPi * u2;
    return {s * std::cos(phi), s * std::sin(phi), c};
}

inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return 2.0 * wo.dot(n) * n - wo; }

// Van der Corput radical inverse in base 2 of i, its bits XOR-scrambled:
// (i / n, radicalInverse2(i)) for i < n = 2^k is a Hammersley set, one point
// in every elementary interval of area 1 / n; a random `scramble` keeps that
// and makes each point uniform (random digit scrambling, Owen 1995).
inline double radicalInverse2(std::uint32_t i, std::uint32_t scramble = 0) {
    i = (i << 16U) | (i >> 16U);
    i = ((i & 0x55555555U) << 1U) | ((i & 0xAAAAAAAAU) >> 1U);
    i = ((i & 0x33333333U) << 2U) | ((i & 0xCCCCCCCCU) >> 2U);
    i = ((i & 0x0F0F0F0FU) << 4U) | ((i & 0xF0F0F0F0U) >> 4U);
    i = ((i & 0x00FF00FFU) << 8U) | ((i & 0xFF00FF00U) >> 8U);
    return static_cast<double>(i ^ scramble) * 0x1p-32;
}

}  // namespace paintlab::raymaps
