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
                         double length, std::int64_t* rays) {
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
        if (rays != nullptr) ++*rays;
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

Vec3 turn(const Vec3& a, double c, double s) { return {c * a.x - s * a.y, s * a.x + c * a.y, a.z}; }

Vec3 normalised(const Vec3& a) {
    const double len = std::sqrt(dot(a, a));
    return {a.x / len, a.y / len, a.z / len};
}

double angleBetween(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(dot(a, b), -1.0, 1.0)); }

// Optical depth from the top of the paint down to `depth` along a direction
// with invariant s = n sin(theta), per slice at its own cosine: the slice's
// extinction of an unscattered ray (pigments, continuum flakes, and for a
// tiled layer the mean extinction of its tile's flakes). Only a proposal
// weight (azimuthGlintSets): any positive value keeps the estimate unbiased.
class ProxyDepth {
public:
    ProxyDepth(const PaintStack& stack, std::span<const LayerFlakes> tiles, double s_invariant) {
        for (const auto& slice : stack.slices) {
            const double sin_t = s_invariant / slice.n;
            const double mu = sin_t < 1.0 ? std::sqrt(1.0 - sin_t * sin_t) : 0.0;
            double rate = std::numeric_limits<double>::infinity();
            if (mu > 1e-6) {
                const auto layer = static_cast<std::size_t>(slice.layer);
                if (layer < tiles.size() && tiles[layer].tile != nullptr) {
                    Slice mean_field = slice;
                    mean_field.flakes = tiles[layer].kinds;
                    rate = mean_field.chainExtinction(mu) / mu;
                } else {
                    rate = slice.chainExtinction(mu) / mu;
                }
            }
            m_top.push_back(slice.top_um);
            m_bottom.push_back(slice.bottom_um);
            m_rate.push_back(rate);
        }
    }
    double at(double depth) const {
        double od = 0.0;
        for (std::size_t j = 0; j < m_top.size() && m_top[j] < depth; ++j) {
            const double thickness = std::min(depth, m_bottom[j]) - m_top[j];
            if (thickness > 0.0) od += std::isinf(m_rate[j]) ? 1e3 : m_rate[j] * thickness;
        }
        return std::min(od, 1e3);
    }

private:
    std::vector<double> m_top, m_bottom, m_rate;
};

constexpr int kAzimuthScan = 16;      // azimuths tested per glint sample (azimuthGlintSample)
constexpr int kAzimuthScanBuild = 8;  // and per listed flake for its proposal weight

