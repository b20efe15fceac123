#pragma once
// The Monte Carlo walks through the paint at one wavelength: forward paths,
// delta-chain, first-flake and reverse walks (mc_walk.cpp; the walker: mc_walker.h).

#include "cavity_chain.h"
#include "chain_length_rate.h"
#include "chain_promise.h"
#include "flake_tile.h"
#include "mc_connection.h"
#include "mc_glints.h"
#include "mc_random.h"
#include "mc_stack.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"

#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

struct WalkSettings {
    int max_events = 1000000;
    double roulette_weight = 0.1;
    // Histogram estimator: the path classes whose escapes it scores, and the parts of class Other.
    HistogramClasses histogram_classes;
    HistogramOtherParts histogram_other;
    // Score classes Smooth and BeamFlake by connections (explicit flakes only; the
    // caller then leaves them out of histogram_classes).
    bool connections = false;
    // Connections run on a random share of the paths (McSettings::connection_fraction);
    // their scores are divided by it.
    double connection_weight = 1.0;
    // A path follows both branches of every explicit flake it meets (reflected
    // with weight R, passed with weight T) and of the top interface (escaped
    // with weight 1 - F, reflected with weight F) instead of choosing one, up to
    // max_splits deep along each branch (McSettings::split_branches).
    bool split_branches = false;
    int max_splits = 6;
    // Reverse walks also connect to the beam's single mirror images off the
    // flakes of the vertex's layer (McSettings::reflected_beams).
    bool reflected_beams = false;
    // And to its images off a flake and then the paint's top (McSettings::top_images).
    bool top_images = false;
    // Connections (forward): the direct next-event estimate from pigment and
    // Lambertian vertices into each cone (ConnectionParts::cone_direct).
    bool cone_direct = true;
    // Connections (forward): pigment vertices of delta_first prefixes
    // (HistogramOtherParts) also connect to each cone through one flake of their
    // layer, and through the top and then such a flake (McSettings::flake_images).
    bool flake_images = false;
    // Delta-chain walks: the beam's reflections off explicit flakes end the
    // branch (the first-flake walks score those chains; McSettings::first_flake_walks).
    bool skip_beam_flake_reflections = false;
    // The chain connections of the layers that run them (LayerFlakes,
    // McSettings::mirror_chain_connections) on the forward walk's flights
    // too, for the escapes its histogram scores (after a smooth vertex:
    // substrate -> flake -> cone); the walk then records its legs and the
    // flakes it meets as the delta-chain walks do.
    bool forward_chain_connections = false;
    // The delta-chain walks run them (ConnectionParts::delta_chains), their
    // scores times chain_connection_weight (1 / ConeRates::delta_chain_share).
    bool delta_chain_connections = true;
    double chain_connection_weight = 1.0;
    // ... and their flights run the drawn cavity chain with this probability,
    // its score times the inverse (ConeRates::drawn_chain_rate).
    double drawn_chain_rate = 1.0;
    // ... and their last-flake connections run on a flight of length l with
    // probability min(1, l / chain_length_um), times the inverse (0: every
    // flight; chain_length_rate.h, ConeRates::chain_length_um).
    double chain_length_um = 0.0;
    // The last-flake connections' cone draw (McSettings::kernel_chain_cones):
    // in proportion to the cone's kernel at the flight times chain_cone_scale
    // (per bin; empty: 1), mixed with the uniform draw; false: uniform.
    bool kernel_chain_cones = false;
    std::span<const double> chain_cone_scale = {};
    CavityForms cavity_forms;  // McSettings::cavity_forms
    // The drawn chains' draw (null: uniform among the forms a flight can run).
    const CavityFormWeights* cavity_form_weights = nullptr;
    // Delta-chain walks: a branch's roulette by its promise (chain_promise.h;
    // null: by weight alone). It survives with probability
    // clamp(w promise / (promise_threshold w_0), promise_floor, 1), w_0 the
    // walk's start weight, and then carries w / q.
    // Connections: the roulette by transmittance (McSettings::connection_roulette).
    bool connection_roulette = true;
    const ChainPromise* chain_promise = nullptr;
    double promise_threshold = 1.4e-4;
    double promise_floor = 0.2;
};

// Projection of what escapes on the fast model's basis (mc_table.h): the
// ambient cosines are cut into cells around the nodes, and an escape with
// weight w at cosine mu_o in cell c and azimuth delta from the incident
// propagation direction adds w cos(m delta) / T(mu_o) * scale[c] to the
// entry (c, m), m < orders. With scale[c] = 1 / (2 pi T(mu_i) int_c mu dmu)
// the mean is the cell's mu-weighted average of f^m / (T(mu_i) T(mu_o)), the
// convention of LayeredBrdf::BandTable (f = T_i T_o sum_m (2 - delta_m0)
// f^m cos(m delta)).
struct FourierCells {
    std::vector<double> upper_mu;  // ascending upper edges (the last is 1)
    std::vector<double> scale;     // per cell
    int orders = 1;
    double top_eta = 1.0;  // n_top / n_ambient, for T(mu_o) = 1 - Fresnel
    double cos_in = 1.0;   // azimuth of the incident propagation direction
    double sin_in = 0.0;
    std::size_t offset = 0;  // index of entry (0, 0) in f_out; entry (c, m) at offset + c * orders + m
};

