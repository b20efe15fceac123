// The adaptive rates' model of the delta-chain walks (mc_rates.h): the share
// of them that run the chain connections, from the split of their score.

#include "mc_rates.h"
#include "mc_statistics.h"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <string>
#include <utility>

namespace paintlab {
namespace {

// One cone, f = 1, nothing but the delta walks: n walks whose score X = E + C
// has the given moments (E the escapes, C the chain connections, unweighted),
// a share `share` of them with connections, costs per walk c_bare and c_chain.
// The histogram, next-event, glint and reverse terms are zero.
mc::Sums deltaOnly(double n, double share, double e2, double ec, double c2, double c_bare, double c_chain) {
    constexpr std::size_t kHistogram = mc::kFirstExit + 1;
    mc::Sums total(kHistogram + 1, 1);
    total.paths = 100000;
    total.mean[mc::kFirstExit] = 1.0;
    mc::ConeStats& cs = total.cones[0];
    const double chained = n * share;
    cs.delta_samples = n;
    cs.delta_s1 = n * 1.0;  // E[X] = f: the walks carry the whole cone
    // Over the walks as run: E + C / share on the chained ones, E on the others.
    cs.delta_s2 = n * e2 + chained * (2.0 * ec / share + c2 / (share * share));
    cs.delta_cost = n * c_bare + chained * c_chain;
    cs.escape_s2 = n * e2;
    cs.chain_samples = chained;
    cs.chain_s2 = chained * c2;
    cs.chain_cross = chained * ec;
    cs.chain_cost = chained * c_chain;
    return total;
}

// The same walks with a drawn cavity chain on their chained walks' flights,
// run at rate q (ConeRates::drawn_chain_rate): per chained walk E[sum Y^2] =
// y2 (part of c2, the connections' E[C^2] at q = 1; the rate adds y2 (1 / q
// - 1) to what the walks record), the drawn chains' cost c_drawn at q = 1
// (part of the walk's cost at q c_drawn) and their largest Y^2.
void addDrawnChains(mc::Sums& total, double share, double q, double y2, double c_drawn, double max2) {
    mc::ConeStats& cs = total.cones[0];
    const double chained = cs.chain_samples;
    const double excess = y2 * (1.0 / q - 1.0);
    cs.chain_s2 += chained * excess;
    cs.delta_s2 += chained * excess / (share * share);
    cs.chain_cost += chained * q * c_drawn;
    cs.delta_cost += chained * q * c_drawn;
    mc::CavityFormLearning& drawn = total.form_learning;
    drawn.drawn_s2 = {chained * y2};
    drawn.drawn_excess = {chained * excess};
    drawn.drawn_max2 = {max2};
    drawn.drawn_steps = chained * q * c_drawn / mc::kCostPerWalkStep;
    drawn.drawn_steps_at_one = chained * c_drawn / mc::kCostPerWalkStep;
}

// The chained walks' last-flake connections at the rate by length
// (chain_length_rate.h), run at L = l_now: per candidate i of
// kChainLengthsUm the variance it adds to a chained walk's C^2 (added[i]),
// the connections per chained walk (connections[i], of which those at l_now
// are part of c_chain at c_connection each) and the largest single term.
void addLengthRate(mc::Sums& total, double share, double l_now, const std::array<double, 7>& added,
                   const std::array<double, 7>& connections, double c_connection,
                   const std::array<double, 7>& max2 = {}) {
    mc::ConeStats& cs = total.cones[0];
    const double chained = cs.chain_samples;
    std::size_t now = 0;
    while (mc::kChainLengthsUm[now] != l_now) ++now;
    cs.chain_s2 += chained * added[now];
    cs.delta_s2 += chained * added[now] / (share * share);
    mc::ChainLengthLearning& learned = total.length_learning;
    learned.m2.assign(mc::kChainLengths, 0.0);
    learned.max2.assign(max2.begin(), max2.end());
    for (std::size_t i = 0; i < mc::kChainLengths; ++i) {
        learned.m2[i] = chained * added[i];
        learned.connections[i] = chained * connections[i];
    }
    learned.excess = {chained * added[now]};
    learned.connected = chained * connections[now];
    learned.steps = learned.connected * c_connection / mc::kCostPerWalkStep;
}

// The rates of one cone, the delta walks' share at `share`.
mc::ConeRates oneConeRates(double share) {
    mc::ConeRates rates;
    rates.nee_fraction.assign(1, 1.0);
    rates.glint_rate.assign(1, 1.0);
    rates.reverse_rate.assign(1, 1.0);
    rates.delta_chain_share = share;
    return rates;
}

TEST(McRates, TheChainShareRecoversTheWalksVarianceFromTheirSplit) {
    // D(1) = E[E^2] + 2 E[E C] + E[C^2] - f^2 whatever share the walks ran
    // at, and D(s) = D(1) + E[C^2] (1 / s - 1), the variance of E + B C / s
    // with B a draw of probability s (exact algebra: the sums are exact).
    for (const double share : {1.0, 0.5, 0.25}) {
        const mc::Sums total = deltaOnly(1.0e4, share, 40.0, 0.04, 1.5, 3.0, 7.0);
        const mc::DeltaWalkModel model = mc::deltaWalkModel(total, true, share);
        ASSERT_TRUE(model.measured);
        EXPECT_NEAR(model.variance(0, 1.0, 1.0), 40.0 + 0.08 + 1.5 - 1.0, 1e-9) << "share " << share;
        EXPECT_NEAR(model.variance(0, 0.125, 1.0), 40.58 + 1.5 * 7.0, 1e-9) << "share " << share;
        EXPECT_NEAR(model.cost(1.0, 1.0), 10.0, 1e-9) << "share " << share;
        EXPECT_NEAR(model.cost(0.25, 1.0), 3.0 + 0.25 * 7.0, 1e-9) << "share " << share;
        ASSERT_EQ(model.shares.size(), 4U);
        EXPECT_EQ(model.shares.front(), 1.0);
        EXPECT_EQ(model.shares.back(), mc::kMinDeltaChainShare);
    }
}

TEST(McRates, FewWalksRunTheConnectionsWhereTheEscapesCarryTheVariance) {
    // Mirror flakes' flop (docs/PERFORMANCE.md): rare escapes carry the
    // variance (E[E^2] = 50 f^2), the connections little (E[C^2] = 0.95 f^2)
    // but 70 % of a walk's cost. Variance x cost per walk: 50 x 10 at share
    // 1 against (50 + 0.95 x 7) x 3.875 = 220 at 1/8, the smallest.
    mc::ConeRates rates = oneConeRates(1.0);
    const mc::Sums total = deltaOnly(1.0e4, 1.0, 50.0, 0.0475, 0.9525, 3.0, 7.0);
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.delta_chain_share, mc::kMinDeltaChainShare);
}

TEST(McRates, HeavyTailedConnectionsKeepEveryWalkOnThem) {
    // The case above, but one walk's connections carry 20 % of the cone's sum
    // of C^2 (kMaxChainTermShare 10 %): E[C^2] is then no measure of what
    // thinning would add (the grid's 50 µm mirror flakes), so share 1, also
    // from a share below it; at 5 % the thinning stands.
    mc::ConeRates rates = oneConeRates(0.25);
    mc::Sums total = deltaOnly(1.0e4, 0.25, 50.0, 0.0475, 0.9525, 3.0, 7.0);
    total.cones[0].chain_max2 = 0.2 * total.cones[0].chain_s2;
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.delta_chain_share, 1.0);
    total.cones[0].chain_max2 = 0.05 * total.cones[0].chain_s2;
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.delta_chain_share, mc::kMinDeltaChainShare);
}

