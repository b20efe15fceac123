#pragma once
// The shape of the full model's explicit flakes (flake_tile.cpp): regular
// polygons of the disk's area. The fast model's validity rule
// (model_validity.cpp) needs the same size for how far a tilted flake
// reaches, so both read it here.

#include <cmath>
#include <numbers>

namespace paintlab::mc {

inline constexpr int kFlakePolygonSides = 16;

// Circumradius of the regular kFlakePolygonSides-gon with the disk's area,
// over the disk's radius: sqrt(2 pi / (n sin(2 pi / n))), 1.0130 for n = 16.
inline double flakeCircumradiusFactor() {
    constexpr double n = kFlakePolygonSides;
    return std::sqrt(2.0 * std::numbers::pi / (n * std::sin(2.0 * std::numbers::pi / n)));
}

}  // namespace paintlab::mc