struct PathContext {
    const PaintStack& stack;
    std::span<const ExitChain> chains;             // next-event estimator (empty: off)
    std::span<const HistogramBin> bins;            // histogram estimator (empty: off)
    std::span<const LayerFlakes> explicit_flakes;  // per layer (empty: flakes are a continuum)
    WalkSettings settings;
    const FourierCells* fourier = nullptr;  // projection (null: off)
    std::span<const GlintSet> glints;       // per bin, this path's tile realisation (connections)
    // Connections with a fraction per cone (mc_job_chunks.cpp): per bin, the weight of
    // this path's next-event connections into it (0: none); empty: settings.connection_weight for all.
    std::span<const double> nee_weights;
    // Where the next-event connections' scores go (per bin); empty: f_out.
    std::span<double> nee_out;
    // Per bin, b >= 1: a pigment collision runs the connections into it with
    // probability min(1, b sigma_s / sigma) instead of sigma_s / sigma, the
    // chance that it scatters (weighted by the inverse; Walker::connectFromPigment);
    // empty: 1 for all.
    std::span<const double> nee_boost = {};
    // Where the chain connections' scores go (per bin); empty: f_out.
    std::span<double> chain_out = {};
    // What the drawn cavity chains learn (null: nothing).
    CavityFormLearning* form_learning = nullptr;
    // What the last-flake connections' rate by length learns (null: nothing).
    ChainLengthLearning* length_learning = nullptr;
};

// What one path carries out of the paint (power per unit incident power),
// and what it cost (tile intersections; the adaptive fractions' cost model).
struct PathOutcome {
    double escaped = 0.0;           // through the top interface
    double transmitted = 0.0;       // into a transparent substrate
    std::int64_t events = 0;        // free paths drawn
    std::int64_t rays = 0;          // tile intersections of the walk itself
    std::int64_t nee_rays = 0;      // tile intersections of its next-event connections
    std::int64_t nee_attempts = 0;  // next-event connections traced (vertex x bin)
    std::int64_t image_calls = 0;   // connections through one flake's mirror image (vertex x bin)
    std::int64_t image_rays = 0;    // their tile intersections and candidate tests (reflectedBeams)
};

// Traces a path that has just been refracted into the top slice with
// propagation direction v (v.z < 0) and weight (power per unit surface area)
// `weight`, starting at lateral position (x, y). Adds to f_out[k] the
// estimate of f for chains[k] or bins[k] (and the projection's entries) and
// returns the weight that leaves through the top and through a transparent
// substrate. With connections, their random numbers come from
// connection_rng, so that the walk itself draws the same numbers with and
// without them. Never throws.
PathOutcome tracePath(const PathContext& context, Vec3 v, double weight, double x, double y, PathRng& rng,
                      std::span<double> f_out, PathRng* connection_rng = nullptr);

// Delta-chain walks (McSettings::delta_walks): the part of class Other with no
// smooth vertex (HistogramOtherParts::delta_chains: chains of flake mirror reflections and
// internal reflections from the beam, e.g. beam -> flake -> flake underside ->
// flake -> cone, which sets the flop geometries' error in the pearlescent demo)
// by a forward walk without collisions: the straight flights between delta
// events carry the weight e^(-sigma_t s) that the analog walk gets as a survival
// probability (the same expectation: such a path has no collision), splitting at
// flakes and the top as the walk; the escapes of class Other into the bins are
// added to f_out. settings.roulette_weight should be low (the chains' weights
// are R^3 e^-tau, ~1e-2). Never throws.
PathOutcome traceDeltaChains(const PathContext& context, Vec3 v, double weight, double x, double y,
                             PathRng& rng, std::span<double> f_out);

// First-flake walks (first_flake.h): the delta chains that begin with the
// beam's reflection off explicit flake `draw.flake` of layer `draw.layer` at
// draw.point. The beam (v_top, refracted into the top slice, with weight
// `weight` per unit area) is traced straight down to the point (pigments,
// flakes crossed, index steps), reflected with the flake's R, and followed as
// a delta-chain walk; its escapes of class Other without a smooth vertex into
// the bins are added to f_out, weighted by A_G |v.n| / (L^2 P_G |v_z|)
// (draw.area_over_probability = A_G / P_G). Never throws.
struct FirstFlakeDraw;
PathOutcome traceFromFirstFlake(const PathContext& context, const Vec3& v_top, double weight,
                                const FirstFlakeDraw& draw, PathRng& rng, std::span<double> f_out);

// Reverse walks (McSettings::reverse_walks): by reciprocity, f(wi, w) = f(w, wi),
// so the cone average of f(wi, .) over cone C is (Omega / Omega_proj) times the
// mean over w uniform in C of w_z f(w, wi). A reverse walk enters from w
// (refracted propagation direction v, weight 1 - F(w)) and estimates f(w, wi)
// by next-event estimation towards the beam's reversed direction `target`
// (upward, in the top slice) through the real tiles, from its smooth vertices,
// but only those after a first direction change that was a delta (a flake's
// mirror reflection, an internal reflection): reversed, these are exactly the
// forward paths of class Other whose first direction change was a smooth
// vertex, e.g. beam -> pigment -> flake -> cone, which the histogram finds
// about once in 10^5 paths at the flop (docs/PERFORMANCE.md), and which the
// forward histogram then leaves out (HistogramOtherParts::smooth_first). Returns the sum
// of those estimates (f(w, wi), 1/sr) and the work done. Never throws.
struct ReverseOutcome {
    double f = 0.0;
    std::int64_t walk_steps = 0;   // free paths + tile intersections of the walk
    std::int64_t nee_steps = 0;    // tile intersections + attempts of its next-event connections
    std::int64_t image_calls = 0;  // its connections to the beam's images (reflectedBeams)
    std::int64_t image_rays = 0;   // their tile intersections and candidate tests
};
ReverseOutcome traceReversePath(const PathContext& context, Vec3 v, double weight, double x, double y,
                                const Vec3& target, PathRng& rng, PathRng& connection_rng);

}  // namespace paintlab::mc