TEST(McRates, EveryWalkRunsTheConnectionsWhereTheyCarryTheVariance) {
    // The interference flakes' chains: the connections carry the cone and its
    // variance (E[C^2] = 20 f^2), the escapes almost nothing; thinning the
    // connections would multiply their variance: share 1 (190 against 253 at 1/2).
    mc::ConeRates rates = oneConeRates(0.25);  // from an earlier round
    const mc::Sums total = deltaOnly(1.0e4, 0.25, 0.01, 0.001, 20.0, 3.0, 7.0);
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.delta_chain_share, 1.0);
}

TEST(McRates, TheForecastStartsFromTheModelAtTheRatesInForce) {
    // The first rates' kept paths weigh the model's relative variance per
    // path at the adapted rates over that at the rates in force (McEngine::run).
    // At the rates in force the model gives the walks' own variance per path,
    // D(1, 1) / d = (E[E^2] + 2 E[E C] + E[C^2] - f^2) / d at d = 1/4 walks
    // a path (every other term zero; exact algebra), and the rates it chose,
    // once in force, are forecast as the variance it chose them for, which
    // is below the first (the walks' share and rate now fit their variance).
    mc::ConeRates rates = oneConeRates(1.0);
    rates.delta_rate = 0.25;
    const mc::Sums total = deltaOnly(1.0e4, 1.0, 0.01, 0.001, 20.0, 3.0, 7.0);
    const mc::RateFit first = mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_NEAR(first.previous_rel_variance, (0.01 + 0.002 + 20.0 - 1.0) / 0.25, 1e-9);
    ASSERT_EQ(rates.delta_chain_share, 1.0);  // so the sums read the same at the new rates
    const mc::RateFit again = mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_NEAR(again.previous_rel_variance, first.rel_variance, 1e-12 * first.rel_variance);
    EXPECT_LT(first.rel_variance, first.previous_rel_variance);
}

