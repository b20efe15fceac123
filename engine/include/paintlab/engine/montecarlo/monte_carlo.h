#pragma once
// The full model (shared/ARCHITECTURE.md, "The full model"): Monte Carlo
// radiative transfer in a layered paint, one wavelength at a time, as the
// independent check of the fast model (layered_brdf.h).
//
// Physics (monte_carlo.cpp and mc_walk.cpp have the details):
//  - a collimated beam enters through the smooth top interface (Fresnel
//    reflection / refraction between the ambient and the top binder);
//  - in each layer the binder with its pigments (and raw media) is a
//    participating medium: free paths by sigma_t, Henyey-Greenstein scattering
//    with the exact lobe mixture of SlabOptics (no delta-M), absorption by
//    weighting with Russian roulette;
//  - flakes are either (default) a continuum of oriented two-sided
//    reflectors with the fast model's statistics (area density,
//    FlakeOrientation, reflectance and thin-film transmittance at the local
//    angle) sampled per collision, or (explicit_flakes) real flat flakes of
//    the recipe's diameter in a laterally periodic tile per layer, traced
//    with Embree, rays wrapping at the tile's sides;
//  - internal interfaces refract / reflect where the binder index changes;
//    the substrate is Lambertian, black, a metal mirror (complex Fresnel) or
//    transparent (what crosses it is lost);
//  - a depth-varying concentration is a stack of homogeneous slices.
//
// Estimators, each with its standard error:
//  - albedo(wi): directional-hemispherical reflectance, the top interface's
//    mirror term included (as LayeredBrdf::albedo);
//  - transmittance(wi): what crosses into a transparent substrate (the
//    unscattered beam included), 0 for the other substrates;
//  - f(wi, wo) by next-event (point) estimation: from every scattering vertex
//    the radiance that reaches wo through the stack's smooth interfaces along
//    the one direction that refracts into wo (straight up, or down and back by
//    specular reflections below, summed in closed form), with the radiance
//    law L / n^2 and the (1 - R) factors; the top interface's mirror term is
//    excluded (as LayeredBrdf::eval);
//  - or, with histogram_cone_deg > 0 (always with explicit flakes, whose
//    mirror reflections are deltas that next-event estimation cannot reach),
//    the escaping weight in a cone of that half-angle around wo over the
//    cone's projected solid angle: the cone average of f cos over that of cos;
//    with explicit flakes and `connections` (default) the paths whose last
//    direction change was a pigment or the Lambertian substrate, and the
//    beam's single flake reflections (averaged over every azimuth of each
//    tile), are scored by exact connections to the cone through the real
//    tiles instead (mc_connection.h), same mean; the walk splits at flakes and
//    at the top interface instead of choosing a branch (split_branches); most
//    of the rest (multiple reflections) by reverse walks from the cone and
//    delta-chain walks without collisions (reverse_walks, delta_walks,
//    reflected_beams, top_images);
//  - a whole table on the fast model's basis: mc_table.h.
//
// Standard errors: over independent paths, except with explicit flakes,
// where the paths are split into `batches`, each tracing its own tile
// realisation, and the error is that of the batches' means (batches - 1
// degrees of freedom): it then includes the randomness of the flake
// arrangement, which at a few hundred flakes per tile is several times the
// path error (tests/engine/montecarlo/test_flake_tiles.cpp).
//
// Determinism: path p of (band b, incidence i) draws from a generator seeded
// by (seed, b, i, p) alone, chunk c of paths belongs to batch c mod batches
// and tile k of a layer is seeded by (seed, layer, k); chunks are merged in
// order, so the numbers do not depend on the thread count or scheduling.
// Stopping by time only changes how many chunks are merged.
//
// Known limits: the tile is periodic (its side is set by tile_flakes, at
// least two flake diameters), so arrangements longer-ranged than the tile are
// not represented; its geometry is float (Embree); flakes are thickness-less
// 16-gons (or exact disks: flake_polygon_sides) and overlap unless reject_overlaps. What the connections and
// the reverse / delta-chain walks leave to the histogram (a flake reflection followed by a top reflection or
// more flakes before a pigment vertex, then a flake) sets the cost of explicit flakes at the flop
// (docs/PERFORMANCE.md). Settings.threads sets TBB's process-wide parallelism for the duration of the call.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/layered_brdf.h"
#include "paintlab/engine/recipe.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace paintlab::mc {

