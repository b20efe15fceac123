#include "mc_rates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
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

DeltaWalkModel deltaWalkModel(const Sums& total, bool delta_walks, double current_share,
                              double current_drawn_rate, bool drawn_rate_adapts, double current_length_um,
                              bool length_adapts) {
    DeltaWalkModel model;
    model.shares = {current_share};
    model.drawn_rates = {current_drawn_rate};
    model.length_um = {current_length_um};
    const std::size_t exits = total.cones.size();
    model.v1.assign(exits, 0.0);
    model.chain_m2.assign(exits, 0.0);
    model.drawn_m2.assign(exits, 0.0);
    model.length_m2.assign(exits, 0.0);
    model.length_max2.assign(exits, 0.0);
    model.length_connections = {0.0};
    if (!delta_walks || exits == 0 || !(total.cones[0].delta_samples > 1.0)) return model;
    model.measured = true;
    const ConeStats& c0 = total.cones[0];
    const double n = c0.delta_samples;
    const double n_chain = c0.chain_samples;
    const CavityFormLearning& drawn = total.form_learning;
    const bool drawn_measured =
        n_chain > 1.0 && drawn.drawn_s2.size() == exits && drawn.drawn_steps_at_one > 0.0;
    const ChainLengthLearning& lengths = total.length_learning;
    const bool length_measured = n_chain > 1.0 && lengths.excess.size() == exits && lengths.connected > 1.0;
    // Every walk so far ran the connections: D(1, 1) is their measured
    // variance less what the drawn chains' rate and the rate by length added.
    const bool all_chained = n_chain == n;
    for (std::size_t k = 0; k < exits; ++k) {
        const ConeStats& cs = total.cones[k];
        const double mean = cs.delta_s1 / n;
        const double measured = std::max(0.0, cs.delta_s2 / n - mean * mean);
        const double excess =
            (drawn_measured ? drawn.drawn_excess[k] : 0.0) + (length_measured ? lengths.excess[k] : 0.0);
        if (n_chain > 1.0) {
            model.chain_m2[k] = std::max(0.0, (cs.chain_s2 - excess) / n_chain);
            model.v1[k] = all_chained ? std::max(0.0, measured - excess / n)
                                      : std::max(0.0, cs.escape_s2 / n + 2.0 * cs.chain_cross / n_chain +
                                                          model.chain_m2[k] - mean * mean);
        } else {
            model.v1[k] = measured;
        }
        if (drawn_measured) model.drawn_m2[k] = drawn.drawn_s2[k] / n_chain;
    }
    model.walk_cost = c0.delta_cost / n;
    // Heavy tails (kMaxChainTermShare): a mean square is then no measure, and
    // a thinned outlier would weigh 1 / s (the drawn chains, whose scores are
    // left out of chain_max2, have their own guard: allowed).
    const bool heavy = std::any_of(total.cones.begin(), total.cones.end(), [](const ConeStats& cs) {
        return cs.chain_s2 > 0.0 && cs.chain_max2 > kMaxChainTermShare * cs.chain_s2;
    });
    if (n_chain > 1.0) {
        model.bare_cost = (c0.delta_cost - c0.chain_cost) / n;
        model.chain_cost = c0.chain_cost / n_chain;
        model.shares.clear();
        for (double s = 1.0; s >= kMinDeltaChainShare * 0.9999 && (s == 1.0 || !heavy); s *= 0.5)
            model.shares.push_back(s);
    }
    if (length_measured) {
        // Option 0 is the current L; then the candidates, while adapting.
        model.length_connections.clear();
        model.length_m2.clear();
        model.length_max2.clear();
        // An option: its L, per cone its added variance per chained walk (the
        // sums m2 over n_chain) and largest term, and its connections per walk.
        const auto add_option = [&](double l_um, std::span<const double> m2, std::span<const double> max2,
                                    double connections) {
            model.length_um.push_back(l_um);
            for (std::size_t k = 0; k < exits; ++k) {
                model.length_m2.push_back(m2[k] / n_chain);
                model.length_max2.push_back(max2.empty() ? 0.0 : max2[k]);
            }
            model.length_connections.push_back(connections / n_chain);
        };
        model.length_um.clear();
        // The current L: the excess it added and the connections that ran.
        add_option(current_length_um, lengths.excess, {}, lengths.connected);
        if (length_adapts)
            for (std::size_t i = 0; i < kChainLengths; ++i)
                if (kChainLengthsUm[i] != current_length_um)
                    add_option(kChainLengthsUm[i], std::span(lengths.m2).subspan(i * exits, exits),
                               std::span(lengths.max2).subspan(i * exits, exits), lengths.connections[i]);
        model.connection_cost = kCostPerWalkStep * lengths.steps / lengths.connected;
        model.length_limit.resize(exits);
        for (std::size_t k = 0; k < exits; ++k) model.length_limit[k] = kMaxChainTermShare * n * model.v1[k];
    }
    if (drawn_measured) {
        model.chain_cost = std::max(0.0, model.chain_cost - kCostPerWalkStep * drawn.drawn_steps / n_chain);
        model.drawn_cost = kCostPerWalkStep * drawn.drawn_steps_at_one / n_chain;
        if (!drawn_rate_adapts) return model;
        model.drawn_rates.clear();
        for (double q = 1.0; q >= kMinDrawnChainRate * 0.9999; q *= 0.5) model.drawn_rates.push_back(q);
        model.drawn_max2 = drawn.drawn_max2;
        model.drawn_limit.resize(exits);
        for (std::size_t k = 0; k < exits; ++k) model.drawn_limit[k] = kMaxChainTermShare * n * model.v1[k];
    }
    return model;
}