TEST(McRates, TheAccountSplitsTheModelAtTheRatesInForceByPart) {
    // `mc --json`'s jobs[].rate_model: the parts of the worst cone's relative
    // variance per path add up to the forecast's baseline (the same sum), and
    // here all of it is the delta walks', D(1, 1) / d (the other terms are
    // zero); their cost per path is d c(1, 1) = 0.25 x 10 and the walk's the
    // fixed cost per path (no free paths recorded); glints and reverse walks
    // without samples cost nothing (exact algebra).
    mc::ConeRates rates = oneConeRates(1.0);
    rates.delta_rate = 0.25;
    const mc::Sums total = deltaOnly(1.0e4, 1.0, 0.01, 0.001, 20.0, 3.0, 7.0);
    const mc::RateFit fit = mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    const mc::RateAccount& a = fit.account;
    ASSERT_TRUE(a.measured);
    EXPECT_EQ(a.worst_exit, 0U);
    double sum = 0.0;
    for (const double part : a.rel_variance_per_path) sum += part;
    EXPECT_NEAR(sum, fit.previous_rel_variance, 1e-12 * fit.previous_rel_variance);
    EXPECT_NEAR(a.rel_variance_per_path[mc::RateAccount::DeltaWalks], (0.01 + 0.002 + 20.0 - 1.0) / 0.25,
                1e-9);
    EXPECT_EQ(a.rel_variance_per_path[mc::RateAccount::Walk], 0.0);
    EXPECT_NEAR(a.cost_us_per_path[mc::RateAccount::DeltaWalks], 0.25 * 10.0, 1e-9);
    EXPECT_NEAR(a.cost_us_per_path[mc::RateAccount::Walk], mc::kCostPerPath, 1e-12);
    EXPECT_EQ(a.cost_us_per_path[mc::RateAccount::Glints], 0.0);
    EXPECT_EQ(a.cost_us_per_path[mc::RateAccount::ReverseWalks], 0.0);
}

TEST(McRates, TheDrawnChainRateRecoversTheWalksVarianceFromItsSums) {
    // D(1, 1) = E[E^2] + 2 E[E C] + E[C^2] - f^2 at q = 1 whatever share and
    // rate the walks ran at, and D(s, q) = D(1, 1) + E[C^2] (1 / s - 1) +
    // E[sum Y^2] (1 / q - 1) / s, the variance of E + B (C_e + sum_i B_i Y_i
    // / q) / s with B, B_i draws of probabilities s and q (exact algebra: the
    // sums are exact); the cost c_bare + s (c_chain + q c_drawn).
    for (const auto& [share, q] : {std::pair{1.0, 1.0}, {1.0, 0.25}, {0.5, 0.5}, {0.25, 0.125}}) {
        mc::Sums total = deltaOnly(1.0e4, share, 40.0, 0.04, 1.5, 3.0, 5.0);
        addDrawnChains(total, share, q, 0.5, 2.0, 1.0);
        const mc::DeltaWalkModel model = mc::deltaWalkModel(total, true, share, q);
        ASSERT_TRUE(model.measured);
        const std::string at = "share " + std::to_string(share) + ", q " + std::to_string(q);
        EXPECT_NEAR(model.variance(0, 1.0, 1.0), 40.58, 1e-9) << at;
        EXPECT_NEAR(model.variance(0, 0.5, 0.25), 40.58 + 1.5 + 0.5 * 3.0 / 0.5, 1e-9) << at;
        EXPECT_NEAR(model.cost(1.0, 1.0), 10.0, 1e-9) << at;
        EXPECT_NEAR(model.cost(0.5, 0.25), 3.0 + 0.5 * (5.0 + 0.25 * 2.0), 1e-9) << at;
        ASSERT_EQ(model.drawn_rates.size(), 4U) << at;
        EXPECT_EQ(model.drawn_rates.back(), mc::kMinDrawnChainRate) << at;
    }
}

