#pragma once
// The full model: Monte Carlo radiative transfer in a layered paint, one
// wavelength at a time, the independent check of the fast model
// (layered_brdf.h; docs/ARCHITECTURE.md, "The full model").
//
// A collimated beam enters through the smooth top interface; each layer's
// binder with its pigments is a participating medium (Henyey-Greenstein
// lobes, absorption by weighting, Russian roulette); flakes are either a
// continuum of oriented reflectors with the fast model's statistics or, with
// explicit_flakes, real flat flakes in a periodic Embree tile per layer;
// internal interfaces refract and reflect; the substrate is Lambertian,
// black, metal or transparent. The layers below the lowest flakes, with the
// substrate, are by default one reflecting surface: their adding-doubling
// operator (McSettings::bottom_operator), the same pigment continuum.
//
// Estimates, each with its standard error: the albedo (mirror term
// included), the transmittance into a transparent substrate, and f(wi, wo)
// by next-event estimation or, with histogram_cone_deg > 0 (always with
// explicit flakes, whose mirror reflections are deltas), as the cone average
// of f cos over that of cos. With explicit flakes most path classes are scored
// by connections, reverse walks and delta-chain walks instead of the
// histogram (mc_connection.h, mc_walk.h); a table on the fast model's basis:
// mc_table.h. Errors are over paths, or with explicit flakes over `batches`
// tile realisations (so they include the flake arrangement's randomness).
//
// Determinism: path p of (band b, incidence i) draws from a generator seeded
// by (seed, b, i, p); chunks are merged in order, so results do not depend on
// the thread count; stopping by time only changes how many chunks are merged.
//
// Limits: the tile is periodic (side set by tile_flakes, >= 2 flake
// diameters) and float (Embree); flakes are thickness-less polygons or disks
// that overlap unless reject_overlaps. settings.threads sets TBB's
// process-wide parallelism for the duration of the call.

#include "paintlab/engine/brdf.h"
#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace paintlab::mc {

// Which parts of the explicit-flake connections run (diagnostics for error
// budgets; all on by default). A part left out is not scored at all: the
// histogram does not take it over.
struct ConnectionParts {
    bool cone_direct = true;    // next-event from pigment and Lambertian vertices into the cones
    bool glints = true;         // the beam's single flake reflections
    bool reverse_walks = true;  // reverse walks from the cones (McSettings::reverse_walks)
    bool delta_walks = true;    // delta-chain walks (McSettings::delta_walks)
    bool flake_images = true;   // forward connections through one flake (McSettings::flake_images)
    // the chain connections on the forward walk's flights (McSettings::mirror_chain_connections,
    // interference_chain_connections; on the delta-chain walks they are part of delta_walks)
    bool forward_chains = true;
    // within delta_walks (so none() keeps it): the chain connections on their flights (off: the
    // walks score only the escapes those connections leave them; an account, not an estimate of f)
    bool delta_chains = true;
    static constexpr ConnectionParts none() { return {false, false, false, false, false, false, true}; }
};

// Which cavity chains (McSettings::cavity_connections, engine/src/montecarlo/
// cavity_chain.h) the connections take: those every flight runs, and the
// drawn ones (more round trips or flakes, or ending at c) in mirror-flake
// layers (a third less time on silver metallic, -3 % to +20 % on the
// fast-vs-full grid's aluminium) and, off by default, in
// interference-flake layers (there they cost a quarter to a half more time
// for the same paths: docs/PERFORMANCE.md); the walks score the escapes of
// the others. walk_scores (tests): All, or only the escapes that end a drawn
// chain (a reference for the drawn forms alone), or None (the connections alone).
struct CavityForms {
    bool every_flight = true;
    bool drawn = true;
    enum class WalkScores { All, DrawnOnly, None };
    WalkScores walk_scores = WalkScores::All;
    bool drawn_on_interference_flakes = false;
};

// The path classes, by their last direction change, whose escapes the
// histogram scores (diagnostics; with connections, beam_flake and smooth are
// scored by them and never by the histogram).
struct HistogramClasses {
    bool beam = true;        // unscattered beam
    bool beam_flake = true;  // the beam's first reflection off an explicit flake
    bool smooth = true;      // a pigment, the Lambertian substrate or a continuum flake
    bool other = true;       // anything else (several flakes, internal reflections, mirrors)
    static constexpr HistogramClasses none() { return {false, false, false, false}; }
};

