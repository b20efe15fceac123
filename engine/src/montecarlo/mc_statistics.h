#pragma once
// Statistics of a job's paths (mc_engine.h): per entry of the paths' sample
// vector the mean and M2 of a chunk or batch, merged in chunk order, the cone
// statistics of the adaptive rates (mc_rates.h), and the standard errors over
// paths or over batches.

#include "cavity_chain.h"
#include "chain_length_rate.h"
#include "paintlab/engine/montecarlo/monte_carlo.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

// A path's sample vector (mc_engine.h): the weight that escapes through the top,
// the weight transmitted into a transparent substrate, then f at each exit.
inline constexpr std::size_t kEscaped = 0;
inline constexpr std::size_t kTransmitted = 1;
inline constexpr std::size_t kFirstExit = 2;

// Per exit cone, what the adaptive connection fractions (adaptRates, mc_rates.h)
// need besides the per-path entries: the raw next-event score of the paths
// that ran it (unweighted by the fraction), the raw glint samples, and costs.
struct ConeStats {
    // Over every path (Sums::paths of them), with or without connections:
    double nee_rate = 0.0;  // sum of their rates x (the cost's unit)
    double nee_s1 = 0.0;    // sum of the weighted scores Y (E[Y] = E[X])
    double nee_s2 = 0.0;    // sum of x Y^2 (E[x Y^2] = E[X^2] at x <= 1)
    double glint_samples = 0.0;
    double glint_s1 = 0.0;
    double glint_s2 = 0.0;
    double glint_rays = 0.0;
    double reverse_samples = 0.0;
    double reverse_s1 = 0.0;
    double reverse_s2 = 0.0;
    double reverse_cost = 0.0;   // microseconds on the reference machine (the cost model below)
    double delta_samples = 0.0;  // delta-chain walks (shared by every cone: same count in each)
    double delta_s1 = 0.0;
    double delta_s2 = 0.0;
    double delta_cost = 0.0;
    // The same walks' score X = E + C split (ConeRates::delta_chain_share):
    // E what their escapes score, C what their chain connections score (C
    // unweighted by the share; only over the walks that ran them), and the
    // connections' part of their cost. Empty while nothing splits them.
    double escape_s2 = 0.0;      // sum of E^2 over every walk
    double chain_samples = 0.0;  // walks that ran the chain connections
    double chain_s2 = 0.0;       // sum of C^2 over those
    double chain_cross = 0.0;    // sum of E C over those
    double chain_cost = 0.0;     // their connections' cost (in delta_cost too)
    double chain_max2 = 0.0;     // the largest C^2 less the drawn cavity chains' part
    void add(const ConeStats& o);
};

// Statistics of the paths of one chunk or batch per sample-vector entry
// (mc_engine.h): mean and sum of squared deviations M2, merged by Chan et
// al.'s pairwise update (each path's total contribution is one independent
// sample). Unlike sum x^2 / n - mean^2 this keeps a zero-variance estimate
// (every path the same) exactly zero.
struct Sums {
    std::int64_t paths = 0;
    std::vector<double> mean;
    std::vector<double> m2;
    std::vector<ConeStats> cones;  // adaptive fractions only
    double walk_cost = 0.0;        // free paths + tile intersections of the walks
    double nee_cost = 0.0;         // the next-event and flake-image connections' cost (the model's µs)
    double nee_attempts = 0.0;
    // First-flake walks (first_flake.h), per proposal key: how many were drawn
    // from it, and per key and cone the sum of (f P_G / A_G)^2, f the walk's
    // estimate (JobRunner::learnFirstFlakeProposal).
    std::vector<double> first_count;
    std::vector<double> first_s2;      // [key * cones + k]
    CavityFormLearning form_learning;  // the delta walks' drawn cavity chains (cavity_chain.h)
    ChainLengthLearning
        length_learning;  // their last-flake connections' rate by length (chain_length_rate.h)

    explicit Sums(std::size_t entries = 0, std::size_t cone_count = 0)
        : mean(entries, 0.0), m2(entries, 0.0), cones(cone_count) {}
    void add(const Sums& other);
};

// Mean and standard error over paths from the mean and the sum of squared deviations M2.
Estimate pooledEstimate(double mean, double m2, std::int64_t paths);
// Over batches: the pooled mean m and the spread of the batches' means m_k
// weighted by their path counts n_k (or the paths' summed weights; N in all,
// K batches with paths): se^2 = K / (K - 1) sum_k (n_k / N)^2 (m_k - m)^2.
Estimate batchMeansEstimate(std::span<const double> batch_means, std::span<const double> batch_paths);

}  // namespace paintlab::mc
