#pragma once
// The beam's single reflections off explicit flakes into the exit cones
// (path class BeamFlake, mc_connection.h): the flakes that glint into each
// cone, listed per tile view (GlintSet) or over every azimuth of the tile at
// once (AzimuthGlintSet, the default), and their samples.

#include "flake_tile.h"
#include "mc_connection.h"
#include "mc_random.h"
#include "mc_stack.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

// Per tile realisation and cone: the flakes whose reflection of the beam
// leaves into the cone, with the cumulative weights A |v.n| / (|v_z| L^2).
struct GlintFlake {
    int layer = 0;
    std::size_t flake = 0;
    Vec3 v;  // the beam's direction in the layer (downward)
    Vec3 r;  // its mirror direction off the flake (upward)
    double cos_local = 0.0;
};

struct GlintSet {
    std::vector<GlintFlake> flakes;
    std::vector<double> cumulative;  // ascending; the last is the total weight
    double total() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
};

// The glint sets of one tile realisation for the beam v_in (refracted into
// the top slice) and every bin.
std::vector<GlintSet> glintSets(const PaintStack& stack, std::span<const LayerFlakes> tiles, const Vec3& v_in,
                                std::span<const HistogramBin> bins);

// One sample of the BeamFlake class's f (1/sr) for every bin, times `weight` (added to f_out[k]).
void scoreGlints(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                 std::span<const GlintSet> glints, std::span<const HistogramBin> bins, double weight,
                 PathRng& rng, std::span<double> f_out);

// BeamFlake over all azimuths of a tile (McSettings::glint_azimuths, the default).
//
// The flake statistics are isotropic, so the tile turned by any azimuth psi is
// as valid a realisation as the tile itself (the views of mc_job_runner.cpp
// take 32 of them). The glint term of the tile averaged over every psi,
//   G = (1/2pi) int dpsi sum_i w_i(psi) <g_i(psi)> 1[flake i glints into the cone at psi],
// with w_i = A_i |v.n| / (|v_z| L^2) and <g_i> the mean over the flake's
// polygon of t_in R t_out (as scoreGlints), is estimated directly:
//  - per bin and layer, the normals whose mirror direction of the beam leaves
//    into the cone lie in a spherical cap around the half-vector of the
//    cone's axis (radius from 64 points of the cone's edge plus twice the
//    largest gap between their images: a superset); a flake of tilt tau meets
//    the cap, turned by psi, on one interval of psi (closed form), listed from
//    the flakes sorted by tilt (TiltIndex, built once per tile for every band);
//  - a sample picks a listed flake with probability proportional to
//    w_i R(|v.n|) exp(-optical depth of beam and exit to the flake's centre,
//    pigments and the layer's mean flake extinction) times the part of its
//    interval where it glints (16 points) (importance sampling: deep flakes
//    are dark under the demo's carbon black; it cut the per-sample relative
//    variance near the specular direction from ~2.4 to 0.1-0.4); then the
//    exact glint test at 16 azimuths of a randomly shifted grid over the
//    interval, one of the glinting ones drawn uniformly (score times the
//    glinting share: unbiased, and no sample is lost where the cap is wider
//    than the glint), a point uniform on the polygon, and the traces through
//    the real tile; divided by the probability density: unbiased for G
//    whatever the proposal, which only has to be positive where the
//    integrand is;
//  - the flakes are listed by depth, so that stratified picks (one per
//    stratum of the cumulative weight) spread over depths.
// No view enters: the tile-to-tile spread of G is that of the tile itself,
// not of 32 sampled azimuths (at 45as110 a view held ~1 glinting flake).
struct TiltIndex {
    std::vector<std::uint32_t> order;  // flake indices by ascending tilt
    std::vector<double> tilt;          // their tilts (radians), ascending
    // What azimuthGlintSets reads of each flake, in the same order: read
    // through `order`, the tile's flakes were a cache miss per flake listed.
    struct Entry {
        Vec3 normal_up;  // the normal turned to z >= 0 (a flake is two-sided)
        double depth_um = 0.0;
        double area_um2 = 0.0;
        int kind = 0;
    };
    std::vector<Entry> entries;
    // A lateral grid of the same flakes (reflectedBeams' candidates): cells x
    // cells squares of side cell_um over the tile, cell c = row * cells + column
    // holding cell_flakes[cell_start[c] .. cell_start[c + 1]) (by the centre's
    // position), each cell by ascending tilt (cell_tilts).
    int cells = 0;
    double cell_um = 0.0;
    double max_radius_um = 0.0;
    std::vector<std::uint32_t> cell_start;
    std::vector<std::uint32_t> cell_flakes;
    std::vector<double> cell_tilts;
};
TiltIndex tiltIndex(const FlakeTile& tile);

struct AzimuthGlint {
    int layer = 0;
    std::uint32_t flake = 0;
    double psi_lo = 0.0;     // the interval of view azimuths (radians) where it may glint
    double psi_width = 0.0;  // in (0, 2 pi]
    double depth = 0.0;      // of its centre (µm), the listing order
};

struct AzimuthGlintSet {
    std::vector<AzimuthGlint> flakes;  // by depth
    std::vector<double> cumulative;    // of the proposal weights; the last is the total
    std::vector<Vec3> v_layer;         // the unturned beam in each layer (downward; z = 0: none)
    std::vector<double> n_layer;       // each layer's binder index
    double total() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
};

// The sets of one tile realisation (layers without a tile or its TiltIndex are left out)
// for the unturned beam v_in (refracted into the top slice) and every bin (unturned).
std::vector<AzimuthGlintSet> azimuthGlintSets(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                                              const Vec3& v_in, std::span<const HistogramBin> bins);

// cos and sin of delta / 8 from cos delta (delta in [0, pi]) by the
// half-angle formulas, square roots only: azimuthGlintSets' scan of a
// flake's azimuth interval takes its steps from them.
struct CosSin {
    double c = 1.0;
    double s = 0.0;
};
CosSin eighthOfAngle(double cos_delta);

// Uniforms of one sample: the pick (stratified by the caller), the azimuth
// within the interval and the point on the polygon (pointOnFlake's three);
// with `moved`, the flake's new place in the tile (McSettings::move_glint_flakes).
struct GlintUniforms {
    double pick = 0.0, psi = 0.0, choose = 0.0, u1 = 0.0, u2 = 0.0, u3 = 0.0;
    bool moved = false;
    double move_x = 0.0, move_y = 0.0;
};

// One sample of bin k's BeamFlake f (1/sr) from its set (0 when the set is empty).
//
// Moved flakes (u.moved): the tiles place their flakes independently and
// uniformly over the tile (without reject_overlaps), so flake i's place is
// independent of its normal, its depth and every other flake. The sample
// may then put the picked flake at a new uniform place, traced through the
// tile without it (AbsentFlake): the same expectation over tiles, but the
// flakes above a glinting one change from sample to sample. Without it each
// tile's glint term keeps its own flakes' shadows, a spread between tiles
// that no path count lowers (docs/PERFORMANCE.md, "The glints' spread
// between tiles"); with it that spread becomes the samples' own variance.
double azimuthGlintSample(const PaintStack& stack, std::span<const LayerFlakes> tiles,
                          const AzimuthGlintSet& set, const HistogramBin& bin, const GlintUniforms& u,
                          std::int64_t* rays = nullptr);

}  // namespace paintlab::mc
