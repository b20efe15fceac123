#include "mc_connection.h"

#include "paintlab/engine/fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr int kMaxCrossings = 100000;  // safety cap on flakes / wraps along one straight path

// Transmittance along the segment from (x, y, depth) of length `length` in
// direction u through one layer's tile (wrapping at its sides): the product
// of T(|u.n|) over the flakes crossed. x, y are advanced to the segment's end.
double tileTransmittance(const LayerFlakes& lf, double& x, double& y, double depth, const Vec3& u,
                         double length) {
    const FlakeTile& tile = *lf.tile;
    const double L = tile.sideUm();
    const double inf = std::numeric_limits<double>::infinity();
    double T = 1.0;
    double t_near = kTileEpsilonUm;
    double left = length;
    for (int step = 0; step < kMaxCrossings && left > 0.0; ++step) {
        if (x < 0.0 || x > L) x -= L * std::floor(x / L);
        if (y < 0.0 || y > L) y -= L * std::floor(y / L);
        const double tx = u.x > 0.0 ? (L - x) / u.x : (u.x < 0.0 ? -x / u.x : inf);
        const double ty = u.y > 0.0 ? (L - y) / u.y : (u.y < 0.0 ? -y / u.y : inf);
        const double t_side = std::min(tx, ty);
        const double t_far = std::min(left, t_side);
        const FlakeHit hit = tile.intersect({x, y, -depth}, u, t_near, t_far);
        if (hit.kind >= 0) {
            T *= lf.kinds[static_cast<std::size_t>(hit.kind)].T(std::abs(dot(u, hit.normal)));
            if (!(T > 0.0)) return 0.0;
            x += u.x * hit.t;
            y += u.y * hit.t;
            depth -= u.z * hit.t;
            left -= hit.t;
            t_near = kTileEpsilonUm;
            continue;
        }
        if (t_side >= left) {
            x += u.x * left;
            y += u.y * left;
            return T;
        }
        x += u.x * t_side;
        y += u.y * t_side;
        depth -= u.z * t_side;
        left -= t_side;
        if (tx <= ty)
            x = u.x > 0.0 ? 0.0 : L;
        else
            y = u.y > 0.0 ? 0.0 : L;
        t_near = 0.0;
    }
    return T;
}

}  // namespace

bool refractPlanar(const Vec3& v, double n_from, double n_to, Vec3& out) {
    const double ratio = n_from / n_to;
    out = {v.x * ratio, v.y * ratio, 0.0};
    const double s2 = out.x * out.x + out.y * out.y;
    if (s2 >= 1.0) return false;
    out.z = std::copysign(std::sqrt(1.0 - s2), v.z);
    return true;
}

double straightToAmbient(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u) {
    double T = 1.0;
    for (;;) {
        const Slice& s = stack.slices[j];
        const double mu = u.z;
        if (!(mu > 1e-12)) return 0.0;
        const double length = std::max(0.0, depth - s.top_um) / mu;
        // Pigments only: the slices of tiled layers carry no continuum flakes.
        T *= std::exp(-(s.sigma_a_per_um + s.sigma_s_per_um) * length);
        const auto layer = static_cast<std::size_t>(s.layer);
        if (layer < tiles.size() && tiles[layer].tile != nullptr) {
            T *= tileTransmittance(tiles[layer], x, y, depth, u, length);
        } else {
            x += u.x * length;
            y += u.y * length;
        }
        if (!(T > 0.0)) return 0.0;
        const double n_above = j == 0 ? stack.ambient_n : stack.slices[j - 1].n;
        if (std::abs(n_above - s.n) >= 1e-12) {
            T *= 1.0 - fresnelDielectric(mu, n_above / s.n);
            Vec3 refracted;
            if (!(T > 0.0) || !refractPlanar(u, s.n, n_above, refracted)) return 0.0;
            u = refracted;
        }
        if (j == 0) return T;
        --j;
        depth = stack.slices[j].bottom_um;
    }
}