// Whether the flake with normal n reflects the beam v0 (layer l, unturned) into the bin at the view
// turned by the angle with cosine c and sine s.
bool glintsAt(const Vec3& v0, const Vec3& n, double n_layer, double ambient_n, const HistogramBin& bin,
              double c, double s) {
    const Vec3 v{c * v0.x - s * v0.y, s * v0.x + c * v0.y, v0.z};
    const double vn = dot(v, n);
    const Vec3 r{v.x - 2.0 * vn * n.x, v.y - 2.0 * vn * n.y, v.z - 2.0 * vn * n.z};
    Vec3 w;
    if (!(r.z > 0.0) || !refractPlanar(r, n_layer, ambient_n, w)) return false;
    const Vec3 wo{c * bin.wo.x - s * bin.wo.y, s * bin.wo.x + c * bin.wo.y, bin.wo.z};
    return dot(w, wo) >= bin.cos_cone;
}

}  // namespace

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
                         double depth, double x, double y, Vec3 u, std::int64_t* rays) {
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
            T *= tileTransmittance(tiles[layer], x, y, depth, u, length, rays);
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
                         double depth, double x, double y, Vec3 u, std::int64_t* rays) {
    const TopArrival top = straightToTop(stack, tiles, j, depth, x, y, u, rays);
    if (!(top.T > 0.0)) return 0.0;
    const double n_top = stack.slices.front().n;
    if (std::abs(stack.ambient_n - n_top) < 1e-12) return top.T;
    Vec3 out;
    if (!refractPlanar(top.u, n_top, stack.ambient_n, out)) return 0.0;
    return top.T * (1.0 - fresnelDielectric(top.u.z, stack.ambient_n / n_top));
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
        const std::size_t j = sliceAt(stack, g.layer, depth);
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

TiltIndex tiltIndex(const FlakeTile& tile) {
    const auto& flakes = tile.flakes();
    std::vector<double> tilt;
    std::vector<std::uint32_t> order;
    for (std::size_t i = 0; i < flakes.size(); ++i) {
        order.push_back(static_cast<std::uint32_t>(i));
        tilt.push_back(std::acos(std::clamp(std::abs(flakes[i].normal.z), 0.0, 1.0)));
    }
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return tilt[a] < tilt[b] || (tilt[a] == tilt[b] && a < b);
    });
    TiltIndex index;
    for (std::uint32_t i : order) index.tilt.push_back(tilt[i]);
    // The lateral grid: cells about a flake diameter wide (a query's box is
    // then covered with little waste), each cell's flakes in tilt order.
    const double L = tile.sideUm();
    for (const auto& f : flakes) index.max_radius_um = std::max(index.max_radius_um, f.radius_um);
    index.cells =
        static_cast<int>(std::clamp(std::floor(L / std::max(2.0 * index.max_radius_um, 1e-9)), 1.0, 1024.0));
    index.cell_um = L / index.cells;
    const auto cell_of = [&](std::uint32_t i) {
        const auto c = [&](double a) {
            return std::clamp(static_cast<int>(std::floor(a / index.cell_um)), 0, index.cells - 1);
        };
        return static_cast<std::size_t>(c(flakes[i].centre.y)) * static_cast<std::size_t>(index.cells) +
               static_cast<std::size_t>(c(flakes[i].centre.x));
    };
    const std::size_t cell_count =
        static_cast<std::size_t>(index.cells) * static_cast<std::size_t>(index.cells);
    index.cell_start.assign(cell_count + 1, 0);
    for (std::uint32_t i : order) ++index.cell_start[cell_of(i) + 1];
    for (std::size_t c = 0; c < cell_count; ++c) index.cell_start[c + 1] += index.cell_start[c];
    index.cell_flakes.resize(order.size());
    index.cell_tilts.resize(order.size());
    std::vector<std::uint32_t> fill(index.cell_start.begin(), index.cell_start.end() - 1);
    for (std::uint32_t i : order) {  // ascending tilt, so each cell stays sorted
        const std::uint32_t at = fill[cell_of(i)]++;
        index.cell_flakes[at] = i;
        index.cell_tilts[at] = tilt[i];
    }
    index.order = std::move(order);
    return index;
}

