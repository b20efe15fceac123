// tabulateMonteCarlo (mc_table.h).
//
// Method: the fast model's grid for the same settings (computeLayeredBrdf)
// gives the wavelengths, each band's node cosines mu_j (ambient) and the
// Fourier orders m < M. For every band and node the full model is run with a
// collimated beam at mu_j (exact in the incidence), and what escapes is
// projected: the ambient cosines are cut into cells at the midpoints between
// adjacent nodes (0 and 1 at the ends), and an escape at (mu_o, delta) in
// cell i adds w cos(m delta) / T(mu_o) / (2 pi T(mu_j) int_cell mu dmu) to
// f^m(i, j), the LayeredBrdf::BandTable convention (f divided by the top
// interface's transmittances T). The albedo at mu_j is the full model's.
//
// Why cells rather than next-event estimates at the node directions: one
// escape costs O(M) (a Chebyshev recurrence), where next-event estimation
// would evaluate the scattering kernel at every node direction and 2M
// azimuths at every collision (~M N times the work), and it does not see
// light whose last bounce is a mirror-like flake (explicit flakes, spread
// 0). The azimuthal projection is exact (no aliasing; orders >= M are
// dropped, as the fast model drops them).
//
// Bias: each f^m(i, j) is the mu-weighted average of f^m(mu_o, mu_j) over
// cell i, not its value at mu_i: second order in the cell width where f^m is
// smooth, more where f^m is sharply peaked (near-mirror flakes) or at the
// cell next to grazing. With the 4 ambient nodes of an 8-node grid under a
// 1.5 coat it moved eval() by up to 1.3 % (pigment slab) and 1.8 % (15-degree
// mirror flakes) against the fast model on the same grid
// (tests/engine/montecarlo/test_mc_table.cpp computes it from a converged
// fast model pushed through the same projection). It shrinks with more
// nodes, at the price of more variance per cell.
//
// The node on the normal (mu = 1, the grid's Gauss-Radau end node): f
// cannot depend on an azimuth that is undefined there, so every order m >= 1
// is exactly 0, as exit (row) and as incidence (column); these entries are
// set to 0 with standard error 0. Their cell averages (noise and the cell's
// odd part, f^m ~ sin^m theta) would make eval() step at the normal: the
// basis (fast_model/layered_brdf.cpp) mirrors the piece there by the parity
// of f^m, and in the incidence plane the view crossing the normal turns
// delta by pi, flipping the odd orders' sign.
//
// Standard errors: per entry over paths (or over batch means with explicit
// flakes, monte_carlo.h); for anything derived from the table (eval at a
// direction pair, colours) from the spread of the per-batch tables
// (batchEstimate, in mc_statistics.cpp so that the fast model's table
// writer uses it without linking the Monte Carlo engine and Embree), which
// accounts for the correlation between the entries that one path feeds.

#include "paintlab/engine/montecarlo/mc_table.h"

#include "mc_engine.h"
#include "run_deadline.h"

#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <memory>

