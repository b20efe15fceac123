#include "mc_connection.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

double tileTransmittance(const LayerFlakes& lf, double& x, double& y, double depth, const Vec3& u,
                         double length, std::int64_t* rays, std::int64_t absent_flake) {
    double T = 1.0;
    const bool passed = marchTile(*lf.tile, x, y, depth, u, length, rays, [&](const FlakeHit& hit, double) {
        if (hit.flake == absent_flake) return true;
        T *= lf.kinds[static_cast<std::size_t>(hit.kind)].T(std::abs(dot(u, hit.normal)));
        return T > 0.0;
    });
    return passed ? T : 0.0;
}

TileHit firstFlakeAlong(const LayerFlakes& lf, double x, double y, double depth, const Vec3& u, double length,
                        std::int64_t* rays) {
    TileHit first;
    const bool passed =
        marchTile(*lf.tile, x, y, depth, u, length, rays, [&](const FlakeHit& hit, double travelled) {
            first = {hit, x + u.x * hit.t, y + u.y * hit.t};
            first.hit.t += travelled;
            return false;
        });
    if (passed) first = {{}, x, y};
    return first;
}

TileHit targetFlakeAlong(const LayerFlakes& lf, double x, double y, double depth, const Vec3& u,
                         double length, std::int64_t target, double& T, std::int64_t* rays) {
    TileHit found;
    const bool passed =
        marchTile(*lf.tile, x, y, depth, u, length, rays, [&](const FlakeHit& hit, double travelled) {
            if (hit.flake == target) {
                found = {hit, x + u.x * hit.t, y + u.y * hit.t};
                found.hit.t += travelled;
                return false;
            }
            T *= lf.kinds[static_cast<std::size_t>(hit.kind)].T(std::abs(dot(u, hit.normal)));
            return T > 0.0;
        });
    if (passed) found = {{}, x, y};
    return found;
}

double layerOpticalDepth(const PaintStack& stack, int layer, double depth_a, double depth_b, double abs_mu) {
    const double lo = std::min(depth_a, depth_b);
    const double hi = std::max(depth_a, depth_b);
    double tau = 0.0;
    for (const auto& s : stack.slices) {
        if (s.layer != layer) continue;
        const double overlap = std::min(hi, s.bottom_um) - std::max(lo, s.top_um);
        if (overlap > 0.0) tau += (s.sigma_a_per_um + s.sigma_s_per_um) * overlap;
    }
    return tau / abs_mu;
}

std::size_t sliceAt(const PaintStack& stack, int layer, double depth) {
    std::size_t j = 0;
    while (j < stack.slices.size() && !(stack.slices[j].layer == layer && depth >= stack.slices[j].top_um &&
                                        depth <= stack.slices[j].bottom_um))
        ++j;
    return j;
}

bool refractPlanar(const Vec3& v, double n_from, double n_to, Vec3& out) {
    const double ratio = n_from / n_to;
    out = {v.x * ratio, v.y * ratio, 0.0};
    const double s2 = out.x * out.x + out.y * out.y;
    if (s2 >= 1.0) return false;
    out.z = std::copysign(std::sqrt(1.0 - s2), v.z);
    return true;
}

TopArrival straightToTop(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u, std::int64_t* rays, PathRng* roulette,
                         const AbsentFlake& absent) {
    double T = 1.0;
    for (;;) {
        const Slice& s = stack.slices[j];
        const double mu = u.z;
        if (!(mu > 1e-12)) return {};
        const double length = std::max(0.0, depth - s.top_um) / mu;
        // Pigments only: the slices of tiled layers carry no continuum flakes.
        T *= std::exp(-(s.sigma_a_per_um + s.sigma_s_per_um) * length);
        const auto layer = static_cast<std::size_t>(s.layer);
        if (layer < tiles.size() && tiles[layer].tile != nullptr) {
            if (roulette != nullptr && T < kConnectionRouletteT) {
                if (!(T > 0.0) || roulette->uniform() * kConnectionRouletteT >= T) return {};
                T = kConnectionRouletteT;
                roulette = nullptr;  // once per connection
            }
            T *= tileTransmittance(tiles[layer], x, y, depth, u, length, rays, absent.in(layer));
        } else {
            x += u.x * length;
            y += u.y * length;
        }
        if (!(T > 0.0)) return {};
        if (j == 0) return {T, x, y, u};
        const double n_above = stack.slices[j - 1].n;
        if (std::abs(n_above - s.n) >= 1e-12) {
            T *= 1.0 - fresnelDielectric(mu, n_above / s.n);
            Vec3 refracted;
            if (!(T > 0.0) || !refractPlanar(u, s.n, n_above, refracted)) return {};
            u = refracted;
        }
        --j;
        depth = stack.slices[j].bottom_um;
    }
}

double straightToAmbient(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                         double depth, double x, double y, Vec3 u, std::int64_t* rays, PathRng* roulette,
                         const AbsentFlake& absent) {
    const TopArrival top = straightToTop(stack, tiles, j, depth, x, y, u, rays, roulette, absent);
    if (!(top.T > 0.0)) return 0.0;
    const double n_top = stack.slices.front().n;
    if (std::abs(stack.ambient_n - n_top) < 1e-12) return top.T;
    Vec3 out;
    if (!refractPlanar(top.u, n_top, stack.ambient_n, out)) return 0.0;
    return top.T * (1.0 - fresnelDielectric(top.u.z, stack.ambient_n / n_top));
}

Vec3 sampleInCone(const HistogramBin& bin, double u1, double u2) {
    const double cos_beta = 1.0 - u1 * (1.0 - bin.cos_cone);
    return directionAround(bin.wo, cos_beta, 2.0 * std::numbers::pi * u2);
}

}  // namespace paintlab::mc
