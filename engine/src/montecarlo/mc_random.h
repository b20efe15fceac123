#pragma once
// Per-path random numbers: xoshiro256** (Blackman & Vigna 2018) seeded by
// SplitMix64 from a key that names the path (seed, band, incidence, path
// index), so every path's numbers are fixed whatever thread runs it.

#include <cstdint>

namespace paintlab::mc {

inline std::uint64_t splitMix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31U);
}

class PathRng {
public:
    PathRng(std::uint64_t seed, std::uint64_t band, std::uint64_t incidence, std::uint64_t path) {
        std::uint64_t key = seed;
        key = splitMix64(key) ^ band;
        key = splitMix64(key) ^ incidence;
        key = splitMix64(key) ^ path;
        for (auto& s : m_s) s = splitMix64(key);
    }

    std::uint64_t next() {
        const std::uint64_t result = rotl(m_s[1] * 5U, 7) * 9U;
        const std::uint64_t t = m_s[1] << 17U;
        m_s[2] ^= m_s[0];
        m_s[3] ^= m_s[1];
        m_s[1] ^= m_s[2];
        m_s[0] ^= m_s[3];
        m_s[2] ^= t;
        m_s[3] = rotl(m_s[3], 45);
        return result;
    }

    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11U) * 0x1.0p-53; }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) {
        return (x << static_cast<unsigned>(k)) | (x >> static_cast<unsigned>(64 - k));
    }
    std::uint64_t m_s[4]{};
};

}  // namespace paintlab::mc
