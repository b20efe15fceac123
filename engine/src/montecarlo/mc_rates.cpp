#include "mc_rates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace paintlab::mc {

std::array<double, 3> cheapestRates(const std::array<RateTerm, 3>& terms, double budget) {
    std::array<double, 3> x{};
    std::array<bool, 3> held{};
    for (std::size_t t = 0; t < 3; ++t) {
        held[t] = !(terms[t].variance > 0.0);
        x[t] = held[t] ? terms[t].lo : terms[t].hi;
    }
    if (!(budget > 0.0)) return x;
    for (int pass = 0; pass < 4; ++pass) {
        double left = budget;
        double sum = 0.0;
        for (std::size_t t = 0; t < 3; ++t) {
            if (held[t])
                left -= terms[t].variance / x[t];
            else
                sum += std::sqrt(terms[t].variance * terms[t].cost);
        }
        if (!(sum > 0.0)) break;
        if (!(left > 0.0)) {
            for (std::size_t t = 0; t < 3; ++t)
                if (!held[t]) x[t] = terms[t].hi;
            break;
        }
        bool changed = false;
        for (std::size_t t = 0; t < 3; ++t) {
            if (held[t]) continue;
            x[t] = std::sqrt(terms[t].variance / terms[t].cost) * sum / left;
            if (x[t] > terms[t].hi || x[t] < terms[t].lo) {
                x[t] = std::clamp(x[t], terms[t].lo, terms[t].hi);
                held[t] = true;
                changed = true;
            }
        }
        if (!changed) break;
    }
    return x;
}

DeltaWalkModel deltaWalkModel(const Sums& total, bool delta_walks, double current_share) {
    DeltaWalkModel model;
    model.shares = {current_share};
    const std::size_t exits = total.cones.size();
    model.v1.assign(exits, 0.0);
    model.chain_m2.assign(exits, 0.0);
    if (!delta_walks || exits == 0 || !(total.cones[0].delta_samples > 1.0)) return model;
    model.measured = true;
    const ConeStats& c0 = total.cones[0];
    const double n = c0.delta_samples;
    const double n_chain = c0.chain_samples;
    // Every walk so far ran the connections: D(1) is their measured variance as it is.
    const bool all_chained = n_chain == n;
    for (std::size_t k = 0; k < exits; ++k) {
        const ConeStats& cs = total.cones[k];
        const double mean = cs.delta_s1 / n;
        const double measured = std::max(0.0, cs.delta_s2 / n - mean * mean);
        if (n_chain > 1.0) {
            model.chain_m2[k] = cs.chain_s2 / n_chain;
            model.v1[k] = all_chained ? measured
                                      : std::max(0.0, cs.escape_s2 / n + 2.0 * cs.chain_cross / n_chain +
                                                          model.chain_m2[k] - mean * mean);
        } else {
            model.v1[k] = measured;
        }
    }
    model.walk_cost = c0.delta_cost / n;
    // Heavy tails (kMaxChainTermShare): E[C^2] is then no measure, and a
    // thinned outlier would weigh 1 / s.
    const bool heavy = std::any_of(total.cones.begin(), total.cones.end(), [](const ConeStats& cs) {
        return cs.chain_s2 > 0.0 && cs.chain_max2 > kMaxChainTermShare * cs.chain_s2;
    });
    if (n_chain > 1.0) {
        model.bare_cost = (c0.delta_cost - c0.chain_cost) / n;
        model.chain_cost = c0.chain_cost / n_chain;
        model.all_chained = all_chained;
        model.shares.clear();
        for (double s = 1.0; s >= kMinDeltaChainShare * 0.9999 && (s == 1.0 || !heavy); s *= 0.5)
            model.shares.push_back(s);
    }
    return model;
}

double DeltaWalkModel::variance(std::size_t k, double share) const {
    return share >= 1.0 ? v1[k] : v1[k] + chain_m2[k] * (1.0 / share - 1.0);
}

double DeltaWalkModel::cost(double share) const {
    if (!(chain_cost > 0.0)) return walk_cost;
    // With every walk chained so far, the cost at share 1 is the measured one as it is.
    return all_chained ? walk_cost - (1.0 - share) * chain_cost : bare_cost + share * chain_cost;
}

std::vector<std::pair<double, double>> DeltaWalkModel::options(const std::vector<double>& rates) const {
    std::vector<std::pair<double, double>> out;
    for (const double d : rates)
        for (const double s : shares) out.emplace_back(d, s);
    return out;
}

