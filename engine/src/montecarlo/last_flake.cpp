#include "last_flake.h"

#include "flake_polygon.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

LastFlakeLaw lastFlakeLaw(const std::vector<FlakeGeometry>& kinds, double top_um, double bottom_um,
                          int polygon_sides) {
    LastFlakeLaw law;
    law.top_um = top_um;
    law.bottom_um = bottom_um;
    law.circumradius_factor = flakeCircumradiusFactor(polygon_sides);
    for (const FlakeGeometry& g : kinds) {
        LastFlakeLaw::Kind kind;
        kind.geometry = g;
        kind.mean_area_um2 = DiameterLaw(g).meanAreaUm2();
        if (g.profile != nullptr && g.profile->meanWeight() > 0.0)
            kind.profile_mean = g.profile->meanWeight();
        law.kinds.push_back(kind);
    }
    return law;
}

VirtualFlake drawVirtualFlake(const LastFlakeLaw& law, std::size_t kind, const Vec3& h, double depth,
                              PathRng& rng) {
    const LastFlakeLaw::Kind& k = law.kinds[kind];
    VirtualFlake flake;
    const double d = DiameterLaw(k.geometry).sample(rng);
    if (!(d > 0.0) || !(k.mean_area_um2 > 0.0)) return flake;
    const double area = 0.25 * std::numbers::pi * d * d;
    flake.radius_um = 0.5 * d;
    // The point uniform on the disk of the flake's area, about the centre, in the flake's plane.
    Vec3 b1;
    Vec3 b2;
    orthonormalBasis(h, b1, b2);
    // By rejection from the square (no trigonometry; pi / 4 of the pairs are kept).
    double a = 0.0;
    double b = 0.0;
    do {
        a = 2.0 * rng.uniform() - 1.0;
        b = 2.0 * rng.uniform() - 1.0;
    } while (!(a * a + b * b < 1.0));
    const double c = flake.radius_um * a;
    const double s = flake.radius_um * b;
    const Vec3 offset{c * b1.x + s * b2.x, c * b1.y + s * b2.y, c * b1.z + s * b2.z};
    flake.centre_offset = {-offset.x, -offset.y, -offset.z};
    // The centre's depth (z is up) and its density as the tile draws it: the
    // relative depth z from the profile, then [lo, 1 - lo] when the flake fits.
    const double height = law.bottom_um - law.top_um;
    if (!(height > 0.0)) return flake;
    const double centre_depth = depth + offset.z;
    const double half_height =
        flake.radius_um * law.circumradius_factor * std::sqrt(std::max(0.0, 1.0 - h.z * h.z));
    const double lo = height > 2.0 * half_height ? half_height : 0.0;
    const double span = height - 2.0 * lo;
    const double z = (centre_depth - law.top_um - lo) / span;
    if (!(z >= 0.0) || !(z <= 1.0)) return flake;
    const double profile =
        k.geometry.profile != nullptr ? k.geometry.profile->weightAt(z) / k.profile_mean : 1.0;
    // Surface density relative to the mean A: height x p(centre depth) x A(d) / E[A].
    flake.rho = height / span * profile * area / k.mean_area_um2;
    return flake;
}

}  // namespace paintlab::mc
