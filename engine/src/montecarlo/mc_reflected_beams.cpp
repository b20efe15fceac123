#include "mc_reflected_beams.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

namespace {

// Transmittance from (x, y, depth) along u through one layer's tile up to
// flake `target` (FlakeTile::flakes(), any periodic copy) at distance t_flake:
// the product of T over the flakes crossed before it; 0 if a mirror blocks the
// way or the ray does not meet that flake there (its polygon is inside the
// disk that selected it). The flake is recognised by its index, not by the
// distance (Embree's float ray, FlakeTile::intersect); the search runs a
// little beyond t_flake for the same reason.
double transmittanceToFlake(const LayerFlakes& lf, double x, double y, double depth, const Vec3& u,
                            double t_flake, std::size_t target, std::int64_t* rays) {
    const double slack = 1e-3 + 1e-4 * t_flake;  // µm: far above float rounding, far below a flake's size
    double T = 1.0;
    bool reached = false;
    marchTile(*lf.tile, x, y, depth, u, t_flake + slack, rays, [&](const FlakeHit& hit, double) {
        if (hit.flake == static_cast<std::int64_t>(target)) {
            reached = true;
            return false;
        }
        T *= lf.kinds[static_cast<std::size_t>(hit.kind)].T(std::abs(dot(u, hit.normal)));
        return T > 0.0;
    });
    return reached ? T : 0.0;
}

// Calls hit(t, rel) for each periodic image of `flake` whose reflected column
// along r holds the point z: z - t r lies on the image's disk, t > 0, at
// `rel` from the image's centre. The disk is the polygon's circumcircle; the
// caller tests the polygon where it matters (FlakeTile::onFlake).
template <class Hit> void columnsHolding(const PlacedFlake& flake, const Vec3& r, double rn, const Vec3& z,
                                         double L, const Hit& hit) {
    const Vec3& n = flake.normal;
    // z seen from the flake's centre, then the periodic image whose column along r can hold it.
    const Vec3 d{z.x - flake.centre.x, z.y - flake.centre.y, z.z - flake.centre.z};
    const double t0 = d.z / r.z;
    const double margin = 4.0 * flake.radius_um / L;
    const double gx = (d.x - t0 * r.x) / L;
    const double gy = (d.y - t0 * r.y) / L;
    const double ax = std::round(gx);
    const double ay = std::round(gy);
    const double sx = gx - ax > 0.5 - margin ? 1.0 : (gx - ax < margin - 0.5 ? -1.0 : 0.0);
    const double sy = gy - ay > 0.5 - margin ? 1.0 : (gy - ay < margin - 0.5 ? -1.0 : 0.0);
    for (int ix = 0; ix <= (sx != 0.0 ? 1 : 0); ++ix)
        for (int iy = 0; iy <= (sy != 0.0 ? 1 : 0); ++iy) {
            const double shift_x = (ax + ix * sx) * L;
            const double shift_y = (ay + iy * sy) * L;
            const Vec3 di{d.x - shift_x, d.y - shift_y, d.z};
            const double t = dot(di, n) / rn;
            if (!(t > kTileEpsilonUm)) continue;
            const Vec3 rel{di.x - t * r.x, di.y - t * r.y, di.z - t * r.z};
            if (dot(rel, rel) > flake.radius_um * flake.radius_um) continue;
            hit(t, rel);
        }
}

}  // namespace

