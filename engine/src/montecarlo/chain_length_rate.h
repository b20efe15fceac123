#pragma once
// The last-flake connections' rate by flight length (McSettings::chain_length_um,
// issue 30). A delta walk's flight of length l connects to a cone with
// probability p(l) = min(1, l / L) and its score carries 1 / p. The score
// grows with l (the connection's point is uniform on the flight, weight l),
// so p proportional to l is the square-root rule's choice (p ~ sqrt(X^2 / c)
// at a fixed cost c per connection) for the flights shorter than L, and L
// trades the work they save against the variance they add. L is learned
// between rounds by the adaptive rates (DeltaWalkModel, mc_rates.h) from
// what the walks record here, for each candidate L_i at once.

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace paintlab::mc {

// The candidate L in µm (0: every flight connects), around the flakes'
// mean free paths at normal incidence (thickness / volume fraction: 7.5 µm
// in silver metallic, 1-30 µm over the grid's aluminium points).
inline constexpr std::array<double, 7> kChainLengthsUm{0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0};
inline constexpr std::size_t kChainLengths = kChainLengthsUm.size();

// The probability that a flight of `length_um` connects at L = `l_um`.
inline double chainLengthProbability(double length_um, double l_um) {
    return l_um > 0.0 ? std::min(1.0, length_um / l_um) : 1.0;
}

// What the delta walks' chained flights record for the choice of L, per
// candidate i and cone k ([i * cones + k]; sized by the first connection).
// X is a connection's score before the weights 1 / p (at the current L)
// and 1 / share, and a flight's connection ran with probability p_now:
// - m2: the sum of X^2 (1 / p_i - 1) / p_now (per walk its mean is the
//   variance that L_i adds to the walk's chain score);
// - max2: the largest single X^2 (1 / p_i - 1) (the heavy-tail guard);
// - excess[k]: the same at the current L (what it added to the walks' C^2);
// - connections[i]: the sum over every flight of p_i (the connections L_i
//   would run); steps and connected: the work of the connections that ran
//   (two walk steps each plus their tile intersections) and their count.
struct ChainLengthLearning {
    std::vector<double> m2;
    std::vector<double> max2;
    std::vector<double> excess;
    std::array<double, kChainLengths> connections{};
    double steps = 0.0;
    double connected = 0.0;
    void add(const ChainLengthLearning& other);
};

}  // namespace paintlab::mc
