#include "mc_glints.h"

#include "paintlab/engine/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace paintlab::mc {

namespace {

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
constexpr int kAzimuthScanBuild = 8;  // and per listed flake for its proposal weight (even)
constexpr double kCosPiOver8 = 0.92387953251128675613;  // the whole circle's half step
constexpr double kSinPiOver8 = 0.38268343236508977173;

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

CosSin eighthOfAngle(double cos_delta) {
    const double c = std::clamp(cos_delta, -1.0, 1.0);
    const double c2 = std::sqrt(0.5 * (1.0 + c));  // delta / 2, in [0, pi / 2]
    const double s2 = std::sqrt(0.5 * (1.0 - c));
    const double c4 = std::sqrt(0.5 * (1.0 + c2));  // delta / 4: sin x = sin 2x / (2 cos x)
    const double s4 = s2 / (2.0 * c4);
    const double c8 = std::sqrt(0.5 * (1.0 + c4));  // delta / 8
    return {c8, s4 / (2.0 * c8)};
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
    for (std::uint32_t i : order) {
        index.tilt.push_back(tilt[i]);
        const PlacedFlake& f = flakes[i];
        const Vec3 up = f.normal.z >= 0.0 ? f.normal : Vec3{-f.normal.x, -f.normal.y, -f.normal.z};
        index.entries.push_back({up, -f.centre.z, tile.flakeAreaUm2(i), f.kind});
    }
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
            // The cap's axis as cosines, read off the unit axis as a flake's are off
            // its normal below: cos and sin of tau_star and its azimuth's unit vector
            // (any when the axis is the normal: the cap is then a tilt band).
            const double cos_tau_star = std::clamp(n_star.z, -1.0, 1.0);
            const double sin_tau_star = std::sqrt(n_star.x * n_star.x + n_star.y * n_star.y);
            const double cos_phi_star = sin_tau_star > 0.0 ? n_star.x / sin_tau_star : 1.0;
            const double sin_phi_star = sin_tau_star > 0.0 ? n_star.y / sin_tau_star : 0.0;
            const auto lo = std::lower_bound(tilts.tilt.begin(), tilts.tilt.end(), tau_star - rho);
            const auto hi = rho >= std::numbers::pi
                                ? tilts.tilt.end()
                                : std::upper_bound(tilts.tilt.begin(), tilts.tilt.end(), tau_star + rho);
            const auto first_index = static_cast<std::size_t>(lo - tilts.tilt.begin());
            const auto last_index = static_cast<std::size_t>(hi - tilts.tilt.begin());
            for (std::size_t q = first_index; q < last_index; ++q) {
                const std::uint32_t f = tilts.order[q];
                const TiltIndex::Entry& flake = tilts.entries[q];
                const Vec3& n = flake.normal_up;
                // cos and sin of its tilt from the normal itself (no trigonometry per flake).
                const double sin_tau = std::sqrt(n.x * n.x + n.y * n.y);
                const double cos_tau = n.z;
                // cos of the half-width delta of the interval of psi (-1: every azimuth).
                double cos_delta = -1.0;
                if (rho < std::numbers::pi) {
                    const double denominator = sin_tau * sin_tau_star;
                    const double numerator = cos_rho - cos_tau * cos_tau_star;
                    if (denominator < 1e-12) {
                        if (numerator > 0.0) continue;  // the angle is |tau - tau_star| for every psi
                    } else {
                        const double c = numerator / denominator;
                        if (c > 1.0) continue;
                        if (c > -1.0) cos_delta = c;
                    }
                }
                const bool whole_circle = !(cos_delta > -1.0);
                const double delta = whole_circle ? std::numbers::pi : std::acos(cos_delta);
                const double phi_n = std::atan2(n.y, n.x);
                const double psi_lo = whole_circle ? 0.0 : phi_n - phi_star - delta;
                const double width = whole_circle ? kTwoPi : 2.0 * delta;
                // Proposal at the interval's middle (the view there: the beam turned by
                // psi_mid = phi_n - phi_star, or pi for the whole circle), and the scan of
                // kAzimuthScanBuild azimuths psi_mid +- (k + 1/2) step, step = width / 8 =
                // delta / 4: their cosines by the half-angle formulas from cos delta.
                double c_mid = -1.0;
                double s_mid = 0.0;
                double c_half = kCosPiOver8;  // of step / 2
                double s_half = kSinPiOver8;
                if (!whole_circle) {
                    const double c_n = n.x / sin_tau;
                    const double s_n = n.y / sin_tau;
                    c_mid = c_n * cos_phi_star + s_n * sin_phi_star;
                    s_mid = s_n * cos_phi_star - c_n * sin_phi_star;
                    const CosSin eighth = eighthOfAngle(cos_delta);
                    c_half = eighth.c;
                    s_half = eighth.s;
                }
                const double c_step = c_half * c_half - s_half * s_half;
                const double s_step = 2.0 * s_half * c_half;
                const Vec3 vt = turn(v, c_mid, s_mid);
                const double vn = dot(vt, n);
                const Vec3 r{vt.x - 2.0 * vn * n.x, vt.y - 2.0 * vn * n.y, vt.z - 2.0 * vn * n.z};
                const double depth = flake.depth_um;
                const double R = tiles[l].kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(vn));
                const double od = beam_depth.at(depth) + (r.z > 0.0 ? exit_depth[k].at(depth) : 1e3);
                int glinting = 0;
                double c_up = c_mid * c_half - s_mid * s_half;  // psi_mid + step / 2
                double s_up = s_mid * c_half + c_mid * s_half;
                double c_down = c_mid * c_half + s_mid * s_half;  // psi_mid - step / 2
                double s_down = s_mid * c_half - c_mid * s_half;
                for (int m = 0; m < kAzimuthScanBuild / 2; ++m) {
                    if (glintsAt(v, n, n_layer, stack.ambient_n, bin, c_up, s_up)) ++glinting;
                    if (glintsAt(v, n, n_layer, stack.ambient_n, bin, c_down, s_down)) ++glinting;
                    const double c_up_next = c_up * c_step - s_up * s_step;
                    s_up = s_up * c_step + c_up * s_step;
                    c_up = c_up_next;
                    const double c_down_next = c_down * c_step + s_down * s_step;
                    s_down = s_down * c_step - c_down * s_step;
                    c_down = c_down_next;
                }
                const double share = (glinting + 0.5) / (kAzimuthScanBuild + 0.5);
                const double weight = flake.area_um2 * std::abs(vn) / (std::abs(v.z) * L * L) * width /
                                      kTwoPi * share * (std::max(R, 0.0) * std::exp(-od) + 1e-9);
                if (!(weight > 0.0)) continue;
                set.flakes.push_back({static_cast<int>(l), f, psi_lo, width, depth});
                set.cumulative.push_back(weight);  // summed below, after sorting by depth
            }
        }
    }
    // Each set by depth (then layer and flake: a total order), sorted on
    // copied keys rather than through an index into the set.
    struct DepthKey {
        double depth;
        int layer;
        std::uint32_t flake;
        std::size_t at;
    };
    std::vector<DepthKey> keys;
    for (auto& set : sets) {
        keys.clear();
        keys.reserve(set.flakes.size());
        for (std::size_t i = 0; i < set.flakes.size(); ++i)
            keys.push_back({set.flakes[i].depth, set.flakes[i].layer, set.flakes[i].flake, i});
        std::sort(keys.begin(), keys.end(), [](const DepthKey& a, const DepthKey& b) {
            if (a.depth != b.depth) return a.depth < b.depth;
            if (a.layer != b.layer) return a.layer < b.layer;
            return a.flake < b.flake;
        });
        std::vector<AzimuthGlint> flakes;
        std::vector<double> cumulative;
        flakes.reserve(keys.size());
        cumulative.reserve(keys.size());
        double total = 0.0;
        for (const DepthKey& key : keys) {
            flakes.push_back(set.flakes[key.at]);
            total += set.cumulative[key.at];
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
    Vec3 p = tile.pointOnFlake(g.flake, u.u1, u.u2, u.u3);
    const double L = tile.sideUm();
    AbsentFlake absent;
    if (u.moved) {
        p.x += u.move_x * L;
        p.y += u.move_y * L;
        absent = {g.layer, static_cast<std::int64_t>(g.flake)};
    }
    const double depth = -p.z;
    const std::size_t j = sliceAt(stack, g.layer, depth);
    if (j == stack.slices.size()) return 0.0;
    const double R = lf.kinds[static_cast<std::size_t>(flake.kind)].R(std::abs(vn));
    if (!(R > 0.0)) return 0.0;
    const double t_in =
        straightToAmbient(stack, tiles, j, depth, p.x, p.y, {-v.x, -v.y, -v.z}, rays, nullptr, absent);
    if (!(t_in > 0.0)) return 0.0;
    const double t_out = straightToAmbient(stack, tiles, j, depth, p.x, p.y, r, rays, nullptr, absent);
    const double weight = tile.flakeAreaUm2(g.flake) * std::abs(vn) / (std::abs(v.z) * L * L);
    return weight * t_in * R * t_out / bin.projected_solid_angle * g.psi_width * share /
           (2.0 * std::numbers::pi * probability);
}

}  // namespace paintlab::mc
