#include "cavity_chain.h"

#include <array>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

Vec3 cavityExit(const Vec3& d, const Vec3& n, const Vec3& h, int k) {
    Vec3 v = d;
    for (int i = 0; i < k; ++i) v = mirrored(mirrored(v, h), n);
    return v;
}

double cavityJacobian(const Vec3& n, const Vec3& e, double theta, double cos_theta, double sin_theta, int k,
                      const Vec3& u) {
    // h = Rot(phi) n for phi = theta e in the plane normal to n (dOmega_h =
    // |sin theta / theta| dA_phi), u = Rot(omega) d for omega = -2 k phi
    // (dA_omega = 4 k^2 dA_phi), and du = (J_l(omega) delta) x u with J_l
    // SO(3)'s left Jacobian, so dOmega_u / dA_omega = |u . (J_l p_1 x J_l p_2)|
    // for an orthonormal basis p_1, p_2 of that plane.
    const Vec3 omega{-2.0 * k * theta * e.x, -2.0 * k * theta * e.y, -2.0 * k * theta * e.z};
    const double a = 2.0 * k * std::abs(theta);
    // cos and sin of 2 k theta as powers of e^(2 i theta) (no more calls to the library's trigonometry).
    const double c2 = cos_theta * cos_theta - sin_theta * sin_theta;
    const double s2 = 2.0 * cos_theta * sin_theta;
    double cos_a = 1.0;
    double sin_a = 0.0;
    for (int i = 0; i < k; ++i) {
        const double c = cos_a * c2 - sin_a * s2;
        sin_a = sin_a * c2 + cos_a * s2;
        cos_a = c;
    }
    if (theta < 0.0) sin_a = -sin_a;  // a = 2 k |theta|
    // (1 - cos a) / a^2 and (a - sin a) / a^3, by their series near 0.
    const double f1 = a < 1e-4 ? 0.5 - a * a / 24.0 : (1.0 - cos_a) / (a * a);
    const double f2 = a < 1e-4 ? 1.0 / 6.0 - a * a / 120.0 : (a - sin_a) / (a * a * a);
    const auto leftJacobian = [&](const Vec3& p) {
        const Vec3 wp = cross(omega, p);
        const Vec3 wwp = cross(omega, wp);
        return Vec3{p.x + f1 * wp.x + f2 * wwp.x, p.y + f1 * wp.y + f2 * wwp.y, p.z + f1 * wp.z + f2 * wwp.z};
    };
    const double area = std::abs(dot(u, cross(leftJacobian(e), leftJacobian(cross(e, n)))));
    const double stretch = std::abs(theta) < 1e-8 ? 1.0 : std::abs(theta / sin_theta);
    return area * 4.0 * k * k * stretch;
}

bool cavityTurn(const Vec3& d, const Vec3& n, const Vec3& target, CavityTurn& out) {
    // The axis e: normal to n (the turn of M_n M_h is about n x h) and to
    // target - d (a turn about e keeps the component along e).
    const Vec3 axis = cross(n, {target.x - d.x, target.y - d.y, target.z - d.z});
    const double axis_len = std::sqrt(dot(axis, axis));
    if (!(axis_len > 1e-9)) return false;
    const Vec3 e{axis.x / axis_len, axis.y / axis_len, axis.z / axis_len};
    const double de = dot(d, e);
    const double te = dot(target, e);
    const Vec3 d_p{d.x - de * e.x, d.y - de * e.y, d.z - de * e.z};
    const Vec3 t_p{target.x - te * e.x, target.y - te * e.y, target.z - te * e.z};
    const double y = dot(e, cross(d_p, t_p));
    const double x = dot(d_p, t_p);
    out.e = e;
    out.en = cross(e, n);
    const double r = std::sqrt(x * x + y * y);
    out.cos_phi = r > 0.0 ? x / r : 1.0;
    out.sin_phi = r > 0.0 ? y / r : 0.0;
    return true;
}

namespace {

// cos and sin of a / 2 from those of a in (-pi, pi] (the half-angle
// formulas, each side where it does not cancel).
void halfAngle(double cos_a, double sin_a, double& cos_half, double& sin_half) {
    if (cos_a >= 0.0) {
        cos_half = std::sqrt(0.5 * (1.0 + cos_a));
        sin_half = sin_a / (2.0 * cos_half);
    } else {
        sin_half = std::copysign(std::sqrt(0.5 * (1.0 - cos_a)), sin_a);
        cos_half = std::abs(sin_a) / (2.0 * std::abs(sin_half));
    }
}

}  // namespace