Vec3 sampleInCone(const HistogramBin& bin, double u1, double u2) {
    const double cos_beta = 1.0 - u1 * (1.0 - bin.cos_cone);
    const double sin_beta = std::sqrt(std::max(0.0, 1.0 - cos_beta * cos_beta));
    const double phi = 2.0 * std::numbers::pi * u2;
    const Vec3& a = bin.wo;
    // Basis around the axis (Duff et al., JCGT 2017).
    const double sign = std::copysign(1.0, a.z);
    const double k = -1.0 / (sign + a.z);
    const double h = a.x * a.y * k;
    const Vec3 b1{1.0 + sign * a.x * a.x * k, sign * h, -sign * a.x};
    const Vec3 b2{h, sign + a.y * a.y * k, -a.y};
    const double cx = sin_beta * std::cos(phi);
    const double cy = sin_beta * std::sin(phi);
    return {cx * b1.x + cy * b2.x + cos_beta * a.x, cx * b1.y + cy * b2.y + cos_beta * a.y,
            cx * b1.z + cy * b2.z + cos_beta * a.z};
}

std::vector<GlintSet> glintSets(const PaintStack& stack, std::span<const LayerFlakes> tiles, const Vec3& v_in,
                                std::span<const HistogramBin> bins) {
    std::vector<GlintSet> sets(bins.size());
    const double n_top = stack.slices.front().n;
    for (std::size_t l = 0; l < tiles.size(); ++l) {
        const FlakeTile* tile = tiles[l].tile;
        if (tile == nullptr) continue;
        // The beam in layer l: the invariant n sin(theta) (every slice of a layer has its binder's index).
        double n_layer = 0.0;
        for (const auto& s : stack.slices)
            if (static_cast<std::size_t>(s.layer) == l) n_layer = s.n;
        if (!(n_layer > 0.0)) continue;
        Vec3 v;
        if (!refractPlanar(v_in, n_top, n_layer, v)) continue;
        const double L = tile->sideUm();
        const auto& flakes = tile->flakes();
        for (std::size_t i = 0; i < flakes.size(); ++i) {
            const Vec3& n = flakes[i].normal;
            const double vn = dot(v, n);
            const Vec3 r{v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
            if (!(r.z > 0.0)) continue;
            // Where the reflection leaves into the ambient (interfaces in between only refract).
            Vec3 w;
            if (!refractPlanar(r, n_layer, stack.ambient_n, w)) continue;
            const double weight = tile->flakeAreaUm2(i) * std::abs(vn) / (std::abs(v.z) * L * L);
            for (std::size_t k = 0; k < bins.size(); ++k) {
                if (dot(w, bins[k].wo) < bins[k].cos_cone) continue;
                GlintSet& set = sets[k];
                set.flakes.push_back({static_cast<int>(l), i, v, r, std::abs(vn)});
                set.cumulative.push_back(set.total() + weight);
            }
        }
    }
    return sets;
}

void scoreGlints(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                 std::span<const GlintSet> glints, std::span<const HistogramBin> bins, double weight,
                 PathRng& rng, std::span<double> f_out) {
    for (std::size_t k = 0; k < glints.size(); ++k) {
        const GlintSet& set = glints[k];
        const double total = set.total();
        if (!(total > 0.0)) continue;
        const double pick = rng.uniform() * total;
        const auto it = std::upper_bound(set.cumulative.begin(), set.cumulative.end(), pick);
        const auto index =
            std::min(static_cast<std::size_t>(it - set.cumulative.begin()), set.flakes.size() - 1);
        const GlintFlake& g = set.flakes[index];
        const LayerFlakes& lf = tiles[static_cast<std::size_t>(g.layer)];
        const double u1 = rng.uniform();
        const double u2 = rng.uniform();
        const Vec3 p = lf.tile->pointOnFlake(g.flake, u1, u2, rng.uniform());
        const double depth = -p.z;
        // The slice of the flake's layer that holds the point; none if the point
        // pokes out of the layer (a flake tilted in a film thinner than it), which
        // the walk cannot hit there either (it traces a tile inside its layer only).
        std::size_t j = 0;
        while (j < stack.slices.size() &&
               !(stack.slices[j].layer == g.layer && depth >= stack.slices[j].top_um &&
                 depth <= stack.slices[j].bottom_um))
            ++j;
        if (j == stack.slices.size()) continue;
        const int kind = lf.tile->flakes()[g.flake].kind;
        const double R = lf.kinds[static_cast<std::size_t>(kind)].R(g.cos_local);
        if (!(R > 0.0)) continue;
        const double t_in = straightToAmbient(stack, tiles, j, depth, p.x, p.y, {-g.v.x, -g.v.y, -g.v.z});
        if (!(t_in > 0.0)) continue;
        const double t_out = straightToAmbient(stack, tiles, j, depth, p.x, p.y, g.r);
        f_out[k] += weight * total * t_in * R * t_out / bins[k].projected_solid_angle;
    }
}

}  // namespace paintlab::mc