std::vector<AzimuthGlintSet> azimuthGlintSets(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                                              const Vec3& v_in, std::span<const HistogramBin> bins) {
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    constexpr int kEdge = 64;  // points on each cone's edge
    std::vector<AzimuthGlintSet> sets(bins.size());
    for (auto& set : sets) {
        set.v_layer.assign(tiles.size(), Vec3{0.0, 0.0, 0.0});
        set.n_layer.assign(tiles.size(), 1.0);
    }
    const double n_top = stack.slices.front().n;
    const ProxyDepth beam_depth(stack, tiles, n_top * std::hypot(v_in.x, v_in.y));
    std::vector<ProxyDepth> exit_depth;
    for (const auto& bin : bins)
        exit_depth.emplace_back(stack, tiles, stack.ambient_n * std::hypot(bin.wo.x, bin.wo.y));
    for (std::size_t l = 0; l < tiles.size(); ++l) {
        const FlakeTile* tile = tiles[l].tile;
        if (tile == nullptr || tiles[l].tilts == nullptr) continue;
        const TiltIndex& tilts = *tiles[l].tilts;
        double n_layer = 0.0;
        for (const auto& slice : stack.slices)
            if (static_cast<std::size_t>(slice.layer) == l) n_layer = slice.n;
        Vec3 v;
        if (!(n_layer > 0.0) || !refractPlanar(v_in, n_top, n_layer, v)) continue;
        const double L = tile->sideUm();
        const auto& flakes = tile->flakes();
        for (std::size_t k = 0; k < bins.size(); ++k) {
            const HistogramBin& bin = bins[k];
            AzimuthGlintSet& set = sets[k];
            set.v_layer[l] = v;
            set.n_layer[l] = n_layer;
            // The cap of normals that glint into the cone (a superset; the sample tests exactly).
            bool everything = false;
            Vec3 r_axis;
            if (!(bin.wo.z > 0.0) || !refractPlanar(bin.wo, stack.ambient_n, n_layer, r_axis))
                everything = true;
            Vec3 n_star{0.0, 0.0, 1.0};
            double rho = std::numbers::pi;
            if (!everything) {
                n_star = normalised({r_axis.x - v.x, r_axis.y - v.y, r_axis.z - v.z});
                double reach = 0.0;
                double gap = 0.0;
                Vec3 previous;
                for (int b = 0; b <= kEdge && !everything; ++b) {
                    const Vec3 w = sampleInCone(bin, 1.0, static_cast<double>(b % kEdge) / kEdge);
                    Vec3 r;
                    if (!(w.z > 1e-9) || !refractPlanar(w, stack.ambient_n, n_layer, r)) {
                        everything = true;
                        break;
                    }
                    const Vec3 h = normalised({r.x - v.x, r.y - v.y, r.z - v.z});
                    reach = std::max(reach, angleBetween(h, n_star));
                    if (b > 0) gap = std::max(gap, angleBetween(h, previous));
                    previous = h;
                }
                rho = everything ? std::numbers::pi : reach + 2.0 * gap + 1e-9;
            }
            const double tau_star = std::acos(std::clamp(n_star.z, -1.0, 1.0));
            const double phi_star = std::atan2(n_star.y, n_star.x);
            const double cos_rho = std::cos(rho);
            const auto lo = std::lower_bound(tilts.tilt.begin(), tilts.tilt.end(), tau_star - rho);
            const auto hi = rho >= std::numbers::pi
                                ? tilts.tilt.end()
                                : std::upper_bound(tilts.tilt.begin(), tilts.tilt.end(), tau_star + rho);
            const auto first_index = static_cast<std::size_t>(lo - tilts.tilt.begin());
            const auto last_index = static_cast<std::size_t>(hi - tilts.tilt.begin());
            for (std::size_t q = first_index; q < last_index; ++q) {
                const std::uint32_t f = tilts.order[q];
                const PlacedFlake& flake = flakes[f];
                // The tile's normals have z >= 0 (FlakeOrientation); a flake is two-sided.
                const Vec3 n = flake.normal.z >= 0.0
                                   ? flake.normal
                                   : Vec3{-flake.normal.x, -flake.normal.y, -flake.normal.z};
                const double tau = tilts.tilt[q];
                double delta = std::numbers::pi;  // half-width of the interval of psi
                if (rho < std::numbers::pi) {
                    const double denominator = std::sin(tau) * std::sin(tau_star);
                    const double numerator = cos_rho - std::cos(tau) * std::cos(tau_star);
                    if (denominator < 1e-12) {
                        if (numerator > 0.0) continue;  // the angle is |tau - tau_star| for every psi
                    } else {
                        const double c = numerator / denominator;
                        if (c > 1.0) continue;
                        if (c > -1.0) delta = std::acos(c);
                    }
                }
                const double phi_n = std::atan2(n.y, n.x);
                const double psi_lo = delta >= std::numbers::pi ? 0.0 : phi_n - phi_star - delta;
                const double width = delta >= std::numbers::pi ? kTwoPi : 2.0 * delta;
                // Proposal at the interval's middle (the view there: the beam turned by psi).
                const double psi_mid = psi_lo + 0.5 * width;
                const Vec3 vt = turn(v, std::cos(psi_mid), std::sin(psi_mid));
                const double vn = dot(vt, n);
                const Vec3 r{vt.x - 2.0 * vn * n.x, vt.y - 2.0 * vn * n.y, vt.z - 2.0 * vn * n.z};
                const double depth = -flake.centre.z;
                const double R = tiles[l].kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(vn));
                const double od = beam_depth.at(depth) + (r.z > 0.0 ? exit_depth[k].at(depth) : 1e3);
                int glinting = 0;
                const double step = width / kAzimuthScanBuild;
                const double c_step = std::cos(step);
                const double s_step = std::sin(step);
                double c_m = std::cos(psi_lo + 0.5 * step);
                double s_m = std::sin(psi_lo + 0.5 * step);
                for (int m = 0; m < kAzimuthScanBuild; ++m) {
                    if (glintsAt(v, flake.normal, n_layer, stack.ambient_n, bin, c_m, s_m)) ++glinting;
                    const double c_next = c_m * c_step - s_m * s_step;
                    s_m = s_m * c_step + c_m * s_step;
                    c_m = c_next;
                }
                const double share = (glinting + 0.5) / (kAzimuthScanBuild + 0.5);
                const double weight = tile->flakeAreaUm2(f) * std::abs(vn) / (std::abs(v.z) * L * L) * width /
                                      kTwoPi * share * (std::max(R, 0.0) * std::exp(-od) + 1e-9);
                if (!(weight > 0.0)) continue;
                set.flakes.push_back({static_cast<int>(l), f, psi_lo, width, depth});
                set.cumulative.push_back(weight);  // summed below, after sorting by depth
            }
        }
    }
    for (auto& set : sets) {
        std::vector<std::size_t> order(set.flakes.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            const auto& fa = set.flakes[a];
            const auto& fb = set.flakes[b];
            if (fa.depth != fb.depth) return fa.depth < fb.depth;
            if (fa.layer != fb.layer) return fa.layer < fb.layer;
            return fa.flake < fb.flake;
        });
        std::vector<AzimuthGlint> flakes;
        std::vector<double> cumulative;
        flakes.reserve(order.size());
        cumulative.reserve(order.size());
        double total = 0.0;
        for (std::size_t i : order) {
            flakes.push_back(set.flakes[i]);
            total += set.cumulative[i];
            cumulative.push_back(total);
        }
        set.flakes = std::move(flakes);
        set.cumulative = std::move(cumulative);
    }
    return sets;
}