namespace {

// Lateral reach by tilt class (reflectedBeams' candidates): a flake of tilt up
// to tilt[i] lights points at most sqrt(reach2[i]) (µm) from its centre
// laterally (squared: the cells' test); both ascending. Flakes steeper than
// the last tilt (the cut) are all visited; an empty table visits every flake.
struct ReachTable {
    std::vector<double> tilt;
    std::vector<double> reach2;
};

// Distance from p to the nearest periodic copy (period L) of the interval [a, b].
double periodicGap(double a, double b, double p, double L) {
    double best = std::numeric_limits<double>::infinity();
    for (int k = -1; k <= 1; ++k) {
        const double lo = a + k * L;
        const double hi = b + k * L;
        best = std::min(best, p < lo ? lo - p : (p > hi ? p - hi : 0.0));
    }
    return best;
}

// The flakes a reflected column can reach a point from, each once: in every
// cell of the lateral grid within the table's last reach of (x, y), those of
// a tilt class whose reach is at least the cell's distance, up to the cut;
// then every steeper one. Returns how many were visited.
template <class Visit> std::size_t visitCandidates(const TiltIndex* tilts, std::size_t flake_count, double L,
                                                   double x, double y, const ReachTable& table,
                                                   const Visit& visit) {
    if (tilts == nullptr || table.tilt.empty() || tilts->cells <= 0) {
        for (std::size_t i = 0; i < flake_count; ++i) visit(i);
        return flake_count;
    }
    const TiltIndex& index = *tilts;
    const double tilt_cut = table.tilt.back();
    const std::vector<double>& reach2 = table.reach2;
    const double reach_um = std::sqrt(reach2.back());
    std::size_t visited = 0;
    const int n = index.cells;
    const auto range = [&](double c, int& lo, int& count) {
        lo = static_cast<int>(std::floor((c - reach_um) / index.cell_um));
        count = std::min(n, static_cast<int>(std::floor((c + reach_um) / index.cell_um)) - lo + 1);
    };
    int x0 = 0;
    int nx = 0;
    int y0 = 0;
    int ny = 0;
    range(x, x0, nx);
    range(y, y0, ny);
    const double px = x - L * std::floor(x / L);
    const double py = y - L * std::floor(y / L);
    const auto wrap = [n](int c) { return ((c % n) + n) % n; };
    for (int iy = 0; iy < ny; ++iy) {
        const int cy = wrap(y0 + iy);
        const double gap_y = periodicGap(cy * index.cell_um, (cy + 1) * index.cell_um, py, L);
        const auto row = static_cast<std::size_t>(cy) * static_cast<std::size_t>(n);
        for (int ix = 0; ix < nx; ++ix) {
            const int cx = wrap(x0 + ix);
            const double gap_x = periodicGap(cx * index.cell_um, (cx + 1) * index.cell_um, px, L);
            const double gap2 = gap_x * gap_x + gap_y * gap_y;
            if (gap2 > reach2.back()) continue;
            // The classes whose reach falls short of the cell: their flakes cannot light the point.
            const auto short_classes = static_cast<std::size_t>(
                std::lower_bound(reach2.begin(), reach2.end(), gap2) - reach2.begin());
            const double tilt_floor = short_classes == 0 ? -1.0 : table.tilt[short_classes - 1];
            const std::size_t cell = row + static_cast<std::size_t>(cx);
            const auto first = index.cell_tilts.begin() + index.cell_start[cell];
            const auto last = index.cell_tilts.begin() + index.cell_start[cell + 1];
            for (auto it = std::upper_bound(first, last, tilt_floor); it != last && *it <= tilt_cut; ++it) {
                visit(index.cell_flakes[static_cast<std::size_t>(it - index.cell_tilts.begin())]);
                ++visited;
            }
        }
    }
    const auto steep = std::upper_bound(index.tilt.begin(), index.tilt.end(), tilt_cut) - index.tilt.begin();
    for (auto k = static_cast<std::size_t>(steep); k < index.order.size(); ++k) visit(index.order[k]);
    return visited + (index.order.size() - static_cast<std::size_t>(steep));
}

// The reach table for a beam at polar angle theta_b (in the layer) that makes
// visitCandidates cheapest: a flake of tilt tau sends the beam at most
// theta_b + 2 tau from the vertical, so tilt class i (up to tau_i, theta_i =
// theta_b + 2 tau_i every 2.5 degrees) reaches reach(theta_i) (infinite: no
// bound); each cut is costed by the flakes it would visit (the steep ones all,
// each class over its own box) and the cells of its box.
template <class Reach>
ReachTable cheapestTable(const TiltIndex& index, double L, double theta_b, const Reach& reach) {
    constexpr double kStep = 2.5 * std::numbers::pi / 180.0;
    constexpr double kLimit = 87.5 * std::numbers::pi / 180.0;
    constexpr double kCellCost = 0.25;  // a cell's distance test against a flake's column test
    ReachTable table;
    ReachTable best;
    const auto all = static_cast<double>(index.order.size());
    double best_cost = all;
    double inner = 0.0;  // the classes so far, each over its box
    std::size_t below = 0;
    for (double theta = theta_b + kStep; theta <= kLimit; theta += kStep) {
        const double cut = 0.5 * (theta - theta_b);
        const double r = reach(theta);
        if (!(r < 0.5 * L)) break;
        const auto upto = static_cast<std::size_t>(
            std::upper_bound(index.tilt.begin(), index.tilt.end(), cut) - index.tilt.begin());
        const double side = std::min(1.0, (2.0 * r + 2.0 * index.cell_um) / L);
        inner += static_cast<double>(upto - below) * side * side;
        below = upto;
        table.tilt.push_back(cut);
        table.reach2.push_back(r * r);
        const double cells =
            side * side * static_cast<double>(index.cells) * static_cast<double>(index.cells);
        const double cost = (all - static_cast<double>(upto)) + inner + kCellCost * cells;
        if (cost < best_cost) {
            best_cost = cost;
            best = table;
        }
    }
    return best;
}

}  // namespace

