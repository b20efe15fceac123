#pragma once
// The state of one Monte Carlo walk through the paint (mc_walk.h has the
// walks it runs): where the path is (position, direction, weight, slice), what
// its direction changes make of it (PathHistory), and what it has tallied
// (WalkTally). mc_walker.cpp moves it (free paths, tiles, interfaces,
// substrate, collisions, splitting and roulette); mc_walker_scores.cpp scores
// it (histogram, projection, next-event estimates and connections).

#include "cavity_chain.h"
#include "mc_path_history.h"
#include "mc_walk.h"

#include <array>
#include <cstdint>
#include <span>

namespace paintlab::mc {

struct LastFlakeLaw;

// What a walk (and the branches split off it) carried out and cost.
struct WalkTally {
    double transmitted = 0.0;    // into a transparent substrate
    double escaped_extra = 0.0;  // what split-off branches carried out through the top
    double reverse_score = 0.0;  // a reverse walk's estimate of f
    std::int64_t events = 0;
    std::int64_t rays = 0;
    std::int64_t nee_rays = 0;
    std::int64_t nee_attempts = 0;
    std::int64_t image_calls = 0;  // flake-image connections (reflectedBeams) traced
    std::int64_t image_rays = 0;   // their tile intersections and candidate tests
};

struct Walker {
    Walker(const PaintStack& stack_, std::span<const LayerFlakes> explicit_flakes_,
           const WalkSettings& settings_, PathRng& rng_, const Vec3& v_, double weight_, double x_, double y_)
        : stack(stack_), explicit_flakes(explicit_flakes_), rng(rng_), settings(settings_), v(v_),
          weight(weight_), x(x_), y(y_) {}

    // What the walk runs in and where its scores go.
    const PaintStack& stack;
    std::span<const ExitChain> chains;
    std::span<const HistogramBin> bins;
    std::span<const LayerFlakes> explicit_flakes;
    const FourierCells* fourier = nullptr;
    PathRng& rng;
    PathRng* connection_rng = nullptr;  // non-null: connections on
    const WalkSettings& settings;
    std::span<double> brdf_out;
    std::span<const double> nee_weights;          // per bin (empty: settings.connection_weight)
    std::span<double> nee_out;                    // per bin (empty: brdf_out)
    std::span<double> chain_out;                  // the chain connections' scores per bin (empty: brdf_out)
    CavityFormLearning* form_learning = nullptr;  // what the drawn cavity chains learn (null: nothing)
    ChainLengthLearning* length_learning = nullptr;  // ... and the rate by length (null: nothing)
    // Per bin, the factor (>= 1) on a pigment collision's chance to run the
    // connections into it (PathContext::nee_boost); empty: 1.
    std::span<const double> nee_boost;

    // Where the path is.
    Vec3 v;
    double weight;
    double x = 0.0;  // lateral position (µm), only used with explicit flakes
    double y = 0.0;
    std::size_t j = 0;   // slice
    double depth = 0.0;  // µm below the top of the paint
    int splits = 0;      // splits above this branch
    PathHistory history;
    WalkTally tally;

    // Which walk this is.
    enum class Mode {
        // tracePath: the analog walk, scored by the histogram, the next-event
        // chains, the projection and the connections.
        Forward,
        // traceReversePath: it enters from the exit cone, and scores next-event
        // estimates towards reverse_target (upward in the top slice, the beam
        // reversed) from its smooth vertices once its first direction change was
        // a delta; a first change at a smooth vertex ends it.
        Reverse,
        // traceDeltaChains, traceFromFirstFlake: no collisions; the extinction of
        // the slices is applied as the weight e^(-sigma t) of the straight flight
        // instead, and a smooth vertex (the Lambertian substrate) ends it.
        DeltaChain,
    };
    Mode mode = Mode::Forward;
    Vec3 reverse_target{0.0, 0.0, 1.0};  // Reverse
    double promise_weight = 0.0;         // DeltaChain: promise_threshold times the start weight
    double beam_x = 1.0;                 // the beam's lateral travel direction (the promise's frame)
    double beam_y = 0.0;