RateFit adaptRates(const Sums& total, std::size_t histogram_entries, bool reverse_walks, bool delta_walks,
                   ConeRates& rates) {
    const std::size_t exits = total.cones.size();
    const auto n = static_cast<double>(total.paths);
    const double c_walk = kCostPerPath + kCostPerWalkStep * total.walk_cost / n;
    double nee_rate = 0.0;
    for (const auto& c : total.cones) nee_rate += c.nee_rate;
    const double c_nee = nee_rate > 0.0 ? std::max(0.01, total.nee_cost / nee_rate) : 0.5;
    // Per cone: the three rates' variance coefficients, costs and bounds (next-event, glint, reverse).
    std::vector<std::array<RateTerm, 3>> terms(exits);
    std::vector<double> a(exits), f2(exits);
    for (std::size_t k = 0; k < exits; ++k) {
        const ConeStats& cs = total.cones[k];
        const std::size_t h = histogram_entries + k;
        const double v_hist = total.paths > 1 ? total.m2[h] / (n - 1.0) : 0.0;
        const double mean_x = cs.nee_s1 / n;
        RateTerm nee{cs.nee_s2 / n, c_nee, kMinFraction, kMaxNeeRate};
        RateTerm glint{0.0, kCostPerGlint, kMinGlintRate, kMaxGlintRate};
        if (cs.glint_samples > 1.0) {
            const double mean_g = cs.glint_s1 / cs.glint_samples;
            glint.variance = std::max(0.0, cs.glint_s2 / cs.glint_samples - mean_g * mean_g);
            glint.cost = kCostPerGlint + kCostPerGlintRay * cs.glint_rays / cs.glint_samples;
        }
        RateTerm reverse{0.0, 1.0, kMinReverseRate, kMaxReverseRate};
        if (reverse_walks && cs.reverse_samples > 1.0) {
            const double mean_r = cs.reverse_s1 / cs.reverse_samples;
            reverse.variance = std::max(0.0, cs.reverse_s2 / cs.reverse_samples - mean_r * mean_r);
            reverse.cost = std::max(0.05, cs.reverse_cost / cs.reverse_samples);
        }
        terms[k] = {nee, glint, reverse};
        a[k] = std::max(0.0, v_hist - mean_x * mean_x);
        const double f = total.mean[kFirstExit + k];
        f2[k] = f * f;
    }
    // The delta-chain walks serve every cone at once: one common rate d, scanned
    // over powers of two, its variance D_k / d joining A; with it the share s
    // of them that run the chain connections (DeltaWalkModel).
    const DeltaWalkModel delta = deltaWalkModel(total, delta_walks, rates.delta_chain_share);
    std::vector<double> delta_rates{rates.delta_rate};
    if (delta.measured) {
        delta_rates.clear();
        for (double d = kMinDeltaRate; d <= kMaxDeltaRate * 1.0001; d *= 2.0) delta_rates.push_back(d);
    }
    double best = std::numeric_limits<double>::infinity();
    double best_share = rates.delta_chain_share;
    std::vector<std::array<double, 3>> x(exits);
    std::vector<double> delta_variance(exits, 0.0);
    for (const auto& [d, share] : delta.options(delta_rates)) {
        std::vector<double> a_d(exits);
        for (std::size_t k = 0; k < exits; ++k) a_d[k] = a[k] + delta.variance(k, share) / d;
        const auto variance = [&](std::size_t k, const std::array<double, 3>& at) {
            double v = a_d[k];
            for (std::size_t t = 0; t < 3; ++t) v += terms[k][t].variance / at[t];
            return v;
        };
        double rho_min = 0.0;  // the worst cone's relative variance at the largest rates
        for (std::size_t k = 0; k < exits; ++k)
            if (f2[k] > 0.0)
                rho_min =
                    std::max(rho_min, variance(k, {kMaxNeeRate, kMaxGlintRate, kMaxReverseRate}) / f2[k]);
        if (!(rho_min > 0.0)) continue;
        for (int step = 0; step < 200; ++step) {
            const double rho = rho_min * std::pow(1.06, step);
            double cost = c_walk + d * delta.cost(share);
            double worst = 0.0;
            for (std::size_t k = 0; k < exits; ++k) {
                if (f2[k] > 0.0) {
                    x[k] = cheapestRates(terms[k], rho * f2[k] - a_d[k]);
                    worst = std::max(worst, variance(k, x[k]) / f2[k]);
                } else {
                    for (std::size_t t = 0; t < 3; ++t) x[k][t] = terms[k][t].lo;
                }
                for (std::size_t t = 0; t < 3; ++t)
                    if (t == 0 || terms[k][t].variance > 0.0) cost += x[k][t] * terms[k][t].cost;
            }
            if (worst * cost < best) {
                best = worst * cost;
                rates.delta_rate = d;
                best_share = share;
                for (std::size_t k = 0; k < exits; ++k) {
                    rates.nee_fraction[k] = x[k][0];
                    rates.glint_rate[k] = x[k][1];
                    rates.reverse_rate[k] = x[k][2];
                }
            }
        }
    }
    rates.delta_chain_share = best_share;
    for (std::size_t k = 0; k < exits; ++k) delta_variance[k] = delta.variance(k, best_share);
    return {std::move(f2), std::move(delta_variance)};
}

}  // namespace paintlab::mc