// Of class `other`, the parts the histogram scores (diagnostics). "Smooth
// vertex": a pigment, the Lambertian substrate or a continuum flake; "delta":
// a mirror reflection (explicit flake, internal interface, metal).
struct HistogramOtherParts {
    bool delta_chains = true;  // only delta events since the beam (the delta-chain walks' part)
    bool delta_first = true;   // a smooth vertex after a first delta change (none of the parts below)
    bool smooth_first = true;  // the first change a smooth vertex (the reverse walks' part)
    // The beam's reflection off an explicit flake, then a pigment vertex in its layer (reflected_beams).
    bool beam_flake_pigment = true;
    // That reflection, the top's internal reflection, then a pigment vertex in the flake's layer
    // (top_images).
    bool beam_flake_top_pigment = true;
    // Ends pigment vertex in a tiled layer -> a flake of that layer -> out (flake_images).
    bool ends_pigment_flake = true;
    // Ends pigment vertex -> the top's internal reflection -> such a flake -> out (flake_images).
    bool ends_pigment_top_flake = true;
    static constexpr HistogramOtherParts none() { return {false, false, false, false, false, false, false}; }
};

struct McSettings {
    std::uint64_t seed = 1;
    // Each (band, incidence) stops at the first of: max_paths paths; every
    // estimate at or below target_rel_error (relative standard error, 0 = off,
    // checked between rounds of chunks; an f also at or below
    // target_abs_error_per_sr); its even share of what is left of
    // max_seconds when it starts (0 = off), which covers the whole call, the
    // tiles' set-up included (tabulateMonteCarlo: the set-up comes on top).
    std::int64_t max_paths = 100000;
    double target_rel_error = 0.0;
    // With target_rel_error: an f and a projection entry (1/sr) also count as
    // converged once their standard error is at or below this floor (0 = off).
    // 1 % of a near-black flop is below any instrument's noise and costs the
    // most (docs/PERFORMANCE.md, the fast-vs-full grid); the albedo keeps the
    // relative target alone.
    double target_abs_error_per_sr = 0.0;
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
    // Flakes per tile aimed at (sets the tile's side, >= 2 diameters). With
    // `batches` tiles per layer: 64 tiles of 5,000 hold as many flakes as 16 of
    // 20,000, but a chunk's tile is a quarter of the memory (its paths cost
    // less) and the errors have 63 degrees of freedom (docs/PERFORMANCE.md,
    // "Smaller tiles, more batches", has the figures).
    int tile_flakes = 5000;
    int max_tile_flakes = 200000;  // per kind and layer
    // A flake that intersects one already placed is moved elsewhere
    // (flake_tile.h), as real flakes do not interpenetrate; InputError when a
    // layer is too crowded for it. Off by default: on the silver metallic it
    // moves f by a few percent at the mid and far geometries and raises the
    // flop's error per CPU second, whose paths between stacked flakes it
    // keeps (docs/PERFORMANCE.md, issue 30).
    bool reject_overlaps = false;
    // Regular polygons of the disk's area with this many sides, or 0 for exact disks (flake_tile.h).
    int flake_polygon_sides = 16;
    // Chunk c of a job belongs to batch c mod batches. With explicit flakes each
    // batch traces its own tile realisation and the errors are those of the
    // batches' means (batches - 1 degrees of freedom), so they include the
    // flake arrangement's randomness. tabulateMonteCarlo keeps one table per batch.
    int batches = 64;
    // Explicit flakes: score the path classes that allow it by exact
    // connections through the tiles (mc_connection.h) instead of the
    // histogram; same mean, far smaller variance. false: the histogram alone.
    bool connections = true;
    // Explicit flakes: trace every tile at this many evenly spaced azimuths
    // (path p at view p mod tile_views). The flake statistics are isotropic,
    // so each view is a valid realisation; averaging removes most of the
    // spread between tiles. 1: the tile's own frame only.
    int tile_views = 32;
    // Connections: the share of paths (in [1e-3, 1]) that run them, their
    // scores divided by it. With glint_azimuths, x > 1 (up to 64) runs them on
    // every path and raises a pigment collision's chance to run them to
    // min(1, x sigma_s / sigma) (PathContext::nee_boost). adaptive_fractions
    // sets x per cone after the first round.
    double connection_fraction = 0.125;
    // Connections: the beam's single flake reflections over every azimuth of
    // each tile at once, importance-sampled and stratified per chunk
    // (mc_glints.h, azimuthGlintSets; errors over paths then become
    // conservative). false: one flake per connected path and view.
    bool glint_azimuths = true;
    // With glint_azimuths: each glint sample puts its flake at a new uniform
    // place in the tile and traces the shadows of the others there (mc_glints.h,
    // azimuthGlintSample): the tiles' own shadows no longer leave a spread
    // between tiles in the glints. Ignored with reject_overlaps (flakes then
    // are not placed independently).
    bool move_glint_flakes = true;
    // Connections with glint_azimuths: per cone, the next-event rate, the glint
    // samples, reverse walks and delta-chain walks per path are chosen after
    // every round from the cones' variances and a cost model (mc_rates.h).
    // Unbiased: a path's rates are fixed before it runs. The first round's
    // paths are dropped when they are a small part of the job.
    bool adaptive_fractions = true;
    // Explicit flakes: a path follows both branches at every explicit flake
    // (weights R and T) and at the top interface (weights F and 1 - F), up to
    // 6 splits deep, instead of choosing one. Same mean; chains of several
    // flake reflections are no longer thinned by their reflectances.
    bool split_branches = true;
    // Connections: the paths whose first direction change was a pigment or the
    // Lambertian substrate and whose last was a delta are scored by reverse
    // walks from the cones (reciprocity; mc_walk.h, traceReversePath).
    bool reverse_walks = true;
    // Reverse walks per path and cone in the first round (adaptive_fractions sets the later ones).
    double reverse_rate = 0.125;
    // Reverse walks: pigment vertices also connect to the beam's mirror images
    // off the flakes of their layer (HistogramOtherParts::beam_flake_pigment).
    bool reflected_beams = true;
    // Reverse walks: ... and to its images off a flake and then the paint's top
    // (HistogramOtherParts::beam_flake_top_pigment).
    bool top_images = true;
    // Connections with glint_azimuths: forward connections from a pigment
    // vertex in a flake layer also reach each cone through one flake of that
    // layer, directly or after the top's internal reflection
    // (HistogramOtherParts::ends_pigment_flake, ends_pigment_top_flake).
    bool flake_images = true;
    // Connections: chains of delta events from the beam are scored by forward
    // walks without collisions that carry the extinction as a weight
    // (mc_walk.h, traceDeltaChains), delta_rate per path, Russian roulette
    // below delta_roulette_weight.
    bool delta_walks = true;
    // Delta-chain walks: the chains that begin at an explicit flake start on
    // it, drawn by groups with learned probabilities (first_flake.h). Off by
    // default: it lowers the variance per walk but not the time to a target.
    bool first_flake_walks = false;
    double delta_rate = 0.25;
    // The share of the delta-chain walks (without first_flake_walks) that run
    // the chain connections, their scores weighted by its inverse; the others
    // score only the escapes those connections leave. The start: with
    // adaptive_fractions the rate model chooses it after every round, from 1
    // down to 1/8 (where the walks' escapes carry the variance, as on mirror
    // flakes), and 1 while the connections' scores are heavy-tailed (mc_rates.h,
    // docs/PERFORMANCE.md); clamped to [1/8, 1].
    double delta_chain_share = 1.0;
    // The share of those walks' flights in mirror-flake layers that run the
    // drawn cavity chain (CavityForms::drawn), its score weighted by the
    // inverse; the forms stay taken, so the walks never score their escapes.
    // The start: with adaptive_fractions the rate model chooses it after
    // every round beside delta_chain_share, from 1 down to 1/8, but not
    // where a single flight's drawn score, so thinned, would add a tenth of
    // the walks' variance (mc_rates.h); clamped to [1/8, 1].
    double drawn_chain_rate = 1.0;
    bool adapt_drawn_chain_rate = true;  // false: drawn_chain_rate throughout (bench config 40)
    // Those walks' last-flake connections run on a flight of length l with
    // probability min(1, l / L), weighted by the inverse (the score grows
    // with l; chain_length_rate.h). L in µm, 0: every flight. The start:
    // with adaptive_fractions the rate model chooses L after every round
    // among 0 and 0.5-16 µm, but not where a single flight's score, so
    // thinned, would add a tenth of the walks' variance (mc_rates.h).
    double chain_length_um = 0.0;
    bool adapt_chain_length = true;  // false: chain_length_um throughout (bench config 42)
    // The delta walks' last-flake connections draw a flight's cone in
    // proportion to its kernel there (the flake law's density at the normal
    // that mirrors the flight into the cone's axis), scaled by the cone's
    // need of the stop rule once rounds have measured it, a quarter of the
    // draw kept uniform; false: uniformly (bench config 41).
    bool kernel_chain_cones = true;
    double delta_roulette_weight = 1e-3;
    // Delta-chain walks (with adaptive_fractions): a branch also survives with a
    // probability set by its promise of reaching a cone (chain_promise.h) and
    // carries the inverse; unbiased, and hopeless branches stop early.
    bool chain_promise = true;
    double chain_promise_threshold = 1.4e-4;  // of the walk's start weight (mc_walk.h)
    double chain_promise_floor = 0.2;         // the lowest survival probability
    // Chain connections (issue 30), for the chains of mirror reflections that
    // a walk would have to land in a 5 degree cone by chance:
    //  - last-flake connections: the escapes whose last change is a reflection
    //    off an explicit flake met for the first time (after an earlier change)
    //    are scored by next-event estimation through a flake drawn on each
    //    flight with the tiles' law (mc/last_flake.h);
    //  - cavity connections: the escapes in which light caught between two
    //    flakes leaves the way it came (mc/cavity_chain.h: after c, the last
    //    flake met for the first time, round trips between c and the flake
    //    before it, then back over the flakes before that) by a flake c drawn
    //    on the flight, its normal solved for the cone.
    // Both run on the delta-chain walks and on the forward walk (for the
    // escapes its histogram scores: substrate -> flake -> cone), one cone per
    // flight, and take those escapes from the walks; ignored with
    // reject_overlaps (the law assumes independently placed flakes).
    // mirror_chain_connections turns both on for the layers whose flakes are
    // all mirror flakes, interference_chain_connections for the other flake
    // layers (where a drawn flake that the path crossed before scores with its
    // T, last_flake.h); both on by default, as the pearl demos and the
    // fast-vs-full grid's pearl points measured reach 1 % sooner with them
    // (docs/PERFORMANCE.md). The other two turn one on for every flake layer.
    bool mirror_chain_connections = true;
    bool interference_chain_connections = true;
    bool last_flake_connections = false;
    bool cavity_connections = false;
    // Connections (next-event into the cones, the reverse walks' towards the
    // beam): Russian roulette of those whose transmittance before the first
    // flake tile is below 1e-3 (mc_connection.h, kConnectionRouletteT);
    // unbiased, and the connections from deep in a scattering coat under a
    // flake layer stop tracing that layer. false: the estimator before issue 30.
    bool connection_roulette = true;
    // The flake-free bottom of the paint (every layer below the lowest layer
    // with flakes, and the substrate) is one reflecting surface of the walk:
    // its reflection operator by the fast model's adding and doubling, the
    // same pigment continuum the walk would cross (mc_bottom.h, which says
    // when it applies). false: the walk crosses those layers.
    bool bottom_operator = true;
    // Diagnostics for error budgets: what each estimator scores.
    ConnectionParts connection_parts;
    CavityForms cavity_forms;
    HistogramClasses histogram_classes;
    HistogramOtherParts histogram_other;
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

// Where a job's time and variance go, by the adaptive rates' model
// (McSettings::adaptive_fractions, mc_rates.h) at the rates its last adapted
// paths ran at: per part, the cost per path (microseconds on the model's
// reference machine, from counted work) and the worst exit cone's relative
// variance per path, V / f^2 (its share of the stop rule's error^2 x paths).
struct RateAccount {
    enum Part { Walk, NextEvent, Glints, ReverseWalks, DeltaWalks, kParts };
    bool measured = false;  // false: no adaptation ran (no explicit flakes, or too few paths)
    std::size_t worst_exit = 0;
    std::array<double, kParts> cost_us_per_path{};
    std::array<double, kParts> rel_variance_per_path{};
};

struct IncidenceResult {
    double specular = 0.0;              // top interface's mirror reflectance (exact, in albedo)
    Estimate albedo;                    // directional-hemispherical, mirror term included
    Estimate transmittance;             // into a transparent substrate (0 for the others)
    std::vector<Estimate> brdf_per_sr;  // f(wi, wo[k]), mirror term excluded
    std::int64_t paths = 0;
    double seconds = 0.0;
    RateAccount account;
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