struct McSettings {
    std::uint64_t seed = 1;
    // Stop for every (band, incidence) at the first of: max_paths paths; all
    // its estimates at or below target_rel_error (relative standard error;
    // 0 = off; checked after each round of chunks); its share of max_seconds
    // (0 = off; the budget is divided evenly over bands x incidences).
    std::int64_t max_paths = 100000;
    double target_rel_error = 0.0;
    double max_seconds = 0.0;
    int chunk_paths = 1024;     // paths per deterministic chunk
    int chunks_per_round = 16;  // chunks run in parallel between stop checks
    int slices = 16;            // slices per layer with a depth-varying concentration
    int max_events = 1000000;   // safety cap on collisions per path (a biased cut, never reached in practice)
    double roulette_weight = 0.1;  // Russian roulette below this weight
    int threads = 0;               // 0: TBB's default (all cores)
    // Estimator of f: 0 = next-event; > 0 = histogram over cones of this half-angle (degrees).
    double histogram_cone_deg = 0.0;
    // Explicit flakes (Embree tile per layer); needs histogram_cone_deg > 0.
    bool explicit_flakes = false;
    int tile_flakes = 20000;       // flakes per tile aimed at (sets the tile's side, >= 2 diameters)
    int max_tile_flakes = 200000;  // per kind and layer
    // Explicit flakes: a flake that intersects one already placed (thickness-less
    // disks, periodic images included) is moved elsewhere (flake_tile.h).
    bool reject_overlaps = false;
    // Explicit flakes' shape: regular polygons of the disk's area with this many
    // sides (16 by default; the polygon's edge is ~1 % of its radius from the
    // disk's), or 0 for exact disks (flake_tile.h).
    int flake_polygon_sides = 16;
    // The paths of each (band, incidence) are split by chunk into this many
    // batches (chunk c into batch c mod batches). With explicit flakes every
    // batch traces its own tile realisation (own seed), and the standard errors
    // are those of the batches' means (batches - 1 degrees of freedom), so they
    // include the randomness of the flake arrangement; otherwise they are over
    // paths. tabulateMonteCarlo (mc_table.h) also keeps one table per batch.
    // 16 (8 before 2026-12-03): the tiles' own spread is then half as large
    // (measured on the demo: as large as the paths' error at the near-specular
    // cones with 8 tiles), and an error from 15 degrees of freedom scatters by
    // ~18 % instead of ~27 %, so the stop rule stops less often on a low draw.
    int batches = 16;
    // Explicit flakes: score the path classes that allow it by connections
    // instead of the histogram (mc_connection.h): next-event estimation from
    // pigment and Lambertian vertices through the tiles into each cone, and
    // the beam's single reflections off the tile's flakes listed per cone.
    // Same expectation (the cone average), far smaller variance; false: the
    // histogram alone (the estimator before 2026-12).
    bool connections = true;
    // Explicit flakes: every tile is traced at this many azimuths of the
    // incidence plane (path p at view p mod tile_views; evenly spaced, with
    // a random offset per batch). The flake statistics are isotropic in
    // azimuth, so each view is as valid a realisation as the tile itself
    // (only the periodic lattice turns with it), and the average over views
    // removes most of the spread between tiles where few flakes glint into
    // a cone. 1: the tile in its own frame only (the estimator before 2026-12).
    int tile_views = 32;
    // Explicit flakes with connections: the share of paths (drawn at random,
    // in [1e-3, 1]) that run them, their scores divided by it (unbiased). The
    // connections cost ~10 shadow rays per path and their own noise is small,
    // while the histogram's share (multiple flake reflections) needs many
    // paths: fewer connected paths buy more paths per second. With
    // glint_azimuths, a value x above 1 (up to 64) runs the next-event
    // connections on every path and raises each pigment collision's chance to
    // run them from sigma_s / sigma (the chance that it scatters) to
    // min(1, x sigma_s / sigma) (mc_walk.h, PathContext::nee_boost): with an
    // absorbing pigment (the demo's carbon black) the scores are otherwise
    // zero on all but 0.5-3 % of the collisions. adaptive_fractions then sets
    // x per cone from the first round on.
    double connection_fraction = 0.125;
    // Explicit flakes with connections: the beam's single flake reflections
    // (class BeamFlake) estimated over every azimuth of each tile at once, the
    // flake drawn by importance (its reflectance and the attenuation down to
    // it), the samples drawn per chunk of paths and stratified over it
    // (mc_connection.h, azimuthGlintSets); false: per view of the tile, one
    // flake per connected path in proportion to its area (the estimator of
    // 2026-12-01; adaptive_fractions then does not apply). The stratified
    // samples tie the paths of a chunk together: errors over batches are
    // exact, errors over paths (batches = 1) conservative.
    bool glint_azimuths = true;
    // Explicit flakes with connections and glint_azimuths: per exit cone, the
    // next-event rate (share of paths, or beyond 1 the collisions' boost; see
    // connection_fraction), the glint samples and the reverse walks per path,
    // and the delta-chain walks per path, chosen after every round of chunks
    // from each cone's own variance so far and a cost model of counted work
    // (monte_carlo.cpp); the first round uses connection_fraction, and its
    // paths are then dropped from the estimate when they are a small part of
    // the job (they only set the rates). Unbiased: a path's rates are fixed
    // before it runs. false: connection_fraction for every cone.
    bool adaptive_fractions = true;
    // Explicit flakes: a path follows both branches wherever an explicit flake
    // reflects or passes it (weights R and T) and where the top interface
    // reflects or lets it out (weights F and 1 - F), instead of drawing one
    // with those probabilities; at most 6 splits deep along a branch, Russian
    // roulette below roulette_weight as always. Same expectation; the chains of
    // several flake reflections (class Other, what limits the explicit-flake
    // estimate, docs/PERFORMANCE.md) are no longer thinned by the product of
    // their reflectances. Lossless paint then no longer returns exactly 1 per
    // path (the roulette of the split-off branches). false: the analog choice.
    bool split_branches = true;
    // Explicit flakes with connections: the paths of class Other whose first
    // direction change was a pigment (or the Lambertian substrate), such as
    // beam -> pigment -> flake -> cone, the part that limited the flop
    // geometries, are scored by reverse walks from the cone (reciprocity;
    // mc_walk.h, traceReversePath) instead of the histogram. false: the histogram.
    bool reverse_walks = true;
    // Reverse walks per path and cone in the first round (adaptive_fractions then sets them per cone).
    double reverse_rate = 0.125;
    // Reverse walks: their pigment vertices also connect to the beam's single
    // mirror images off the explicit flakes of their layer (a flat flake keeps
    // the beam collimated; mc_connection.h, reflectedBeams), which scores the
    // forward paths beam -> flake -> pigment -> ... -> delta -> cone
    // (histogram_other bit 8) instead of the histogram.
    bool reflected_beams = true;
    // Reverse walks: their pigment vertices also connect to the beam's images
    // off an explicit flake of their layer and then the paint's top (the
    // column the flake reflects upwards comes back down from the top's
    // internal reflection, still collimated), which scores the forward paths
    // beam -> flake -> top -> pigment -> ... -> delta -> cone (histogram_other
    // bit 16) instead of the histogram: at the flop they were most of what the
    // histogram had left (docs/PERFORMANCE.md).
    bool top_images = true;
    // Explicit flakes with connections and glint_azimuths: the forward
    // next-event connections from a pigment vertex in a flake layer also reach
    // each cone through one mirror reflection off a flake of that layer
    // (straight, or after the top's internal reflection), for the paths whose
    // prefix no other walk takes (histogram_other bit 2): by reciprocity the
    // cone direction's images off the flakes, as reflected_beams and top_images
    // (mc_connection.h, reflectedBeams). It scores the paths ending pigment ->
    // flake -> cone and pigment -> top -> flake -> cone after chains such as
    // beam -> flake -> flake (histogram_other bits 32 and 64) instead of the
    // histogram: the last path the histogram found at 45as110 in the demo was
    // one of them (docs/PERFORMANCE.md).
    bool flake_images = true;
    // Explicit flakes with connections: the paths of class Other without a
    // smooth vertex (chains of flake and internal reflections from the beam)
    // are scored by delta-chain walks (mc_walk.h, traceDeltaChains): forward
    // walks without collisions that carry the pigments' extinction as a weight,
    // delta_rate of them per path, with Russian roulette below
    // delta_roulette_weight. false: the histogram.
    bool delta_walks = true;
    // Delta-chain walks: the chains that begin with the beam's reflection off
    // an explicit flake start on that flake, drawn by groups (tilt, azimuth
    // relative to the beam, depth) with probabilities learned from the walks
    // so far, half kept proportional to the groups' areas (first_flake.h;
    // unbiased for any such probabilities). At the demo's flop three-flake
    // chains whose first flake leans towards the light were most of the
    // delta walks' variance. Off by default: on the demo they halve that
    // variance per walk at 437 nm but did not shorten the stop rule's time
    // (docs/PERFORMANCE.md, "First-flake walks"). false: every chain from a
    // uniform entry point.
    bool first_flake_walks = false;
    double delta_rate = 0.25;
    double delta_roulette_weight = 1e-3;
    // Delta-chain walks: besides the roulette by weight, each new branch is
    // kept with a probability set by its promise, how likely its next
    // reflection or two turn it into a cone (the orientation law at the
    // half-vector; chain_promise.h), the cones weighted by their relative
    // error and their need of the delta walks, and
    // carries the inverse: unbiased, and most branches that cannot score stop
    // early. From the first adaptation on (adaptive_fractions); false: by
    // weight alone.
    bool chain_promise = true;
    double chain_promise_threshold = 1.4e-4;  // of the walk's start weight (mc_walk.h)
    double chain_promise_floor = 0.2;         // the lowest survival probability
    // Diagnostics for error budgets: with connections and glint_azimuths, the parts that run (bit
    // mask): 1 next-event from smooth vertices, 2 the beam's single flake
    // reflections (glints), 4 the reverse walks. A part left out is not scored at
    // all (the histogram does not take it over); 8 the delta-chain walks, 16
    // the forward flake images (flake_images).
    unsigned connection_parts = 31;
    // Diagnostics for error budgets: bit mask of the path classes whose
    // escapes the histogram scores (1 unscattered beam, 2 the beam's first
    // reflection off an explicit flake, 4 last direction change a pigment,
    // the Lambertian substrate or a continuum flake, 8 anything else); with
    // connections, classes 2 and 4 are scored by them and never by the histogram.
    unsigned histogram_classes = 15;
    // Diagnostics: of class 8, the part the histogram scores: 1 chains of
    // delta events from the beam (several flake reflections, internal
    // reflections), 2 delta events after a pigment, substrate or continuum-flake
    // vertex when the first direction change was a delta, 4 the same when it was
    // such a vertex (with reverse_walks, scored by them and never by the
    // histogram), 8 instead of 2 when the first change was the beam's reflection
    // off an explicit flake and the second a pigment vertex in its layer (with
    // reflected_beams, scored by the reverse walks), 16 instead of 2 when the
    // first change was that reflection, the second the internal reflection at
    // the paint's top and the third a pigment vertex in the flake's layer (with
    // top_images, scored by the reverse walks), 32 instead of 2 when the path
    // ends with a pigment vertex in a flake layer, one reflection off a flake
    // of that layer and the way out, 64 the same with the top's internal
    // reflection between the vertex and the flake (with flake_images, scored
    // by the forward connections).
    unsigned histogram_other = 127;
};

