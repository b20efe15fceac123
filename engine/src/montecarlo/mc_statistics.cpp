#include "mc_statistics.h"

#include "paintlab/engine/montecarlo/mc_table.h"

#include <algorithm>
#include <cmath>

namespace paintlab::mc {

namespace {

void addElementwise(std::vector<double>& to, const std::vector<double>& from) {
    if (to.size() < from.size()) to.resize(from.size(), 0.0);
    for (std::size_t i = 0; i < from.size(); ++i) to[i] += from[i];
}

}  // namespace

void CavityFormLearning::add(const CavityFormLearning& other) {
    addElementwise(m2_over_p, other.m2_over_p);
    for (std::size_t i = 0; i < available.size(); ++i) available[i] += other.available[i];
    addElementwise(drawn_s1, other.drawn_s1);
    addElementwise(drawn_s2, other.drawn_s2);
    addElementwise(drawn_excess, other.drawn_excess);
    if (drawn_max2.size() < other.drawn_max2.size()) drawn_max2.resize(other.drawn_max2.size(), 0.0);
    for (std::size_t k = 0; k < other.drawn_max2.size(); ++k)
        drawn_max2[k] = std::max(drawn_max2[k], other.drawn_max2[k]);
    drawn_steps += other.drawn_steps;
    drawn_steps_at_one += other.drawn_steps_at_one;
}

void ChainLengthLearning::add(const ChainLengthLearning& other) {
    addElementwise(m2, other.m2);
    addElementwise(excess, other.excess);
    if (max2.size() < other.max2.size()) max2.resize(other.max2.size(), 0.0);
    for (std::size_t i = 0; i < other.max2.size(); ++i) max2[i] = std::max(max2[i], other.max2[i]);
    for (std::size_t i = 0; i < kChainLengths; ++i) connections[i] += other.connections[i];
    steps += other.steps;
    connected += other.connected;
}

void ConeStats::add(const ConeStats& o) {
    delta_samples += o.delta_samples;
    delta_s1 += o.delta_s1;
    delta_s2 += o.delta_s2;
    delta_cost += o.delta_cost;
    escape_s2 += o.escape_s2;
    chain_samples += o.chain_samples;
    chain_s2 += o.chain_s2;
    chain_cross += o.chain_cross;
    chain_cost += o.chain_cost;
    chain_max2 = std::max(chain_max2, o.chain_max2);
    reverse_samples += o.reverse_samples;
    reverse_s1 += o.reverse_s1;
    reverse_s2 += o.reverse_s2;
    reverse_cost += o.reverse_cost;
    nee_rate += o.nee_rate;
    nee_s1 += o.nee_s1;
    nee_s2 += o.nee_s2;
    glint_samples += o.glint_samples;
    glint_s1 += o.glint_s1;
    glint_s2 += o.glint_s2;
    glint_rays += o.glint_rays;
}

void Sums::add(const Sums& other) {
    for (std::size_t k = 0; k < cones.size() && k < other.cones.size(); ++k) cones[k].add(other.cones[k]);
    addElementwise(first_count, other.first_count);
    addElementwise(first_s2, other.first_s2);
    form_learning.add(other.form_learning);
    length_learning.add(other.length_learning);
    walk_cost += other.walk_cost;
    nee_cost += other.nee_cost;
    nee_attempts += other.nee_attempts;
    if (other.paths == 0) return;
    const auto na = static_cast<double>(paths);
    const auto nb = static_cast<double>(other.paths);
    const double n = na + nb;
    for (std::size_t k = 0; k < mean.size(); ++k) {
        const double delta = other.mean[k] - mean[k];
        mean[k] += delta * nb / n;
        m2[k] += other.m2[k] + delta * delta * na * nb / n;
    }
    paths += other.paths;
}

Estimate pooledEstimate(double mean, double m2, std::int64_t n) {
    if (n <= 0) return {};
    const auto dn = static_cast<double>(n);
    const double var = n > 1 ? m2 / (dn - 1.0) : 0.0;
    return {mean, std::sqrt(var / dn)};
}

Estimate batchMeansEstimate(std::span<const double> batch_means, std::span<const double> batch_paths) {
    double total = 0.0;
    double dn = 0.0;
    for (std::size_t b = 0; b < batch_means.size(); ++b) {
        total += batch_means[b] * batch_paths[b];
        dn += batch_paths[b];
    }
    if (!(dn > 0.0)) return {};
    const double mean = total / dn;
    const auto k = static_cast<double>(batch_means.size());
    if (k < 2.0) return {mean, 0.0};
    double var = 0.0;
    for (std::size_t b = 0; b < batch_means.size(); ++b) {
        const double d = (batch_means[b] - mean) * batch_paths[b] / dn;
        var += d * d;
    }
    return {mean, std::sqrt(var * k / (k - 1.0))};
}

// Declared in mc_table.h; defined here, apart from McEngine (Embree), for the fast
// model's table writer (fast_model/brdf_table_io.cpp).
Estimate batchEstimate(std::span<const double> per_batch) {
    if (per_batch.empty()) return {};
    const auto k = static_cast<double>(per_batch.size());
    double mean = 0.0;
    for (double v : per_batch) mean += v;
    mean /= k;
    if (per_batch.size() < 2) return {mean, 0.0};
    double var = 0.0;
    for (double v : per_batch) var += (v - mean) * (v - mean);
    return {mean, std::sqrt(var / (k - 1.0) / k)};
}

}  // namespace paintlab::mc