TEST(McRates, FewFlightsRunTheDrawnChainsWhereTheyCostMoreThanTheyCarry) {
    // Silver metallic's flop as measured (docs/PERFORMANCE.md, per walk in
    // units of f^2): D(1, 1) = 20, E[C^2] = 13, the drawn chains' E[sum Y^2]
    // only 0.37 but a quarter of a walk's cost (2.6 of bare 2.6 + chain 5.1
    // + 2.6). Variance x cost per walk at share 1: 20 x 10.3 = 206 at q = 1,
    // 21.1 x 8.35 = 176 at 1/4, the least (1/2: 183, 1/8: 181; share 1/2
    // at best 193).
    mc::ConeRates rates = oneConeRates(1.0);
    mc::Sums total = deltaOnly(1.0e4, 1.0, 8.0, 0.0, 13.0, 2.6, 5.1);
    addDrawnChains(total, 1.0, 1.0, 0.37, 2.6, 0.1 * 0.37 * 1.0e4);
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.drawn_chain_rate, 0.25);
    EXPECT_EQ(rates.delta_chain_share, 1.0);
}

TEST(McRates, DrawnChainsThatCarryTheVarianceOrOneHeavyFlightKeepEveryFlightOnThem) {
    // Where the drawn chains carry the cone (E[sum Y^2] = 1.5 of D = 2):
    // thinning them multiplies their variance, q = 1 (2 x 10.3 against 3.5 x
    // 9 at 1/2).
    mc::ConeRates rates = oneConeRates(1.0);
    mc::Sums carry = deltaOnly(1.0e4, 1.0, 0.2, 0.0, 2.8, 2.6, 5.1);
    addDrawnChains(carry, 1.0, 1.0, 1.5, 2.6, 1.0);
    mc::adaptRates(carry, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.drawn_chain_rate, 1.0);
    // Expensive drawn chains (6 of a walk's 13.7), E[sum Y^2] = 4 of D = 20:
    // q = 1/2 by the model (24 x 10.7 = 257 against 274 at 1), unless one
    // flight carries 90 % of their sum, whose thinning at 1/2 would add 18 %
    // of the walks' variance (the guard: 10 %); at 10 % of their sum, 2 %.
    mc::Sums heavy = deltaOnly(1.0e4, 1.0, 8.0, 0.0, 13.0, 2.6, 5.1);
    addDrawnChains(heavy, 1.0, 1.0, 4.0, 6.0, 0.9 * 4.0 * 1.0e4);
    rates = oneConeRates(1.0);
    mc::adaptRates(heavy, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.drawn_chain_rate, 1.0);
    heavy.form_learning.drawn_max2 = {0.1 * 4.0 * 1.0e4};
    mc::adaptRates(heavy, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.drawn_chain_rate, 0.5);
}

// Silver-like walks per chained walk (units of f^2 and the cost model's
// µs): D(1, 1) = 20 (E[E^2] 8, E[C^2] 13), bare 2.6, chain 5.1 of which ten
// last-flake connections at 0.4 each; the rate by length at L = 0, 0.5,
// 1, 2, 4, 8, 16 µm would add 0, 0.05, 0.2, 0.6, 1.5, 4, 10 to C^2 and run
// 10, 9.5, 9, 8, 6.5, 4.5, 3 connections.
constexpr std::array<double, 7> kSilverAdded{0.0, 0.05, 0.2, 0.6, 1.5, 4.0, 10.0};
constexpr std::array<double, 7> kSilverConnections{10.0, 9.5, 9.0, 8.0, 6.5, 4.5, 3.0};

TEST(McRates, TheRateByLengthRecoversTheWalksVarianceWhateverLTheyRanAt) {
    // D(1, 1) at L = 0 from walks run at any L (what that L added taken out
    // of C^2), D at option o = D(1, 1) + E[C^2] (1 / s - 1) + added_o / s,
    // and the cost c_bare + s (c_chain + c_connection (n_o - n_now)) (exact
    // algebra: the sums are exact). Options: the current L first, then the
    // other candidates.
    for (const auto& [share, l_now] : {std::pair{1.0, 0.0}, {1.0, 4.0}, {0.5, 16.0}}) {
        std::size_t now = 0;
        while (mc::kChainLengthsUm[now] != l_now) ++now;
        const double c_chain = 5.1 - 0.4 * (10.0 - kSilverConnections[now]);
        mc::Sums total = deltaOnly(1.0e4, share, 8.0, 0.0, 13.0, 2.6, c_chain);
        addLengthRate(total, share, l_now, kSilverAdded, kSilverConnections, 0.4);
        const mc::DeltaWalkModel model =
            mc::deltaWalkModel(total, true, share, 1.0, true, l_now, /*length_adapts=*/true);
        const std::string at = "share " + std::to_string(share) + ", L " + std::to_string(l_now);
        ASSERT_EQ(model.length_um.size(), mc::kChainLengths) << at;
        EXPECT_EQ(model.length_um[0], l_now) << at;
        EXPECT_NEAR(model.variance(0, 1.0, 1.0, 0), 20.0 + kSilverAdded[now], 1e-9) << at;
        for (std::size_t o = 0; o < model.length_um.size(); ++o) {
            std::size_t i = 0;
            while (mc::kChainLengthsUm[i] != model.length_um[o]) ++i;
            EXPECT_NEAR(model.variance(0, 0.5, 1.0, o), 20.0 + 13.0 + kSilverAdded[i] / 0.5, 1e-9) << at;
            EXPECT_NEAR(model.cost(0.5, 1.0, o), 2.6 + 0.5 * (5.1 - 0.4 * (10.0 - kSilverConnections[i])),
                        1e-9)
                << at << ", option L " << model.length_um[o];
        }
    }
}

