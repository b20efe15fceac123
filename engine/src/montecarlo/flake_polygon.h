#pragma once
// The shape of the full model's explicit flakes (flake_tile.cpp): regular
// polygons of the disk's area (McSettings::flake_polygon_sides; 0: exact
// disks). The fast model's validity rule (model_validity.cpp) needs the
// default's size for how far a tilted flake reaches, so both read it here.

#include <cmath>
#include <numbers>

namespace paintlab::mc {

inline constexpr int kFlakePolygonSides = 16;

// Circumradius of the regular n-gon with the disk's area, over the disk's
// radius: sqrt(2 pi / (n sin(2 pi / n))), 1.0130 for n = 16; 1 for the disk (n = 0).
inline double flakeCircumradiusFactor(int sides = kFlakePolygonSides) {
    if (sides == 0) return 1.0;
    const double n = sides;
    return std::sqrt(2.0 * std::numbers::pi / (n * std::sin(2.0 * std::numbers::pi / n)));
}

}  // namespace paintlab::mc