double azimuthGlintSample(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                          const AzimuthGlintSet& set, const HistogramBin& bin, const GlintUniforms& u,
                          std::int64_t* rays) {
    const double total = set.total();
    if (!(total > 0.0)) return 0.0;
    const auto it = std::upper_bound(set.cumulative.begin(), set.cumulative.end(), u.pick * total);
    const auto index = std::min(static_cast<std::size_t>(it - set.cumulative.begin()), set.flakes.size() - 1);
    const double probability =
        (set.cumulative[index] - (index > 0 ? set.cumulative[index - 1] : 0.0)) / total;
    if (!(probability > 0.0)) return 0.0;
    const AzimuthGlint& g = set.flakes[index];
    const LayerFlakes& lf = tiles[static_cast<std::size_t>(g.layer)];
    const FlakeTile& tile = *lf.tile;
    const PlacedFlake& flake = tile.flakes()[g.flake];
    const Vec3& v0 = set.v_layer[static_cast<std::size_t>(g.layer)];
    const double n_layer = set.n_layer[static_cast<std::size_t>(g.layer)];
    // The glint test on a shifted grid of azimuths over the interval; one glinting azimuth, uniformly.
    // Azimuths psi_0 + m step by the rotation recurrence (exact to rounding over 16 steps).
    int glinting[kAzimuthScan];
    int hits = 0;
    const double step = g.psi_width / kAzimuthScan;
    const double psi_0 = g.psi_lo + step * u.psi;
    const double c_step = std::cos(step);
    const double s_step = std::sin(step);
    double c_m = std::cos(psi_0);
    double s_m = std::sin(psi_0);
    for (int m = 0; m < kAzimuthScan; ++m) {
        if (glintsAt(v0, flake.normal, n_layer, stack.ambient_n, bin, c_m, s_m)) glinting[hits++] = m;
        const double c_next = c_m * c_step - s_m * s_step;
        s_m = s_m * c_step + c_m * s_step;
        c_m = c_next;
    }
    if (hits == 0) return 0.0;
    const double psi = psi_0 + step * glinting[std::min(hits - 1, static_cast<int>(u.choose * hits))];
    const double share = static_cast<double>(hits) / kAzimuthScan;
    const double c = std::cos(psi);
    const double s = std::sin(psi);
    // The view at psi: beam and cone turned by psi over the tile as it is.
    const Vec3 v = turn(v0, c, s);
    const double vn = dot(v, flake.normal);
    const Vec3 r{v.x - 2.0 * vn * flake.normal.x, v.y - 2.0 * vn * flake.normal.y,
                 v.z - 2.0 * vn * flake.normal.z};
    if (!(r.z > 0.0)) return 0.0;
    const Vec3 p = tile.pointOnFlake(g.flake, u.u1, u.u2, u.u3);
    const double depth = -p.z;
    const std::size_t j = sliceAt(stack, g.layer, depth);
    if (j == stack.slices.size()) return 0.0;
    const double R = lf.kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(vn));
    if (!(R > 0.0)) return 0.0;
    const double t_in = straightToAmbient(stack, tiles, j, depth, p.x, p.y, {-v.x, -v.y, -v.z}, rays);
    if (!(t_in > 0.0)) return 0.0;
    const double t_out = straightToAmbient(stack, tiles, j, depth, p.x, p.y, r, rays);
    const double L = tile.sideUm();
    const double weight = tile.flakeAreaUm2(g.flake) * std::abs(vn) / (std::abs(v.z) * L * L);
    return weight * t_in * R * t_out / bin.projected_solid_angle * g.psi_width * share /
           (2.0 * std::numbers::pi * probability);
}

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
    const FlakeTile& tile = *lf.tile;
    const double L = tile.sideUm();
    const double inf = std::numeric_limits<double>::infinity();
    const double slack = 1e-3 + 1e-4 * t_flake;  // µm: far above float rounding, far below a flake's size
    double T = 1.0;
    double travelled = 0.0;
    double t_near = kTileEpsilonUm;
    for (int step = 0; step < kMaxCrossings; ++step) {
        if (x < 0.0 || x > L) x -= L * std::floor(x / L);
        if (y < 0.0 || y > L) y -= L * std::floor(y / L);
        const double tx = u.x > 0.0 ? (L - x) / u.x : (u.x < 0.0 ? -x / u.x : inf);
        const double ty = u.y > 0.0 ? (L - y) / u.y : (u.y < 0.0 ? -y / u.y : inf);
        const double t_side = std::min(tx, ty);
        const double left = t_flake + slack - travelled;
        if (!(left > 0.0)) return 0.0;
        const double t_far = std::min(left, t_side);
        const FlakeHit hit = tile.intersect({x, y, -depth}, u, t_near, t_far);
        if (rays != nullptr) ++*rays;
        if (hit.kind >= 0) {
            if (hit.flake == static_cast<std::int64_t>(target)) return T;
            T *= lf.kinds[static_cast<std::size_t>(hit.kind)].T(std::abs(dot(u, hit.normal)));
            if (!(T > 0.0)) return 0.0;
            x += u.x * hit.t;
            y += u.y * hit.t;
            depth -= u.z * hit.t;
            travelled += hit.t;
            t_near = kTileEpsilonUm;
            continue;
        }
        if (t_side >= left) return 0.0;
        x += u.x * t_side;
        y += u.y * t_side;
        depth -= u.z * t_side;
        travelled += t_side;
        if (tx <= ty)
            x = u.x > 0.0 ? 0.0 : L;
        else
            y = u.y > 0.0 ? 0.0 : L;
        t_near = 0.0;
    }
    return 0.0;
}

// Pigment optical depth of the straight segment between two depths of one
// layer along a direction of cosine |mu| (the slices of a depth profile each at their own extinction).
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
    // (kCostPerImageRay, monte_carlo.cpp) is fitted to measured times.
    if (rays != nullptr) *rays += static_cast<std::int64_t>(tested / 64);
    return sum;
}

}  // namespace paintlab::mc