struct Estimate {
    double mean = 0.0;
    double std_error = 0.0;  // standard error of the mean
    double relError() const { return mean != 0.0 ? std_error / std::abs(mean) : 0.0; }
};

// One incidence direction and the exit directions at which f is estimated.
struct IncidenceRequest {
    Direction wi;
    std::vector<Direction> wo;
};

struct IncidenceResult {
    double specular = 0.0;              // top interface's mirror reflectance (exact, in albedo)
    Estimate albedo;                    // directional-hemispherical, mirror term included
    Estimate transmittance;             // into a transparent substrate (0 for the others)
    std::vector<Estimate> brdf_per_sr;  // f(wi, wo[k]), mirror term excluded
    std::int64_t paths = 0;
    double seconds = 0.0;
};

struct McResult {
    std::vector<double> wavelengths_nm;
    std::vector<std::vector<IncidenceResult>> bands;  // [band][incidence]
    std::int64_t total_paths = 0;
    double seconds = 0.0;
};

// Runs the full model at each wavelength for each incidence. The recipe must
// be valid (validateRecipe) and every layer thicker than 0 (else InputError);
// explicit_flakes without histogram_cone_deg > 0 throws InputError. Throws
// Error("cancelled") when progress returns false (called with the fraction of
// (band, incidence) jobs done, or of the path budget when no time or error
// target applies).
McResult runMonteCarlo(const Recipe& recipe, std::span<const double> wavelengths_nm,
                       std::span<const IncidenceRequest> requests, const McSettings& settings,
                       const ProgressCallback& progress = {});

// What the estimators of this recipe cannot see, in words for reports:
// flakes with orientation spread 0 (their mirror reflection is a delta in
// direction, so f misses light whose last bounce is such a flake; the albedo
// is exact) and a metal substrate (its unscattered mirror image of the beam
// is a delta, not part of f; the fast model carries it on its table's diagonal).
std::vector<std::string> estimatorLimitations(const Recipe& recipe);

}  // namespace paintlab::mc
