// The adaptive rates' model of the delta-chain walks (mc_rates.h): the share
// of them that run the chain connections, from the split of their score.

#include "mc_rates.h"
#include "mc_statistics.h"

#include <gtest/gtest.h>

#include <cstddef>

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
        EXPECT_NEAR(model.variance(0, 1.0), 40.0 + 0.08 + 1.5 - 1.0, 1e-9) << "share " << share;
        EXPECT_NEAR(model.variance(0, 0.125), 40.58 + 1.5 * 7.0, 1e-9) << "share " << share;
        EXPECT_NEAR(model.cost(1.0), 10.0, 1e-9) << "share " << share;
        EXPECT_NEAR(model.cost(0.25), 3.0 + 0.25 * 7.0, 1e-9) << "share " << share;
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

TEST(McRates, WithoutTheSplitTheShareStays) {
    // First-flake walks (and walks without connections) record no split: the
    // model keeps the share it has and the delta walks' measured variance.
    mc::Sums total = deltaOnly(1.0e4, 1.0, 50.0, 0.0475, 0.9525, 3.0, 7.0);
    total.cones[0].chain_samples = 0.0;
    const mc::DeltaWalkModel model = mc::deltaWalkModel(total, true, 1.0);
    ASSERT_EQ(model.shares.size(), 1U);
    EXPECT_EQ(model.shares.front(), 1.0);
    EXPECT_NEAR(model.variance(0, 1.0), 50.0 + 0.095 + 0.9525 - 1.0, 1e-9);
    EXPECT_NEAR(model.cost(1.0), 10.0, 1e-9);
}

}  // namespace
}  // namespace paintlab