    // Splitting (WalkSettings::split_branches): the same expectation as choosing a
    // branch with its probability, without that choice's noise; it matters for
    // the chains of several delta reflections (class Other), which the choice
    // thins by the product of the flakes' R and the top's F (docs/PERFORMANCE.md).
    bool splitting() const { return settings.split_branches && splits < settings.max_splits; }
    // Follows a copy of this path, its weight times `factor`, to its end, and keeps what it carried.
    void runBranch(double factor);
    bool tiled(int layer) const {
        return static_cast<std::size_t>(layer) < explicit_flakes.size() &&
               explicit_flakes[static_cast<std::size_t>(layer)].tile != nullptr;
    }
    void move(double t) {
        x += v.x * t;
        y += v.y * t;
        ux += v.x * t;
        uy += v.y * t;
    }

    // Delta-chain walks with last-flake connections (last_flake.h): the
    // lateral position without the tile's wraps, the path's last vertices
    // (where its straight legs meet; a ring of the latest kLegVertices), and
    // the layer of the flake whose reflection was the last direction change
    // (-1: another change, or a flake the path reflected off before: the walk
    // scores those escapes, the connections only the last flakes met once), and
    // the flakes reflected off so far (layer, index; a ring of the latest
    // kLegVertices; passing a flake is not meeting it).
    static constexpr int kLegVertices = 32;
    std::array<std::int64_t, kLegVertices> met{};
    int met_count = 0;
    // Records a reflection off flake `flake` of `layer`; returns whether the path reflected off it before.
    bool meetFlake(int layer, std::int64_t flake) {
        const std::int64_t id = flake * 64 + layer;
        const int stored = met_count < kLegVertices ? met_count : kLegVertices;
        bool before = false;
        for (int i = 0; i < stored; ++i) before = before || met[static_cast<std::size_t>(i)] == id;
        met[static_cast<std::size_t>(met_count % kLegVertices)] = id;
        ++met_count;
        return before;
    }
    double ux = 0.0;
    double uy = 0.0;
    std::array<Vec3, kLegVertices> vertices{};
    int vertex_count = 0;
    int last_flake_layer = -1;
    // false: the walk scores every escape (first-flake walks, whose legs before
    // their first flake are not recorded); true: the chain connections of the
    // layers that run them (LayerFlakes) take their escapes.
    bool chain_connections = true;
    // Whether this walk runs the chain connections (last-flake, cavity) and so
    // records its legs and the flakes it meets.
    bool chainRecording() const {
        return mode == Mode::DeltaChain || (mode == Mode::Forward && settings.forward_chain_connections);
    }
    // Their random numbers: the forward walk's connection stream (the walk
    // draws the same numbers with and without them), else the walk's own.
    PathRng& chainRng() const {
        return mode == Mode::Forward && connection_rng != nullptr ? *connection_rng : rng;
    }
    // Forward walk: whether its histogram would score an escape after
    // `reflections` more reflections off flakes of `layer` (the chain
    // connections take only those).
    bool forwardScoresAfter(int layer, int reflections) const {
        PathHistory after = history;
        for (int i = 0; i < reflections; ++i) after.flakeReflection(layer);
        return after.path_class == PathClass::Other &&
               after.histogramScores(settings.histogram_classes, settings.histogram_other);
    }
    void markVertex() {
        vertices[static_cast<std::size_t>(vertex_count % kLegVertices)] = {ux, uy, -depth};
        ++vertex_count;
    }
    // The latest direction changes (a ring of kChangeRing): the flake
    // reflected and whether it was met for the first time
    // (cavity_chain.h), with the flake's normal and kind.
    static constexpr int kChangeRing = 16;
    struct Change {
        ChainChange chain;
        Vec3 normal{0.0, 0.0, 1.0};
        int kind = -1;
    };
    std::array<Change, kChangeRing> changes{};
    int change_count = 0;
    // Change i back (0: the latest); i < min(change_count, kChangeRing).
    const Change& changeBack(int i) const {
        return changes[static_cast<std::size_t>((change_count - 1 - i) % kChangeRing)];
    }
    // A direction change here: by a reflection off a flake of `flake_layer`
    // met for the first time, or (-1) another; `flake_id` (flake * 64 +
    // layer), `normal` and `kind` name the flake reflected, met before or
    // not (-1: not a tile's flake).
    void changedAtVertex(int flake_layer = -1, std::int64_t flake_id = -1, const Vec3& normal = {},
                         int kind = -1) {
        last_flake_layer = flake_layer;
        if (!chainRecording()) return;  // the ring serves the chain connections only
        changes[static_cast<std::size_t>(change_count % kChangeRing)] = {
            {flake_id, flake_layer >= 0}, normal, kind};
        ++change_count;
        markVertex();
    }
    // The cavity chain the escape now ends (cavityChainForm; layer -1: none).
    CavityForm cavityFormNow() const;

