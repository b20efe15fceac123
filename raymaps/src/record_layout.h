#pragma once
// Byte layout of one paint record (docs/RAYMAPS.md, "What a paint pixel
// stores"), little-endian, no padding, read with memcpy:
//
//   offset  size        field
//   0       u32         pixel index in the image (row-major)
//   4       2 x u16     world shading normal, octahedral
//   8       2 x u16     world view direction (towards the eye), octahedral
//   12      3 x f32     world position (point lights need the distance)
//   24      half        footprint: pixel width at the hit (scene units)
//   26      3 x half    weight = coverage x throughput, RGB
//   32      3 x f32     mirror radiance (float: a sun's disk exceeds half's range)
//   44      J x 3 half  l^0_j, RGB
//   ..      J x (M_L-1) x 3 x i8   l^m_j / l^0_j x 127 (|l^m| <= l^0)
//   ..      K x u8      visibility of each explicit light x 255

#include "sampling.h"

#include <Eigen/Core>
#include <Imath/half.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace paintlab::raymaps {

struct RecordLayout {
    int cells = 4;
    int orders = 4;
    int lights = 0;
    static constexpr std::size_t kPixel = 0;
    static constexpr std::size_t kNormal = 4;
    static constexpr std::size_t kView = 8;
    static constexpr std::size_t kPosition = 12;
    static constexpr std::size_t kFootprint = 24;
    static constexpr std::size_t kWeight = 26;
    static constexpr std::size_t kMirror = 32;
    static constexpr std::size_t kMoments0 = 44;
    std::size_t momentsM() const { return kMoments0 + 6 * static_cast<std::size_t>(cells); }
    std::size_t visibility() const {
        return momentsM() + 3 * static_cast<std::size_t>(cells) * static_cast<std::size_t>(orders - 1);
    }
    std::size_t bytes() const { return visibility() + static_cast<std::size_t>(lights); }
};

// Reading a record's fields (records are unaligned bytes: memcpy, never a cast).
template <typename T> T recordField(const std::byte* at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

inline float recordHalf(const std::byte* at) {
    Imath::half h;
    h.setBits(recordField<std::uint16_t>(at));
    return static_cast<float>(h);
}

// An octahedral-encoded unit vector (the normal or the view direction).
inline Eigen::Vector3d recordDirection(const std::byte* at) {
    return decodeOctahedral(recordField<std::uint16_t>(at), recordField<std::uint16_t>(at + 2))
        .cast<double>();
}

}  // namespace paintlab::raymaps
