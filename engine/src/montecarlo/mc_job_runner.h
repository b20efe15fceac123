#pragma once
// One (band, incidence) job of the Monte Carlo runner (mc_engine.h): its
// estimators set up from the settings (exit cones or chains, the tile's
// views, the projection), its chunks of paths run (mc_job_chunks.cpp), and
// the adaptive rates learned from the paths so far (mc_job_runner.cpp).

#include "chain_promise.h"
#include "first_flake.h"
#include "mc_connection.h"
#include "mc_engine.h"
#include "mc_rates.h"
#include "mc_statistics.h"
#include "mc_walk.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

class JobRunner {
public:
    JobRunner(const McEngine::Band& band, const JobSpec& job, const McSettings& settings, double tile_side_um,
              std::uint64_t band_key, std::uint64_t incidence_key);

    double specular() const { return m_specular; }
    std::size_t exitCount() const { return m_exits; }
    // The estimates' entries end here; then, with adaptive fractions, the
    // histogram's part of f per exit (a diagnostic for adapt()).
    std::size_t estimateEntries() const { return kFirstExit + m_exits + m_projected; }
    std::size_t entries() const { return estimateEntries() + m_diagnostics; }
    std::size_t coneStats() const { return m_adaptive ? m_exits : 0; }

    // The paths first_path .. first_path + paths - 1 of tile realisation `batch`,
    // with the glint, reverse and delta-chain samples attached to them.
    Sums runChunk(std::size_t batch, std::int64_t first_path, std::int64_t paths) const;

    // Adaptive fractions: sets the next paths' rates from every path so far
    // (mc_rates.h, adaptRates). Returns whether it set them.
    bool adapt(const Sums& total);
    // The paths adapt() waits for before it sets the first rates.
    static constexpr std::int64_t kPathsToAdapt = 1024;
    // What adapt() would choose now, without setting it: the worst cone's
    // relative variance per path at those rates over that at the rates in
    // force (the rate model's forecast; NaN without one).
    double forecastVarianceRatio(const Sums& total) const;
    // The rate model's account at the last adapt() (not measured before one).
    const RateAccount& account() const { return m_account; }

private:
    struct View {
        Vec3 v_in;
        std::vector<HistogramBin> bins;
        FourierCells cells;
        std::vector<GlintSet> glints;  // per bin (connections)
    };

    void buildChainPromise();
    void buildViews(const McSettings& settings);
    std::vector<double> chunkGlints(std::size_t batch, std::int64_t first_path, std::int64_t paths,
                                    std::vector<ConeStats>& cones) const;
    void chunkReverse(std::size_t batch, std::int64_t first_path, std::int64_t paths,
                      std::vector<double>& added, std::vector<ConeStats>& cones) const;
    double firstFlakeWalk(const PathContext& context, const FirstFlakeTable& table, const Vec3& v_in,
                          PathRng& rng, std::vector<double>& f_out, Sums& sums) const;
    void chunkDelta(std::size_t batch, std::int64_t first_path, std::int64_t paths,
                    std::vector<double>& added, Sums& sums) const;
    void weighPromiseCones(const Sums& total, const std::vector<double>& delta_variance,
                           const std::vector<double>& f2);
    void learnFirstFlakeProposal(const Sums& total, const std::vector<double>& f2);

    const McEngine::Band& m_band;
    const McSettings& m_settings;
    double m_tile_side_um = 1.0;
    std::uint64_t m_band_key;
    std::uint64_t m_incidence_key;
    std::vector<ExitChain> m_chains;
    std::vector<HistogramBin> m_bins;
    FourierCells m_cells;
    std::size_t m_exits = 0;
    std::size_t m_projected = 0;
    double m_specular = 0.0;
    double m_entry_weight = 0.0;
    Vec3 m_v_in;
    bool m_connections = false;
    WalkSettings m_walk;
    std::vector<std::vector<View>> m_views;  // [batch][view]
    std::size_t m_view_count = 1;
    double m_connection_fraction = 1.0;
    bool m_azimuths = false;           // glint_azimuths
    bool m_move_glint_flakes = false;  // move_glint_flakes, where the tiles allow it
    bool m_adaptive = false;           // adaptive_fractions
    bool m_reverse = false;            // reverse_walks
    bool m_nee_on = true;              // ConnectionParts::cone_direct
    bool m_glints_on = true;
    bool m_delta = false;          // delta_walks
    bool m_first_flake = false;    // first_flake_walks: the delta chains that begin at a flake
    bool m_uniform_delta = false;  // the uniform delta-chain walks (for the other chains)
    FirstFlakeProposal m_first_proposal;
    ChainPromise m_promise;  // the delta walks' roulette by promise (empty: off)
    std::size_t m_diagnostics = 0;
    // The drawn cavity chains' weights from the cones' needs (coneNeeds).
    void learnCavityFormWeights(const Sums& total, std::span<const double> needs);
    // Per cone the stop rule's need, r_k / (r_max f_k^2) with r_k its
    // relative variance per path (empty before any cone has an estimate).
    std::vector<double> coneNeeds(const Sums& total) const;
    ConeRates m_rates;
    RateAccount m_account;
    // The delta walks' drawn cavity chains: their draw's weights, learned
    // after every round (sqrt of each form's mean square per flight that could draw it).
    CavityFormWeights m_form_weights{};
    bool m_form_weights_learned = false;
    // The last-flake connections' cone scales (WalkSettings::chain_cone_scale),
    // learned after every round (empty: 1 until then).
    std::vector<double> m_chain_cone_scale;
    std::vector<std::vector<AzimuthGlintSet>> m_azimuth_glints;  // [batch][exit]
};

}  // namespace paintlab::mc