    // The weight that leaves through the top; 0 when the path is absorbed or lost.
    double run();
    // Returns false when the path ends.
    bool roulette();
    // Delta-chain walks: the roulette of a new branch by its promise
    // (WalkSettings::chain_promise); the beam's own branches and those that
    // head into a cone always go on. Returns false when the branch ends.
    bool promiseRoulette();

    // Moving (mc_walker.cpp).
    // Explicit flakes of the current layer along the free path t (medium) and
    // to_boundary (slice): 1 = a flake was hit and handled, 2 = the ray
    // wrapped at the tile's side, 0 = nothing in the way, -1 = the path ended.
    int traceTile(const Slice& s, double sigma, double t, double to_boundary);
    // An explicit flake hit with unit normal n: reflect, pass or absorb.
    bool explicitFlakeEvent(const FlakeKind& f, const Vec3& n, int layer, std::int64_t flake = -1,
                            int kind = -1);
    // A flake collision: sample a normal from D weighted by |v.n| (the flakes a
    // ray meets), then reflect, pass (interference flakes) or absorb.
    bool flakeEvent(const FlakeKind& f);
    bool collide(const Slice& s, double sigma, double flake_rate);
    // `top`: the paint's top (the ambient beyond).
    bool crossInterface(double n_from, double n_to, bool top);
    bool substrate(const Slice& s);