namespace paintlab::mc {

namespace {

using Clock = std::chrono::steady_clock;

// The projection's cells around the ascending node cosines: edges at the
// midpoints between neighbours, 0 and 1 at the ends.
void cellEdges(const std::vector<double>& mu, std::vector<double>& lower, std::vector<double>& upper) {
    lower.clear();
    upper.clear();
    for (std::size_t i = 0; i < mu.size(); ++i) {
        lower.push_back(i == 0 ? 0.0 : 0.5 * (mu[i - 1] + mu[i]));
        upper.push_back(i + 1 == mu.size() ? 1.0 : 0.5 * (mu[i] + mu[i + 1]));
    }
}

// Orders m >= 1 of the node on the normal: exactly 0 (see the top of the file).
void clearAzimuthalOrdersAtNormal(const std::vector<double>& mu, std::vector<Eigen::MatrixXd>& f) {
    for (std::size_t k = 0; k < mu.size(); ++k) {
        if (mu[k] != 1.0) continue;
        const auto kk = static_cast<Eigen::Index>(k);
        for (std::size_t m = 1; m < f.size(); ++m) {
            f[m].row(kk).setZero();
            f[m].col(kk).setZero();
        }
    }
}

// A band table of the grid's shape with zero entries.
LayeredBrdf::BandTable emptyTable(const LayeredBrdf::BandTable& g) {
    LayeredBrdf::BandTable t;
    const auto n = static_cast<Eigen::Index>(g.mu.size());
    t.f.assign(g.f.size(), Eigen::MatrixXd::Zero(n, n));
    t.albedo = Eigen::VectorXd::Zero(n);
    return t;
}

}  // namespace

McTable tabulateMonteCarlo(const Recipe& recipe, const FastModelSettings& grid_settings,
                           const McSettings& settings, const ProgressCallback& progress) {
    std::unique_ptr<tbb::global_control> threads;
    if (settings.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        static_cast<std::size_t>(settings.threads));
    // The basis: the fast model's grid (its share of the progress is small).
    constexpr double kGridShare = 0.02;
    ProgressCallback grid_progress;
    if (progress) grid_progress = [&progress](double fraction) { return progress(kGridShare * fraction); };
    const LayeredBrdf grid = computeLayeredBrdf(recipe, grid_settings, grid_progress);
    const auto start = Clock::now();
    std::function<bool()> keep_going;
    if (progress) keep_going = [&progress] { return progress(kGridShare); };
    const McEngine engine(recipe, settings, keep_going);
    // Jobs run band by band; the same incidence node in each band is one kind.
    std::vector<std::size_t> kinds;
    for (const auto& g : grid.bands())
        for (std::size_t j = 0; j < g.mu.size(); ++j) kinds.push_back(j);
    const std::size_t jobs = kinds.size();
    // Unlike runMonteCarlo, the budget starts after the tiles' set-up: a
    // table has ~250 jobs, and the GUI's 1 s budget (full_model_job.cpp) is
    // shorter than the set-up, which would leave every job its pilot round
    // alone. An overrun of one job still comes out of the later ones.
    RunDeadline deadline(settings.max_seconds, kinds);
    const auto wavelengths = grid.wavelengthsNm();
    const auto& grid_bands = grid.bands();
    const auto batches = static_cast<std::size_t>(engine.batches());

    McTable table;
    std::vector<LayeredBrdf::BandTable> tables;
    std::vector<std::vector<LayeredBrdf::BandTable>> batch_tables(batches);
    bool every_batch = true;
    std::size_t jobs_done = 0;
    BandsInTurn bands(engine, {wavelengths.begin(), wavelengths.end()});
    for (std::size_t b = 0; b < grid_bands.size(); ++b) {
        const LayeredBrdf::BandTable& g = grid_bands[b];
        const McEngine::Band& band = bands.band(b);
        JobSpec job;
        cellEdges(g.mu, job.cell_lower_mu, job.cell_upper_mu);
        job.orders = static_cast<int>(g.f.size());
        const auto orders = g.f.size();
        LayeredBrdf::BandTable t = emptyTable(g);
        for (auto& bt : batch_tables) bt.push_back(emptyTable(g));
        std::vector<Eigen::MatrixXd> se(orders, Eigen::MatrixXd::Zero(t.albedo.size(), t.albedo.size()));
        Eigen::VectorXd albedo_se = Eigen::VectorXd::Zero(t.albedo.size());
        std::vector<Estimate> transmittance;
        for (std::size_t j = 0; j < g.mu.size(); ++j) {
            const double mu = g.mu[j];
            job.wi = {std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
            std::function<bool(double)> job_progress;
            if (progress)
                job_progress = [&](double fraction) {
                    return progress(kGridShare + (1.0 - kGridShare) *
                                                     (static_cast<double>(jobs_done) + fraction) /
                                                     static_cast<double>(jobs));
                };
            const JobResult r = engine.run(band, b, j, job, deadline.nextJobBudget(), job_progress);
            deadline.jobDone(r.incidence.seconds, largestRelativeError(r, job.orders));
            const auto jj = static_cast<Eigen::Index>(j);
            t.albedo(jj) = r.incidence.albedo.mean;
            albedo_se(jj) = r.incidence.albedo.std_error;
            transmittance.push_back(r.incidence.transmittance);
            for (std::size_t i = 0; i < g.mu.size(); ++i)
                for (std::size_t m = 0; m < orders; ++m) {
                    const Estimate& e = r.projection[i * orders + m];
                    t.f[m](static_cast<Eigen::Index>(i), jj) = e.mean;
                    se[m](static_cast<Eigen::Index>(i), jj) = e.std_error;
                }
            every_batch = every_batch && r.batch_means.size() == batches;
            for (std::size_t k = 0; k < batches && k < r.batch_means.size(); ++k) {
                // Sample vector: escaped, transmitted, then the projection (no exit directions).
                const auto& mean = r.batch_means[k];
                LayeredBrdf::BandTable& bt = batch_tables[k].back();
                bt.albedo(jj) = mean[0] + r.incidence.specular;
                for (std::size_t i = 0; i < g.mu.size(); ++i)
                    for (std::size_t m = 0; m < orders; ++m)
                        bt.f[m](static_cast<Eigen::Index>(i), jj) = mean[2 + i * orders + m];
            }
            table.total_paths += r.incidence.paths;
            ++jobs_done;
        }
        clearAzimuthalOrdersAtNormal(g.mu, t.f);
        clearAzimuthalOrdersAtNormal(g.mu, se);
        for (auto& bt : batch_tables) clearAzimuthalOrdersAtNormal(g.mu, bt.back().f);
        tables.push_back(std::move(t));
        table.f_std_error.push_back(std::move(se));
        table.albedo_std_error.push_back(std::move(albedo_se));
        table.transmittance.push_back(std::move(transmittance));
    }
    table.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    table.brdf = LayeredBrdf::withTables(grid, std::move(tables), table.seconds);
    if (every_batch)
        for (auto& bt : batch_tables)
            table.batch_brdfs.push_back(LayeredBrdf::withTables(grid, std::move(bt), 0.0));
    return table;
}

}  // namespace paintlab::mc
