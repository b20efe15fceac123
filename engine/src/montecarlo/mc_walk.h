#pragma once
// One Monte Carlo path through the paint at one wavelength (mc_walk.cpp).

#include "flake_tile.h"
#include "mc_random.h"
#include "mc_stack.h"

#include <span>

namespace paintlab::mc {

struct WalkSettings {
    int max_events = 1000000;
    double roulette_weight = 0.1;
};

// Histogram estimator of f around an exit direction: escaping weight inside
// the cone of half-angle alpha, divided by the cone's projected solid angle
// pi sin^2(alpha) cos(theta_o), estimates the cone average of f cos / the
// cone average of cos.
struct HistogramBin {
    Vec3 wo;
    double cos_cone = 1.0;
    double projected_solid_angle = 0.0;
};

// Explicit flakes of one layer: its tile and the optics of its kinds at this
// wavelength, in the tile's kind order.
struct LayerFlakes {
    const FlakeTile* tile = nullptr;
    std::vector<FlakeKind> kinds;
};

struct PathContext {
    const PaintStack& stack;
    std::span<const ExitChain> chains;             // next-event estimator (empty: off)
    std::span<const HistogramBin> bins;            // histogram estimator (empty: off)
    std::span<const LayerFlakes> explicit_flakes;  // per layer (empty: flakes are a continuum)
    WalkSettings settings;
};

// Traces a path that has just been refracted into the top slice with
// propagation direction v (v.z < 0) and weight (power per unit surface area)
// `weight`, starting at lateral position (x, y). Adds to f_out[k] the
// estimate of f for chains[k] or bins[k] and returns the weight that leaves
// through the top interface. Never throws.
double tracePath(const PathContext& context, Vec3 v, double weight, double x, double y, PathRng& rng,
                 std::span<double> f_out);

}  // namespace paintlab::mc