    // Scoring (mc_walker_scores.cpp).
    // Left through the top (v already refracted into the ambient): the
    // histogram bins that contain the exit direction.
    void escape();
    void project(const FourierCells& cells);
    // Next-event estimate from a collision in slice j with sampling rate sigma.
    void scoreCollision(const Slice& s, double sigma);
    // The smooth substrate's (Lambertian or the bottom operator's) next-event
    // estimates (chains and cone connections).
    void scoreLambert(const Slice& s);
    // What that substrate sends towards the upward u per sr: weight times its f from v into u.
    double substrateEmitted(const Vec3& u) const;
    // Connections from a pigment collision into the cones (directly and through a flake's image).
    void connectFromPigment(const Slice& s, double sigma);
    // Delta-chain walk: the last-flake connections from the flight of `length`
    // µm ahead (no real flake on it) in slice s of a layer with a law (last_flake.h),
    // run at the rate by length (WalkSettings::chain_length_um).
    void lastFlakeConnections(const Slice& s, const LayerFlakes& lf, double length, double sigma);
    // One such connection, its score weighted 1 / p_length (added to chainOut; value 0: none).
    struct ConeScore {
        std::size_t k = 0;
        double value = 0.0;
    };
    ConeScore lastFlakeConnection(const Slice& s, const LayerFlakes& lf, double length, double sigma,
                                  double p_length, PathRng& chain_rng);
    // What that score tells the choice of L (ChainLengthLearning).
    void learnChainLength(const ConeScore& score, const std::array<double, kChainLengths>& p_candidates,
                          double p_length);
    // A chain connection's draw on the flight of `length` µm ahead: one cone
    // (a flight's draws for all six cost more than the walk itself), a point
    // at t uniform on the flight, a direction uniform in the cone (u: in
    // slice s), and the factors every such connection carries: the flight's
    // length and transmittance e^(-sigma t), the radiance law (n_0 / n)^2,
    // 1 / u_z, the cone's w_z Omega / Omega_proj and 1 / the cone's
    // probability (the number of cones when drawn uniformly). ok false: no connection.
    struct ChainDraw {
        std::size_t k = 0;
        double t = 0.0;
        Vec3 u;
        double point_depth = 0.0;
        double factor = 0.0;
        bool ok = false;
    };
    // cone_p: the cones' probabilities (empty: uniform, the drawn cone weighing the number of cones).
    ChainDraw drawChainCone(const Slice& s, double length, double sigma, PathRng& chain_rng,
                            std::span<const double> cone_p = {}) const;
    // The last-flake connections' cone probabilities for the flight ahead
    // (WalkSettings::kernel_chain_cones): per cone the kernel's flake density
    // sum_i A_i D_i(h) at the normal h that mirrors v into the cone's axis,
    // times the axis' w_z / u_z Omega / Omega_proj and the cone's scale, mixed
    // with the uniform draw (kUniformConeShare); false (p untouched): draw uniformly.
    static constexpr std::size_t kMaxKernelCones = 16;
    static constexpr double kUniformConeShare = 0.25;
    bool kernelConeProbabilities(const Slice& s, const LayerFlakes& lf,
                                 std::array<double, kMaxKernelCones>& p) const;
    // The cones' axes refracted into a slice of index n (u.z 0: none) and
    // their w_z / u_z Omega / Omega_proj, kept for the last n asked (every
    // flight of a delta walk asks, most in one layer).
    struct RefractedConeAxes {
        double n = 0.0;
        std::array<Vec3, kMaxKernelCones> u{};
        std::array<double, kMaxKernelCones> factor{};
    };
    mutable RefractedConeAxes cone_axes;
    const RefractedConeAxes& coneAxesIn(double n) const;
    std::span<double> chainOut() const { return chain_out.empty() ? brdf_out : chain_out; }
    // Its kernel per kind (the layer's first 4) for c's normal h: A D(h)
    // `geometric` R(cos_vh) (before rho), after a Russian roulette below
    // settings.roulette_weight on the value with R = 1 (a mirror's complex
    // Fresnel is evaluated for the survivors only); q its survival
    // probability, 0 when the connection ends.
    struct ChainKernel {
        std::array<double, 4> per_kind{};
        double q = 0.0;
    };
    ChainKernel chainKernel(const LayerFlakes& lf, const Vec3& h, double cos_vh, double geometric,
                            double factor, PathRng& chain_rng);
    // Delta-chain walk: the cavity connections (cavity_chain.h) from the
    // flight of `length` µm ahead, which began at a reflection off a flake of
    // this layer (changeBack(0)).
    void cavityConnections(const Slice& s, const LayerFlakes& lf, double length, double sigma);
    // One chain (j round trips, m flakes gone back over; m = 0: ending at c)
    // of a cavity connection's draw, its score times form_weight (returned too).
    // Its target before the flakes gone back over (M_2 ... M_m u; M_1 u at m = 0)
    // and the turn towards it from x_1 (cavityTurn), shared by every round-trip
    // count j >= 1 (j = 0 takes the half vector: oneTripNormal).
    struct CavityAim {
        Vec3 target;
        CavityTurn turn;
    };
    Vec3 cavityTarget(const Vec3& u, int m) const;
    double cavityFormConnection(const Slice& s, const LayerFlakes& lf, const ChainDraw& draw,
                                const CavityAim& aim, int trips, int m, double form_weight,
                                PathRng& chain_rng);
    // Their chain from the drawn flake c (mc_walker_cavity.cpp): the legs'
    // plan, and one normal's score (added to chainOut(), returned) times `factor`.
    struct CavityLeg;
    double cavityNormalScore(const Slice& s, const LayerFlakes& lf, const ChainDraw& draw,
                             const CavityNormal& normal, CavityLeg& leg, double factor, PathRng& chain_rng);
    double traceCavityChain(const Slice& s, const LayerFlakes& lf, const CavityLeg& leg) const;
    // The transmittance of a drawn flake c of `kind` (centre, unit normal n, radius) to the path's
    // previous legs: the product of its T over the legs that cross it within the layer's depths
    // (with c in the tile, the path so far is the branch that passed c there; a mirror: 0).
    double legsTransmittance(const Vec3& centre, const Vec3& n, double radius_um, const FlakeKind& kind,
                             const LastFlakeLaw& law) const;
    // Reverse walk: the estimates from a pigment collision and from the smooth substrate.
    void reverseFromPigment(const Slice& s, double sigma);
    void reverseFromLambert(const Slice& s);
    // Whether the exit direction of upward v (in slice j) lies in a cone: n sin(theta) is kept up to the
    // ambient.
    bool headsIntoCone() const;
    // A pigment collision's chance to run cone k's connections: the share
    // q = sigma_s / sigma of the collisions that scatter, times the cone's boost.
    double coneCollisionRate(double q, std::size_t k) const {
        return nee_boost.empty() ? q : std::min(1.0, q * nee_boost[k]);
    }

private:
    template <class Score, class ConeWeight>
    void eachCone(const Slice& s, const Score& score, const ConeWeight& cone_weight);
    template <class Emitted, class ConeWeight>
    void coneNextEvent(const Slice& s, const Emitted& emitted, const ConeWeight& cone_weight);
    template <class ConeWeight>
    void coneFlakeImages(const Slice& s, double factor, const ConeWeight& cone_weight);
    template <class Emitted> void reverseNextEvent(const Slice& s, const Emitted& emitted);
    void reverseReflectedBeams(const Slice& s, double factor);
};

}  // namespace paintlab::mc