double DeltaWalkModel::variance(std::size_t k, double share, double drawn_rate, std::size_t length) const {
    const std::size_t exits = v1.size();
    return v1[k] + chain_m2[k] * (1.0 / share - 1.0) + drawn_m2[k] * (1.0 / drawn_rate - 1.0) / share +
           length_m2[length * exits + k] / share;
}

double DeltaWalkModel::cost(double share, double drawn_rate, std::size_t length) const {
    if (!(chain_cost + drawn_cost > 0.0)) return walk_cost;
    const double connections = length_connections[length] - length_connections[0];
    return bare_cost +
           share * std::max(0.0, chain_cost + drawn_rate * drawn_cost + connection_cost * connections);
}

bool DeltaWalkModel::allowed(double share, double drawn_rate, std::size_t length) const {
    for (std::size_t k = 0; k < drawn_max2.size() && k < drawn_limit.size(); ++k)
        if (drawn_max2[k] * (1.0 / (share * drawn_rate) - 1.0) > drawn_limit[k]) return false;
    const std::size_t exits = v1.size();
    for (std::size_t k = 0; k < length_limit.size(); ++k)
        if (length_max2[length * exits + k] / share > length_limit[k]) return false;
    return true;
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
    const DeltaWalkModel delta =
        deltaWalkModel(total, delta_walks, rates.delta_chain_share, rates.drawn_chain_rate,
                       rates.drawn_chain_rate_adapts, rates.chain_length_um, rates.chain_length_adapts);
    std::vector<double> delta_rates{rates.delta_rate};
    if (delta.measured) {
        delta_rates.clear();
        for (double d = kMinDeltaRate; d <= kMaxDeltaRate * 1.0001; d *= 2.0) delta_rates.push_back(d);
    }
    // The worst cone's relative variance per path at the rates in force (the
    // forecast's baseline), and the account of its parts and of the cost.
    double previous_rel_variance = 0.0;
    RateAccount account;
    account.cost_us_per_path[RateAccount::Walk] = c_walk;
    account.cost_us_per_path[RateAccount::DeltaWalks] =
        rates.delta_rate * delta.cost(rates.delta_chain_share, rates.drawn_chain_rate);
    const RateAccount::Part parts[3] = {RateAccount::NextEvent, RateAccount::Glints,
                                        RateAccount::ReverseWalks};
    for (std::size_t k = 0; k < exits; ++k) {
        const std::array<double, 3> now{rates.nee_fraction[k], rates.glint_rate[k], rates.reverse_rate[k]};
        std::array<double, RateAccount::kParts> v{};
        v[RateAccount::Walk] = a[k];
        v[RateAccount::DeltaWalks] =
            delta.variance(k, rates.delta_chain_share, rates.drawn_chain_rate) / rates.delta_rate;
        for (std::size_t t = 0; t < 3; ++t) {
            v[parts[t]] = terms[k][t].variance / now[t];
            if (t == 0 || terms[k][t].variance > 0.0)
                account.cost_us_per_path[parts[t]] += now[t] * terms[k][t].cost;
        }
        // Summed in the baseline's order of earlier versions (the same bits for the forecast).
        double sum = v[RateAccount::Walk] + v[RateAccount::DeltaWalks];
        for (const RateAccount::Part part : parts) sum += v[part];
        if (f2[k] > 0.0 && sum / f2[k] > previous_rel_variance) {
            previous_rel_variance = sum / f2[k];
            account.measured = true;
            account.worst_exit = k;
            for (std::size_t p = 0; p < v.size(); ++p) account.rel_variance_per_path[p] = v[p] / f2[k];
        }
    }
    double best = std::numeric_limits<double>::infinity();
    double best_worst = 0.0;
    double best_share = rates.delta_chain_share;
    double best_drawn_rate = rates.drawn_chain_rate;
    std::size_t best_length = 0;
    std::vector<std::array<double, 3>> x(exits);
    std::vector<double> delta_variance(exits, 0.0);
    const auto consider = [&](double d, double share, double drawn_rate, std::size_t length = 0) {
        std::vector<double> a_d(exits);
        for (std::size_t k = 0; k < exits; ++k)
            a_d[k] = a[k] + delta.variance(k, share, drawn_rate, length) / d;
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
        if (!(rho_min > 0.0)) return;
        for (int step = 0; step < 200; ++step) {
            const double rho = rho_min * std::pow(1.06, step);
            double cost = c_walk + d * delta.cost(share, drawn_rate, length);
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
                best_worst = worst;
                rates.delta_rate = d;
                best_share = share;
                best_drawn_rate = drawn_rate;
                best_length = length;
                for (std::size_t k = 0; k < exits; ++k) {
                    rates.nee_fraction[k] = x[k][0];
                    rates.glint_rate[k] = x[k][1];
                    rates.reverse_rate[k] = x[k][2];
                }
            }
        }
    };
    // The walk rate and the share at the current drawn rate; then every
    // (share, drawn rate) at the best walk rate; then the walk rate at the
    // best pair: 61 options where all triples are 144 and made a round's
    // scan three times as long (~13 ms; the walk rate barely moves the best
    // pair).
    const double q_now = delta.allowed(1.0, rates.drawn_chain_rate) ? rates.drawn_chain_rate : 1.0;
    for (const double d : delta_rates)
        for (const double share : delta.shares)
            if (delta.allowed(share, q_now)) consider(d, share, q_now);
    const double d_best = rates.delta_rate;
    for (const double share : delta.shares)
        for (const double q : delta.drawn_rates)
            if (q != q_now && delta.allowed(share, q)) consider(d_best, share, q);
    if (best_drawn_rate != q_now) {
        const double share = best_share;
        const double q = best_drawn_rate;
        for (const double d : delta_rates)
            if (d != d_best) consider(d, share, q);
    }
    // Then every L of the rate by length at the best (d, s, q).
    for (std::size_t length = 1; length < delta.length_um.size(); ++length)
        if (delta.allowed(best_share, best_drawn_rate, length))
            consider(rates.delta_rate, best_share, best_drawn_rate, length);
    rates.delta_chain_share = best_share;
    rates.drawn_chain_rate = best_drawn_rate;
    rates.chain_length_um = delta.length_um[best_length];
    for (std::size_t k = 0; k < exits; ++k)
        delta_variance[k] = delta.variance(k, best_share, best_drawn_rate, best_length);
    return {std::move(f2), std::move(delta_variance), best_worst, previous_rel_variance, account};
}

}  // namespace paintlab::mc
