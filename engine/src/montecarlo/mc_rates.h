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
// The smallest share of their flights that run the drawn cavity chain (ConeRates::drawn_chain_rate).
inline constexpr double kMinDrawnChainRate = 1.0 / 8.0;
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
    // The share q of their flights that run the drawn cavity chain, its score
    // divided by it (McSettings::drawn_chain_rate): on the grid's mirror
    // flakes over black the drawn chains cost more than they take.
    double drawn_chain_rate = 1.0;
    bool drawn_chain_rate_adapts = true;  // false: held (McSettings::adapt_drawn_chain_rate)
    // L of their last-flake connections' rate by flight length, µm (0: every
    // flight; chain_length_rate.h), chosen among kChainLengthsUm.
    double chain_length_um = 0.0;
    bool chain_length_adapts = true;  // false: held (McSettings::adapt_chain_length)
};

// Per cone: f^2 and the delta walks' variance per walk (the promise's and the
// first-flake walks' learning reuse them); and the model's forecast of the
// worst cone's relative variance per path (V_k / f_k^2) at the rates chosen
// and at the rates they replaced.
struct RateFit {
    std::vector<double> f2;
    std::vector<double> delta_variance;
    double rel_variance = 0.0;
    double previous_rel_variance = 0.0;
    // The model's parts at the rates in force (their worst cone's sum is previous_rel_variance).
    RateAccount account;
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
// scanned over a geometric grid. The delta walks' common rate d, the share s
// of them that run the chain connections and the share q of those walks'
// flights that run the drawn cavity chain are scanned with it: per walk the
// variance is D_k(s, q) = D_k(1, 1) + E[C_k^2] (1 / s - 1) + E[sum Y_k^2]
// (1 / q - 1) / s (C_k what the connections score, Y_k a flight's drawn
// chain) at a cost of c_bare + s (c_chain + q c_drawn). Only the next paths'
// fractions change, so each path's estimate stays unbiased.
// Sets `rates` and returns the model's inputs that the job runner reuses.
// `histogram_entries`: the index of the first histogram-part entry (one per
// cone) in the sample vector; total.cones has one entry per cone.
// The delta-chain walks' variance and cost per walk against the share s that
// runs the chain connections and the drawn chains' rate q, from their split
// sums (ConeStats, CavityFormLearning): per cone D_k(1, 1) = E[E^2] + 2 E[E C]
// + E[C^2] - f_delta^2, E[C^2] (C unweighted by the share and the rate) and
// E[sum Y^2], and per walk c_bare + s (c_chain + q c_drawn). `shares`: those
// adaptRates scans (1, 1/2, ... kMinDeltaChainShare once the split is
// measured and no cone's largest C^2, less the drawn chains' part, is beyond
// kMaxChainTermShare of its sum; 1 when one is; else the current share
// alone); `drawn_rates` likewise (1 ... kMinDrawnChainRate once the drawn
// chains are measured, unless held); the pairs (s, q) scanned filtered by `allowed`.
struct DeltaWalkModel {
    bool measured = false;  // the walks have samples (else only the current rate and share)
    std::vector<double> v1;
    std::vector<double> chain_m2;
    std::vector<double> drawn_m2;  // E[sum over a chained walk's flights of Y^2] at q = 1
    double walk_cost = 0.0;        // per walk, as run so far
    double bare_cost = 0.0;
    double chain_cost = 0.0;  // per walk that runs the connections, without the drawn chains
    double drawn_cost = 0.0;  // ... the drawn chains' at q = 1
    std::vector<double> shares;
    std::vector<double> drawn_rates;
    // A pair (s, q) with s < 1 or q < 1 only while no single flight's drawn
    // Y^2 (1 / (s q) - 1), the variance its thinning would add, is beyond
    // kMaxChainTermShare of the cone's sum of the walks' variance
    // (drawn_limit): the drawn chains' scores are heavy-tailed among
    // themselves (on silver their largest term is 10-100 % of their sum)
    // but a small part of the walks' variance.
    std::vector<double> drawn_max2;
    std::vector<double> drawn_limit;
    // The last-flake connections' rate by length (chain_length_rate.h): the
    // options' L, the current first (then the candidates, once measured and
    // adapting); per option and cone ([o * cones + k], per chained walk) the
    // variance it adds to C^2 and the largest single flight's part of it;
    // per option the connections per chained walk; the cost of one. v1 and
    // chain_m2 above are at L = 0 (what the current L added taken out).
    // An option is allowed while max2 / s stays within drawn_limit's share.
    std::vector<double> length_um;
    std::vector<double> length_m2;
    std::vector<double> length_max2;
    std::vector<double> length_connections;
    double connection_cost = 0.0;
    std::vector<double> length_limit;
    bool allowed(double share, double drawn_rate, std::size_t length = 0) const;
    double variance(std::size_t k, double share, double drawn_rate, std::size_t length = 0) const;
    double cost(double share, double drawn_rate, std::size_t length = 0) const;
};
DeltaWalkModel deltaWalkModel(const Sums& total, bool delta_walks, double current_share,
                              double current_drawn_rate = 1.0, bool drawn_rate_adapts = true,
                              double current_length_um = 0.0, bool length_adapts = false);

RateFit adaptRates(const Sums& total, std::size_t histogram_entries, bool reverse_walks, bool delta_walks,
                   ConeRates& rates);

}  // namespace paintlab::mc