TEST(McRates, ShortFlightsConnectLessWhereTheyCostMoreThanTheyCarry) {
    // kSilver*: variance x cost per walk at share 1 is 20 x 7.7 = 154 at
    // L = 0, 21.5 x 6.3 = 135 at 4 µm, 24 x 5.5 = 132 at 8 µm (the least),
    // 30 x 4.9 = 147 at 16 µm: L = 8 µm. Unless one flight's term at 8 and
    // 16 µm is beyond a tenth of the walks' variance (the guard, as the
    // drawn chains'): then 4 µm. Where the short flights carry the cone
    // (40 times the added variance: 22 x 7.5 = 165 at 0.5 µm) every flight connects.
    mc::ConeRates rates = oneConeRates(1.0);
    mc::Sums total = deltaOnly(1.0e4, 1.0, 8.0, 0.0, 13.0, 2.6, 5.1);
    addLengthRate(total, 1.0, 0.0, kSilverAdded, kSilverConnections, 0.4);
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.chain_length_um, 8.0);
    EXPECT_EQ(rates.delta_chain_share, 1.0);
    const double limit = 0.1 * 1.0e4 * 20.0;
    addLengthRate(total, 1.0, 0.0, kSilverAdded, kSilverConnections, 0.4,
                  {0.0, 0.0, 0.0, 0.0, 0.5 * limit, 1.5 * limit, 3.0 * limit});
    rates = oneConeRates(1.0);
    mc::adaptRates(total, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.chain_length_um, 4.0);
    std::array<double, 7> carried{};
    for (std::size_t i = 0; i < carried.size(); ++i) carried[i] = 40.0 * kSilverAdded[i];
    mc::Sums carry = deltaOnly(1.0e4, 1.0, 8.0, 0.0, 13.0, 2.6, 5.1);
    addLengthRate(carry, 1.0, 0.0, carried, kSilverConnections, 0.4);
    rates = oneConeRates(1.0);
    mc::adaptRates(carry, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.chain_length_um, 0.0);
    // Held (McSettings::adapt_chain_length false): L stays.
    rates = oneConeRates(1.0);
    rates.chain_length_adapts = false;
    rates.chain_length_um = 2.0;
    mc::Sums held = deltaOnly(1.0e4, 1.0, 8.0, 0.0, 13.0, 2.6, 5.1 - 0.4 * 2.0);
    addLengthRate(held, 1.0, 2.0, kSilverAdded, kSilverConnections, 0.4);
    mc::adaptRates(held, mc::kFirstExit + 1, false, true, rates);
    EXPECT_EQ(rates.chain_length_um, 2.0);
}

TEST(McRates, WithoutTheSplitTheShareStays) {
    // First-flake walks (and walks without connections) record no split: the
    // model keeps the share it has and the delta walks' measured variance.
    mc::Sums total = deltaOnly(1.0e4, 1.0, 50.0, 0.0475, 0.9525, 3.0, 7.0);
    total.cones[0].chain_samples = 0.0;
    const mc::DeltaWalkModel model = mc::deltaWalkModel(total, true, 1.0);
    ASSERT_EQ(model.shares.size(), 1U);
    EXPECT_EQ(model.shares.front(), 1.0);
    EXPECT_NEAR(model.variance(0, 1.0, 1.0), 50.0 + 0.095 + 0.9525 - 1.0, 1e-9);
    EXPECT_NEAR(model.cost(1.0, 1.0), 10.0, 1e-9);
}

}  // namespace
}  // namespace paintlab
