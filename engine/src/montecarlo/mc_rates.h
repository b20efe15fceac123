#pragma once
// The adaptive rates (McSettings::adaptive_fractions): per exit cone the share
// of paths that run next-event connections (beyond 1, the boost of each
// collision's chance), the glint samples and reverse walks per path, and the
// delta-chain walks per path, chosen after every round from the cones'
// variances so far and a cost model of counted work.

#include "mc_statistics.h"

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace paintlab::mc {

// Reverse walks per path and cone: at most (so that sample j of a chunk has a unique stream).
inline constexpr double kMaxReverseRate = 4.0;
inline constexpr double kMinReverseRate = 1.0 / 256.0;
// Delta-chain walks per path (the same bound).
inline constexpr double kMaxDeltaRate = 4.0;
inline constexpr double kMinDeltaRate = 1.0 / 64.0;
// The smallest share of the delta-chain walks that run the chain connections
// (ConeRates::delta_chain_share): their scores then carry at most 8 times the weight.
inline constexpr double kMinDeltaChainShare = 1.0 / 8.0;
// ... and only while no single walk's connections carry more than this share
// of any cone's sum of C^2: where one does (heavy tails, as on the grid's
// 50 µm flakes; the measured shares in docs/PERFORMANCE.md), the mean square
// is no measure of the variance thinning adds, and a thinned outlier weighs 1 / s.
inline constexpr double kMaxChainTermShare = 0.1;
// Bounds of the adaptive fractions: next-event rate (the share of paths up to
// 1, beyond it the boost of every collision's chance), glint samples per path.
inline constexpr double kMinFraction = 1.0 / 64.0;
inline constexpr double kMaxNeeRate = 64.0;
inline constexpr double kMaxGlintRate = 4.0;
inline constexpr double kMinGlintRate = 1.0 / 64.0;
// Their cost model (thread-microseconds on the reference machine): per path
// (walk or delta-chain walk), per free path or tile intersection of a walk, per
// next-event attempt or intersection, per unit of a flake-image connection's
// work (reflectedBeams: a shadow ray or 64 candidate flakes tested), per glint
// sample and per intersection of its traces; fitted to measured times of the
// pearlescent demo (docs/PERFORMANCE.md; history in docs/CHANGELOG.md).
inline constexpr double kCostPerPath = 0.32;
inline constexpr double kCostPerWalkStep = 0.135;
inline constexpr double kCostPerNeeStep = 0.134;
inline constexpr double kCostPerImageRay = 3.6;
inline constexpr double kCostPerGlint = 1.2;
inline constexpr double kCostPerGlintRay = 0.13;

// One rate of a cone's variance model (adaptRates): its variance
// coefficient (the variance it adds per path is variance / x at rate x), the
// cost per unit of rate, and its bounds.
struct RateTerm {
    double variance = 0.0;
    double cost = 1.0;
    double lo = 0.0;
    double hi = 1.0;
};

// The cheapest rates (least sum x_t cost_t) with sum variance_t / x_t <= budget:
// x_t proportional to sqrt(variance_t / cost_t) (Lagrange), those beyond a bound
// held at it and the rest solved again for what is left; every rate at its top
// when the budget cannot be met; at its bottom a term without variance.
std::array<double, 3> cheapestRates(const std::array<RateTerm, 3>& terms, double budget);

// What a path of the next round runs, per exit cone (and the delta walks' common rate).
struct ConeRates {
    std::vector<double> nee_fraction;  // share of paths that run the cone's next-event connections
    std::vector<double> glint_rate;    // glint samples per path
    std::vector<double> reverse_rate;  // reverse walks per path
    double delta_rate = 0.25;          // delta-chain walks per path
    // The share of the delta-chain walks that run the chain connections (last
    // flake, cavity), their scores divided by it; the others score only the
    // escapes those connections leave (on mirror flakes a walk without them
    // costs a quarter to a third as much, and the escapes carry most of the
    // variance: docs/PERFORMANCE.md).
    double delta_chain_share = 1.0;
};

// Per cone: f^2 and the delta walks' variance per walk (the promise's and the
// first-flake walks' learning reuse them).
struct RateFit {
    std::vector<double> f2;
    std::vector<double> delta_variance;
};

// Adaptive fractions (McSettings::adaptive_fractions) from every path so
// far (`total`: the batches' sums merged in order, so deterministic). Per
// exit cone k the variance of f per path is modelled as
//   V_k(q, g, r) = A + B / q + C / g + D / r,   A = Var(histogram part) - E[X]^2,
// B = E[X^2] (X the raw next-event score of a path that runs it, q the share
// of paths that do), C = Var(raw glint sample) (g samples per path; the
// stratification only lowers it), D = Var(raw reverse-walk sample) (r walks
// per path), and the cost per path (microseconds on the reference machine,
// from counted work: free paths, tile intersections, connections;
// docs/PERFORMANCE.md) as c_walk + sum_k (q_k c_nee + g_k c_glint,k + r_k c_rev,k).
// The stop rule waits for the worst cone, so the fractions minimise
// max_k V_k / f_k^2 x cost: for a common level rho of V_k / f_k^2 each cone
// takes the cheapest (q, g, r) that reaches it (cheapestRates), and rho is
// scanned over a geometric grid. The delta walks' common rate d and the share s
// of them that run the chain connections are scanned with it: per walk the
// variance is D_k(s) = D_k(1) + E[C_k^2] (1 / s - 1) (C_k what the
// connections score) at a cost of c_bare + s c_chain. Only the next paths'
// fractions change, so each path's estimate stays unbiased.
// Sets `rates` and returns the model's inputs that the job runner reuses.
// `histogram_entries`: the index of the first histogram-part entry (one per
// cone) in the sample vector; total.cones has one entry per cone.
// The delta-chain walks' variance and cost per walk against the share s that
// runs the chain connections, from their split sums (ConeStats): per cone
// D_k(1) = E[E^2] + 2 E[E C] + E[C^2] - f_delta^2 and E[C^2] (C unweighted by
// the share), and per walk c_bare + s c_chain. `shares`: those adaptRates
// scans (1, 1/2, ... kMinDeltaChainShare once the split is measured and no
// cone's largest C^2 is beyond kMaxChainTermShare of its sum; 1 when one is;
// else the current share alone).
struct DeltaWalkModel {
    bool measured = false;  // the walks have samples (else only the current rate and share)
    std::vector<double> v1;
    std::vector<double> chain_m2;
    double walk_cost = 0.0;  // per walk, as run so far
    double bare_cost = 0.0;
    double chain_cost = 0.0;  // per walk that runs the connections
    bool all_chained = false;
    std::vector<double> shares;
    double variance(std::size_t k, double share) const;
    double cost(double share) const;
    // Every (rate, share) pair, the rates outermost.
    std::vector<std::pair<double, double>> options(const std::vector<double>& rates) const;
};
DeltaWalkModel deltaWalkModel(const Sums& total, bool delta_walks, double current_share);

RateFit adaptRates(const Sums& total, std::size_t histogram_entries, bool reverse_walks, bool delta_walks,
                   ConeRates& rates);

}  // namespace paintlab::mc
