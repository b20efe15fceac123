#pragma once
// First-flake walks (McSettings::first_flake_walks): the delta chains that
// begin with the beam's reflection off an explicit flake (beam -> A -> B -> C
// -> cone, beam -> A -> top -> C -> cone), started on that flake instead of
// at a uniform entry point.
//
// Why: in the pearlescent demo at 45as110 nearly all of the delta-chain
// walks' variance came from three-flake chains whose first flake leans
// towards the light source (docs/PERFORMANCE.md, "First-flake walks"). A
// uniform entry point finds such a flake no more often than any other. Here
// the first flake A is drawn from groups of the tile's flakes (tilt quantile,
// azimuth of the normal relative to the beam, depth third) with probabilities
// P_G learned from the walks so far, a point uniform on its polygon; the beam
// is traced down to the point (its transmittance), reflected, and the walk
// goes on as a delta-chain walk (mc_walk.h, traceFromFirstFlake).
//
// Unbiased for any P_G > 0: a uniform entry point p of the top slice whose
// beam first reflects off A at a point of A has, under this sampling, the
// density P_G |v_z| / (A_G |v.n_A|) (the beam's cross-section is the same on
// the entry plane, |v_z| dp, and on the flake, |v.n| dA; A_G the group's
// area), so the walk's weight carries A_G |v.n_A| / (L^2 P_G |v_z|) against
// the uniform walk's 1 / L^2. A share of P_G (kDefensiveShare) stays
// proportional to A_G, so a group the learning missed costs at most a
// constant factor of variance, never bias.
//
// Off by default: on the demo they lower the delta walks' variance per walk
// but not the stop rule's time (docs/PERFORMANCE.md, "First-flake walks").

#include "flake_tile.h"
#include "mc_connection.h"
#include "mc_glints.h"

#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

// One tile's flakes by group: tilt (kTiltBins quantiles of the tile's own
// tilts, so any orientation spread fills them), azimuth of the upward normal
// in the tile's frame (kAzimuthBins), depth in the layer (kDepthBins).
struct FlakeGroups {
    static constexpr int kTiltBins = 8;
    static constexpr int kAzimuthBins = 16;
    static constexpr int kDepthBins = 3;
    static constexpr int kGroups = kTiltBins * kAzimuthBins * kDepthBins;
    static int group(int tilt, int azimuth, int depth) {
        return (tilt * kAzimuthBins + azimuth) * kDepthBins + depth;
    }

    std::vector<std::uint32_t> start;  // group g's flakes are flakes[start[g] .. start[g + 1])
    std::vector<std::uint32_t> flakes;
    std::vector<double> cumulative_area;  // running polygon area within each group (µm^2)
    std::vector<double> area;             // per group (µm^2)
};
FlakeGroups flakeGroups(const FlakeTile& tile, const TiltIndex& tilts, double top_um, double bottom_um);

// Part of P_G that stays proportional to the group's area: a walk's weight is
// then at most 1 / kDefensiveShare times the area-proportional one (2x). The
// demo's stop rule took as long on average with 0.25 (10 seeds) and 0.5 (20
// seeds), two runs over 10 s each (docs/PERFORMANCE.md, "First-flake walks");
// 0.5 for the tighter bound on the weights.
constexpr double kDefensiveShare = 0.5;

// Learned factors rho per (layer, tilt bin, azimuth bin relative to the beam,
// depth bin): key(layer, group of a view) = layer * kGroups + the group with
// its azimuth bin shifted by the view's beam azimuth; the learned part of P_G
// is proportional to A_G rho_key (rho_default for keys beyond h). Empty: P_G
// is proportional to the area alone (the uniform walk's own distribution of
// first flakes, up to |v.n|).
struct FirstFlakeProposal {
    std::vector<double> h;  // rho per key, >= 0
    double rho_default = 0.0;
};

// The groups' probabilities for one view: P_G per (layer, group), layer-major,
// as cumulative sums (the last is 1); empty when no layer has groups.
struct FirstFlakeTable {
    std::vector<double> cumulative;
    std::vector<int> key;     // per entry: its proposal key
    double area_total = 0.0;  // of every group (µm^2)
};
FirstFlakeTable firstFlakeTable(std::span<const LayerFlakes> tiles, const Vec3& v_top,
                                const FirstFlakeProposal& proposal);

// A drawn first flake: its layer and index, the point on it, and the factor
// A_G / P_G of the walk's weight; key: the proposal key of its group.
struct FirstFlakeDraw {
    int layer = -1;
    std::uint32_t flake = 0;
    Vec3 point;
    double probability = 0.0;  // P_G
    double area_over_probability = 0.0;
    // (A_G / sum of areas) / P_G: the weight's factor against the area-proportional
    // draw, by which the walk's roulette threshold is scaled (the same chains
    // then reach the same depth whatever P_G).
    double natural_over_probability = 0.0;
    int key = -1;
};
FirstFlakeDraw drawFirstFlake(std::span<const LayerFlakes> tiles, const FirstFlakeTable& table,
                              double u_group, double u_flake, double u1, double u2, double u3);

}  // namespace paintlab::mc