int cavityNormals(const CavityTurn& turn, const Vec3& d, const Vec3& n, const Vec3& target, int k,
                  CavityNormals& out) {
    if (k < 1 || k > static_cast<int>(out.size())) return 0;
    // h = n turned about e by theta makes M_n M_h the turn about e by
    // -2 theta, so its k-th power takes d to target for theta_i =
    // -(phi + 2 pi i) / (2k); h and -h are one flake (theta modulo pi): i < k.
    // theta_0's cosine and sine by halving phi (k = 1, 2, 4: no library
    // trigonometry), the others by turning on in steps of -pi / k.
    const double phi = k > 1 ? turn.phi() : 0.0;  // the Jacobian's theta (k = 1: 4 |d.h|)
    double c = 1.0;
    double s = 0.0;
    if (k == 3) {
        c = std::cos(phi / 6.0);
        s = std::sin(phi / 6.0);
    } else {
        c = turn.cos_phi;
        s = turn.sin_phi;
        for (int halves = k == 1 ? 1 : (k == 2 ? 2 : 3); halves > 0; --halves) halfAngle(c, s, c, s);
    }
    s = -s;  // theta_0 = -phi / (2k)
    // cos and sin of pi / k, k = 1 .. 4.
    static_assert(kMaxCavityRoundTrips + 1 == 4, "the halvings and the steps cover k = 1 .. 4");
    constexpr std::array<double, 4> kStepCos{-1.0, 0.0, 0.5, 0.70710678118654752};
    constexpr std::array<double, 4> kStepSin{0.0, 1.0, 0.86602540378443865, 0.70710678118654752};
    const double step_cos = kStepCos[static_cast<std::size_t>(k - 1)];
    const double step_sin = kStepSin[static_cast<std::size_t>(k - 1)];
    int count = 0;
    for (int i = 0; i < k; ++i) {
        const double theta = -(phi + 2.0 * std::numbers::pi * i) / (2.0 * k);
        Vec3 h{c * n.x + s * turn.en.x, c * n.y + s * turn.en.y, c * n.z + s * turn.en.z};
        if (h.z < 0.0) h = {-h.x, -h.y, -h.z};
        // J = dOmega_exit / dOmega_h in closed form (cavityJacobian; at one
        // round trip the half vector's 4 |d.h|).
        const double jacobian =
            k == 1 ? 4.0 * std::abs(dot(d, h)) : cavityJacobian(n, turn.e, theta, c, s, k, target);
        if (jacobian > 0.0) out[static_cast<std::size_t>(count++)] = {h, jacobian};
        const double next_c = c * step_cos + s * step_sin;  // theta - pi / k
        s = s * step_cos - c * step_sin;
        c = next_c;
    }
    return count;
}

bool oneTripNormal(const Vec3& d, const Vec3& n, const Vec3& target, CavityNormal& out) {
    const Vec3 w = mirrored(target, n);
    const Vec3 half{d.x - w.x, d.y - w.y, d.z - w.z};
    const double length = std::sqrt(dot(half, half));
    if (!(length > 1e-12)) return false;
    out.h = {half.x / length, half.y / length, half.z / length};
    if (out.h.z < 0.0) out.h = {-out.h.x, -out.h.y, -out.h.z};
    out.jacobian = 4.0 * std::abs(dot(d, out.h));
    return out.jacobian > 0.0;
}

int cavityNormals(const Vec3& d, const Vec3& n, const Vec3& target, int k, CavityNormals& out) {
    CavityTurn turn;
    if (!cavityTurn(d, n, target, turn)) return 0;
    return cavityNormals(turn, d, n, target, k, out);
}

CavityForm cavityChainForm(std::span<const ChainChange> latest_first) {
    const auto size = static_cast<int>(latest_first.size());
    int ic = 0;
    while (ic < size && !latest_first[static_cast<std::size_t>(ic)].first_meeting) ++ic;
    if (ic == 0 || ic >= size) return {};  // no suffix after c, or no c in the ring
    const std::int64_t c = latest_first[static_cast<std::size_t>(ic)].flake_id;
    if (c < 0) return {};
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
        if (m < 0 || m > kMaxCavityRetrace || (m == 0 && j == 0)) continue;
        const std::int64_t x1 = x(1);
        if (x1 < 0) continue;
        bool match = true;
        for (int t = 0; t < j && match; ++t) match = s(2 * t + 1) == x1 && s(2 * t + 2) == c;
        match = match && (m == 0 || s(2 * j + 1) == x1);
        for (int i = 2; i <= m && match; ++i) match = x(i) >= 0 && s(2 * j + i) == x(i);
        if (match) return {static_cast<int>(layer), j, m};
    }
    return {};
}

}  // namespace paintlab::mc
