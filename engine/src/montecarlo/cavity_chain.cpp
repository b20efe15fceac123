#include "cavity_chain.h"

#include <cmath>
#include <numbers>

namespace paintlab::mc {

namespace {

Vec3 normalized(const Vec3& v) {
    const double len = std::sqrt(dot(v, v));
    return {v.x / len, v.y / len, v.z / len};
}

}  // namespace

Vec3 cavityExit(const Vec3& d, const Vec3& n, const Vec3& h, int k) {
    Vec3 v = d;
    for (int i = 0; i < k; ++i) v = mirrored(mirrored(v, h), n);
    return v;
}

int cavityNormals(const Vec3& d, const Vec3& n, const Vec3& target, int k, CavityNormals& out) {
    if (k < 1 || k > static_cast<int>(out.size())) return 0;
    // The axis e: normal to n (the turn of M_n M_h is about n x h) and to
    // target - d (a turn about e keeps the component along e).
    const Vec3 axis = cross(n, {target.x - d.x, target.y - d.y, target.z - d.z});
    const double axis_len = std::sqrt(dot(axis, axis));
    if (!(axis_len > 1e-9)) return 0;
    const Vec3 e{axis.x / axis_len, axis.y / axis_len, axis.z / axis_len};
    const double de = dot(d, e);
    const double te = dot(target, e);
    const Vec3 d_p{d.x - de * e.x, d.y - de * e.y, d.z - de * e.z};
    const Vec3 t_p{target.x - te * e.x, target.y - te * e.y, target.z - te * e.z};
    const double phi = std::atan2(dot(e, cross(d_p, t_p)), dot(d_p, t_p));
    const Vec3 en = cross(e, n);
    // h = n turned about e by theta makes M_n M_h the turn about e by
    // -2 theta, so its k-th power takes d to target for theta =
    // -(phi + 2 pi i) / (2k); h and -h are one flake (theta modulo pi): i < k.
    int count = 0;
    for (int i = 0; i < k; ++i) {
        const double theta = -(phi + 2.0 * std::numbers::pi * i) / (2.0 * k);
        const double c = std::cos(theta);
        const double s = std::sin(theta);
        Vec3 h{c * n.x + s * en.x, c * n.y + s * en.y, c * n.z + s * en.z};
        if (h.z < 0.0) h = {-h.x, -h.y, -h.z};
        // J = dOmega_exit / dOmega_h: 4 |d.h| for one round trip (M_n keeps
        // solid angles; the mirror M_h doubles angles), else by finite
        // differences on the tangent plane (eps 1e-6 rad: truncation ~1e-6
        // relative, rounding ~1e-10).
        if (k == 1) {
            out[static_cast<std::size_t>(count++)] = {h, 4.0 * std::abs(dot(d, h))};
            continue;
        }
        constexpr double eps = 1e-6;
        const Vec3 exit = cavityExit(d, n, h, k);
        Vec3 t1;
        Vec3 t2;
        orthonormalBasis(h, t1, t2);
        const Vec3 e1 =
            cavityExit(d, n, normalized({h.x + eps * t1.x, h.y + eps * t1.y, h.z + eps * t1.z}), k);
        const Vec3 e2 =
            cavityExit(d, n, normalized({h.x + eps * t2.x, h.y + eps * t2.y, h.z + eps * t2.z}), k);
        const Vec3 area = cross({e1.x - exit.x, e1.y - exit.y, e1.z - exit.z},
                                {e2.x - exit.x, e2.y - exit.y, e2.z - exit.z});
        const double jacobian = std::sqrt(dot(area, area)) / (eps * eps);
        if (!(jacobian > 0.0)) continue;
        out[static_cast<std::size_t>(count++)] = {h, jacobian};
    }
    return count;
}

int cavityChainLayer(std::span<const ChainChange> latest_first) {
    const auto size = static_cast<int>(latest_first.size());
    int ic = 0;
    while (ic < size && !latest_first[static_cast<std::size_t>(ic)].first_meeting) ++ic;
    if (ic == 0 || ic >= size) return -1;  // no suffix after c, or no c in the ring
    const std::int64_t c = latest_first[static_cast<std::size_t>(ic)].flake_id;
    if (c < 0) return -1;
    const std::int64_t layer = c % 64;
    // x_i = latest_first[ic + i] (i >= 1); suffix entry s (1-based, in time order) = latest_first[ic - s].
    const auto x = [&](int i) {
        const int at = ic + i;
        if (at >= size) return std::int64_t{-1};
        const std::int64_t id = latest_first[static_cast<std::size_t>(at)].flake_id;
        return id >= 0 && id % 64 == layer ? id : std::int64_t{-1};
    };
    const auto s = [&](int k) { return latest_first[static_cast<std::size_t>(ic - k)].flake_id; };
    const int length = ic;
    for (int j = 0; j <= kMaxCavityRoundTrips; ++j) {
        const int m = length - 2 * j;
        if (m < 1 || m > kMaxCavityRetrace) continue;
        const std::int64_t x1 = x(1);
        if (x1 < 0) continue;
        bool match = true;
        for (int t = 0; t < j && match; ++t) match = s(2 * t + 1) == x1 && s(2 * t + 2) == c;
        match = match && s(2 * j + 1) == x1;
        for (int i = 2; i <= m && match; ++i) match = x(i) >= 0 && s(2 * j + i) == x(i);
        if (match) return static_cast<int>(layer);
    }
    return -1;
}

}  // namespace paintlab::mc
