#include "first_flake.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace paintlab::mc {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Azimuth bin of a direction's horizontal part (radians in [0, 2 pi) cut into kAzimuthBins).
int azimuthBin(double x, double y) {
    double phi = std::atan2(y, x);
    if (phi < 0.0) phi += kTwoPi;
    const int bin = static_cast<int>(phi / kTwoPi * FlakeGroups::kAzimuthBins);
    return std::clamp(bin, 0, FlakeGroups::kAzimuthBins - 1);
}

double rho(const FirstFlakeProposal& proposal, int key) {
    const auto k = static_cast<std::size_t>(key);
    return k < proposal.h.size() ? proposal.h[k] : proposal.rho_default;
}

}  // namespace

FlakeGroups flakeGroups(const FlakeTile& tile, const TiltIndex& tilts, double top_um, double bottom_um) {
    FlakeGroups groups;
    const auto& flakes = tile.flakes();
    // Tilt quantiles from the tile's sorted tilts: upper edges of bins 0 .. kTiltBins - 2.
    std::vector<double> edges;
    for (int q = 1; q < FlakeGroups::kTiltBins; ++q)
        edges.push_back(
            tilts.tilt.empty()
                ? 0.0
                : tilts.tilt[tilts.tilt.size() * static_cast<std::size_t>(q) / FlakeGroups::kTiltBins]);
    const double thickness = std::max(bottom_um - top_um, 1e-12);
    std::vector<int> group_of(flakes.size());
    for (std::size_t i = 0; i < flakes.size(); ++i) {
        const PlacedFlake& f = flakes[i];
        const double tilt = std::acos(std::clamp(std::abs(f.normal.z), 0.0, 1.0));
        const int t = static_cast<int>(std::upper_bound(edges.begin(), edges.end(), tilt) - edges.begin());
        const double up = f.normal.z < 0.0 ? -1.0 : 1.0;
        const int a = azimuthBin(up * f.normal.x, up * f.normal.y);
        const double depth = -f.centre.z;
        const int d = std::clamp(static_cast<int>((depth - top_um) / thickness * FlakeGroups::kDepthBins), 0,
                                 FlakeGroups::kDepthBins - 1);
        group_of[i] = FlakeGroups::group(t, a, d);
    }
    groups.start.assign(FlakeGroups::kGroups + 1, 0);
    for (const int g : group_of) ++groups.start[static_cast<std::size_t>(g) + 1];
    for (int g = 0; g < FlakeGroups::kGroups; ++g)
        groups.start[static_cast<std::size_t>(g) + 1] += groups.start[static_cast<std::size_t>(g)];
    groups.flakes.resize(flakes.size());
    groups.cumulative_area.resize(flakes.size());
    groups.area.assign(FlakeGroups::kGroups, 0.0);
    std::vector<std::uint32_t> fill(groups.start.begin(), groups.start.end() - 1);
    for (std::size_t i = 0; i < flakes.size(); ++i) {  // ascending index within each group: deterministic
        const auto g = static_cast<std::size_t>(group_of[i]);
        const std::uint32_t at = fill[g]++;
        groups.flakes[at] = static_cast<std::uint32_t>(i);
        groups.area[g] += tile.flakeAreaUm2(i);
        groups.cumulative_area[at] = groups.area[g];
    }
    return groups;
}

FirstFlakeTable firstFlakeTable(std::span<const LayerFlakes> tiles, const Vec3& v_top,
                                const FirstFlakeProposal& proposal) {
    FirstFlakeTable table;
    // The view's beam azimuth as a whole number of bins: group (t, a, d) of the
    // tile then has relative azimuth bin a - shift for every flake's key.
    const int shift =
        static_cast<int>(
            std::floor((std::atan2(v_top.y, v_top.x) + kTwoPi) / kTwoPi * FlakeGroups::kAzimuthBins + 0.5)) %
        FlakeGroups::kAzimuthBins;
    double area_total = 0.0;
    double h_total = 0.0;
    std::vector<double> areas;
    std::vector<double> learned_weights;  // A_G rho_key
    for (std::size_t l = 0; l < tiles.size(); ++l) {
        const FlakeGroups* groups = tiles[l].groups;
        if (groups == nullptr) continue;
        for (int t = 0; t < FlakeGroups::kTiltBins; ++t)
            for (int a = 0; a < FlakeGroups::kAzimuthBins; ++a)
                for (int d = 0; d < FlakeGroups::kDepthBins; ++d) {
                    const int g = FlakeGroups::group(t, a, d);
                    const int relative = (a - shift + FlakeGroups::kAzimuthBins) % FlakeGroups::kAzimuthBins;
                    const int key =
                        static_cast<int>(l) * FlakeGroups::kGroups + FlakeGroups::group(t, relative, d);
                    const double area = groups->area[static_cast<std::size_t>(g)];
                    const double h = area * rho(proposal, key);
                    area_total += area;
                    h_total += h;
                    areas.push_back(area);
                    learned_weights.push_back(h);
                    table.key.push_back(key);
                }
    }
    if (!(area_total > 0.0)) return {};
    table.area_total = area_total;
    const double learned = h_total > 0.0 ? 1.0 - kDefensiveShare : 0.0;
    double running = 0.0;
    for (std::size_t e = 0; e < areas.size(); ++e) {
        running += (1.0 - learned) * areas[e] / area_total +
                   (h_total > 0.0 ? learned * learned_weights[e] / h_total : 0.0);
        table.cumulative.push_back(running);
    }
    return table;
}

FirstFlakeDraw drawFirstFlake(std::span<const LayerFlakes> tiles, const FirstFlakeTable& table,
                              double u_group, double u_flake, double u1, double u2, double u3) {
    if (table.cumulative.empty()) return {};
    const double total = table.cumulative.back();
    const auto it = std::upper_bound(table.cumulative.begin(), table.cumulative.end(), u_group * total);
    const auto e =
        std::min(static_cast<std::size_t>(it - table.cumulative.begin()), table.cumulative.size() - 1);
    const double probability = (table.cumulative[e] - (e > 0 ? table.cumulative[e - 1] : 0.0)) / total;
    if (!(probability > 0.0)) return {};
    // The key names the layer; entries run over each layer's groups in order.
    const auto l = static_cast<std::size_t>(table.key[e] / FlakeGroups::kGroups);
    const FlakeGroups& groups = *tiles[l].groups;
    // The group's own index in the tile's frame (entries run over t, a, d as the groups do).
    const std::size_t g = e % FlakeGroups::kGroups;
    const std::uint32_t begin = groups.start[g];
    const std::uint32_t end = groups.start[g + 1];
    if (begin == end) return {};
    const double area = groups.area[g];
    const auto first = groups.cumulative_area.begin() + begin;
    const auto last = groups.cumulative_area.begin() + end;
    const auto at = std::min(static_cast<std::size_t>(std::upper_bound(first, last, u_flake * area) - first),
                             static_cast<std::size_t>(end - begin - 1));
    FirstFlakeDraw draw;
    draw.layer = static_cast<int>(l);
    draw.flake = groups.flakes[begin + at];
    draw.point = tiles[l].tile->pointOnFlake(draw.flake, u1, u2, u3);
    draw.probability = probability;
    draw.area_over_probability = area / probability;
    draw.natural_over_probability = area / table.area_total / probability;
    draw.key = table.key[e];
    return draw;
}

}  // namespace paintlab::mc