double reflectedBeams(const PaintStack& stack, std::span<const LayerFlakes> tiles, std::size_t j,
                      double depth, double x, double y, const Vec3& v, const Vec3& beam_top,
                      BeamImages images, std::int64_t* rays) {
    const Slice& s = stack.slices[j];
    const auto layer = static_cast<std::size_t>(s.layer);
    if (layer >= tiles.size() || tiles[layer].tile == nullptr) return 0.0;
    if (!images.off_flakes && !images.off_flake_then_top) return 0.0;
    const LayerFlakes& lf = tiles[layer];
    const FlakeTile& tile = *lf.tile;
    Vec3 beam;  // the beam in this layer (downward)
    if (!refractPlanar(beam_top, stack.slices.front().n, s.n, beam) || !(beam.z < 0.0)) return 0.0;
    const double L = tile.sideUm();
    const Vec3 z{x, y, -depth};
    // The layer's slices (contiguous), the slices above it and its top.
    std::size_t first = j;
    while (first > 0 && stack.slices[first - 1].layer == s.layer) --first;
    std::size_t last = j;
    while (last + 1 < stack.slices.size() && stack.slices[last + 1].layer == s.layer) ++last;
    const std::span<const Slice> above = std::span(stack.slices).first(first);
    const double layer_top_um = stack.slices[first].top_um;
    const double layer_um = stack.slices[last].bottom_um - layer_top_um;
    const double n_top = stack.slices.front().n;
    const auto& flakes = tile.flakes();
    double sum = 0.0;
    // The point z lit straight from flake i, along u = -r.
    // The beam's mirror direction r off a flake, with beam.n and r.n.
    struct Mirror {
        Vec3 r;
        double bn = 0.0;
        double rn = 0.0;
    };
    const auto mirror = [&beam](const PlacedFlake& flake) {
        const Vec3& n = flake.normal;
        const double bn = dot(beam, n);
        const Vec3 r{beam.x - 2.0 * bn * n.x, beam.y - 2.0 * bn * n.y, beam.z - 2.0 * bn * n.z};
        return Mirror{r, bn, dot(r, n)};
    };
    const auto offFlake = [&](std::size_t i) {
        const PlacedFlake& flake = flakes[i];
        const Mirror m = mirror(flake);
        const Vec3& r = m.r;
        const double bn = m.bn;
        const double rn = m.rn;
        if (std::abs(r.z) < 1e-9 || std::abs(rn) < 1e-12) return;
        const Vec3 u{-r.x, -r.y, -r.z};
        columnsHolding(flake, r, rn, z, L, [&](double t, const Vec3& /*rel*/) {
            // The point on the flake (lateral coordinates continued from z's).
            const double px = x - t * r.x;
            const double py = y - t * r.y;
            const double p_depth = depth + t * r.z;
            const std::size_t jp = sliceAt(stack, s.layer, p_depth);
            if (jp == stack.slices.size()) return;
            // R(|beam.n|) (a metal's is a complex Fresnel).
            const double R = lf.kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(bn));
            const double phase = s.kernel(v, u);
            if (!(R > 0.0) || !(phase > 0.0)) return;
            const double to_flake =
                transmittanceToFlake(lf, x, y, depth, u, t, i, rays) *
                std::exp(-layerOpticalDepth(stack, s.layer, depth, p_depth, std::abs(r.z)));
            if (!(to_flake > 0.0)) return;
            const double to_top =
                straightToAmbient(stack, tiles, jp, p_depth, px, py, {-beam.x, -beam.y, -beam.z}, rays);
            sum += phase * to_flake * R * to_top;
        });
    };
    // The column flake i reflects upwards, back down from the top's internal
    // reflection: z is lit along (r.x, r.y, -r.z), so from z the light is seen
    // along u = (-r.x, -r.y, r.z). Unfolded at the top, the column is
    // straight: z's image at the layer's top is shifted by the lateral run of
    // u up from z to the paint's top and down again through the slices above
    // (Snell in each).
    const auto offFlakeThenTop = [&](std::size_t i) {
        const PlacedFlake& flake = flakes[i];
        const Mirror m = mirror(flake);
        const Vec3& r = m.r;
        const double bn = m.bn;
        const double rn = m.rn;
        if (!(r.z > 1e-9) || std::abs(rn) < 1e-12) return;
        const Vec3 u{-r.x, -r.y, r.z};
        const double sin2 = r.x * r.x + r.y * r.y;  // in this layer
        double run = (depth - layer_top_um) / r.z;  // lateral run per unit of (-r.x, -r.y)
        for (const Slice& a : above) {
            const double ratio = s.n / a.n;
            const double cos2 = 1.0 - sin2 * ratio * ratio;
            if (!(cos2 > 1e-12)) return;  // totally reflected on the way up: not this path class
            run += 2.0 * (a.bottom_um - a.top_um) * ratio / std::sqrt(cos2);
        }
        const Vec3 image{x - run * r.x, y - run * r.y, -layer_top_um};
        columnsHolding(flake, r, rn, image, L, [&](double t, const Vec3& rel) {
            if (!tile.onFlake(i, rel)) return;
            const double px = image.x - t * r.x;
            const double py = image.y - t * r.y;
            const double p_depth = layer_top_um + t * r.z;
            const std::size_t jp = sliceAt(stack, s.layer, p_depth);
            if (jp == stack.slices.size()) return;
            const double R = lf.kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(bn));
            const double phase = s.kernel(v, u);
            if (!(R > 0.0) || !(phase > 0.0)) return;
            // From z up to the top, the top's reflectance, from the flake up to the
            // top (the same straight segment as from the top down to it).
            const TopArrival down = straightToTop(stack, tiles, j, depth, x, y, u, rays);
            if (!(down.T > 0.0)) return;
            const double F = std::abs(stack.ambient_n - n_top) < 1e-12
                                 ? 0.0
                                 : fresnelDielectric(down.u.z, stack.ambient_n / n_top);
            if (!(F > 0.0)) return;
            const TopArrival up = straightToTop(stack, tiles, jp, p_depth, px, py, r, rays);
            if (!(up.T > 0.0)) return;
            const double to_top =
                straightToAmbient(stack, tiles, jp, p_depth, px, py, {-beam.x, -beam.y, -beam.z}, rays);
            sum += phase * down.T * F * up.T * R * to_top;
        });
    };
    // Which flakes to test (TiltIndex's grid; without it, all). A column from a
    // flake tilted by tau leaves at most theta_max = theta_b + 2 tau from the
    // vertical, and both its ends lie in the layer (its top for the top
    // images, which then also run twice through each slice above).
    std::size_t tested = 0;
    const double theta_b = std::acos(std::clamp(-beam.z, 0.0, 1.0));
    const auto tanOf = [](double sin_theta) {
        return sin_theta < 1.0 ? sin_theta / std::sqrt(1.0 - sin_theta * sin_theta)
                               : std::numeric_limits<double>::infinity();
    };
    // Without the tilt index every flake is a candidate (visitCandidates).
    const auto candidates = [&](const auto& reach, const auto& visit) {
        const ReachTable table =
            lf.tilts == nullptr ? ReachTable{} : cheapestTable(*lf.tilts, L, theta_b, reach);
        tested += visitCandidates(lf.tilts, flakes.size(), L, x, y, table, visit);
    };
    const double radius_um = lf.tilts == nullptr ? 0.0 : lf.tilts->max_radius_um;
    if (images.off_flakes)
        candidates([&](double theta_max) { return layer_um * std::tan(theta_max) + radius_um; }, offFlake);
    if (images.off_flake_then_top)
        candidates(
            [&](double theta_max) {
                double reach = 2.0 * layer_um * std::tan(theta_max) + radius_um;
                for (const Slice& a : above)
                    reach += 2.0 * a.thicknessUm() * tanOf(std::sin(theta_max) * s.n / a.n);
                return reach;
            },
            offFlakeThenTop);
    // The candidates' plane tests join the shadow rays in the cost model of
    // the adaptive rates, 64 tests as one unit; the unit's cost
    // (kCostPerImageRay, mc_rates.h) is fitted to measured times.
    if (rays != nullptr) *rays += static_cast<std::int64_t>(tested / 64);
    return sum;
}

}  // namespace paintlab::mc
