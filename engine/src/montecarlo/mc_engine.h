#pragma once
// The Monte Carlo runner behind runMonteCarlo (monte_carlo.h) and
// tabulateMonteCarlo (mc_table.h): the flake tiles of every batch, the
// paint at one wavelength, and one (band, incidence) job run in
// deterministic chunks until its stop rule.
//
// Every path yields one sample vector: [0] the weight that escapes through
// the top, [1] the weight transmitted into a transparent substrate, then f at
// each exit direction, then the projection's entries (mc_walk.h,
// FourierCells), then (adaptive connection fractions) the histogram's part of
// each f. Chunk c of a job belongs to batch c mod batches; with explicit
// flakes batch k traces its own tile realisation. The glint samples of a chunk
// are stratified over it and attached to some of its paths, so its paths are
// not independent: errors over batches (of chunks) stay exact, errors over
// paths (batches = 1) become conservative.

#include "first_flake.h"
#include "flake_tile.h"
#include "last_flake.h"
#include "mc_connection.h"
#include "mc_glints.h"
#include "mc_stack.h"
#include "mc_walk.h"

#include "paintlab/engine/montecarlo/monte_carlo.h"

#include <functional>
#include <memory>
#include <vector>

namespace paintlab::mc {

struct JobSpec {
    Direction wi;
    std::vector<Direction> wo;
    // Projection on the fast model's basis: upper edges of the cells in the
    // ambient cosine (empty: none) and the Fourier orders.
    std::vector<double> cell_upper_mu;
    std::vector<double> cell_lower_mu;
    int orders = 0;
};

struct JobResult {
    IncidenceResult incidence;
    std::vector<Estimate> projection;  // [cell * orders + m]: cell average of f^m / (T_i T_o), 1/sr
    // Per batch that has paths: its paths' summed weight and mean sample
    // vector (albedo without the mirror term). A path weighs 1, one at the
    // first rates kept beside the later ones less (McEngine::run).
    std::vector<double> batch_weights;
    std::vector<std::vector<double>> batch_means;
    double weighted_paths = 0.0;  // their sum
};

// A job's largest relative standard error: of its albedo, every f and its
// projection's order-0 entries (0 where a mean is 0); RunDeadline's measure
// of what a job kind needs.
double largestRelativeError(const JobResult& r, int orders);

class McEngine {
public:
    // Builds the tiles (explicit flakes): one per layer with flakes and batch.
    // Throws InputError as runMonteCarlo. `keep_going`, if given, is called
    // on this thread every ~20 ms while the tiles are built (they take 1-3 s
    // for the demo paints on 2 cores); false cancels (Error "cancelled").
    McEngine(const Recipe& recipe, const McSettings& settings, const std::function<bool()>& keep_going = {});
    ~McEngine();
    McEngine(const McEngine&) = delete;
    McEngine& operator=(const McEngine&) = delete;

    struct Band {
        PaintStack stack;
        std::vector<std::vector<LayerFlakes>> explicit_flakes;  // [batch][layer]; empty: continuum
    };
    Band band(double wavelength_nm) const;

    // Runs one job; keys name its paths' random streams. `progress` gets the
    // job's fraction done and returns false to cancel (Error "cancelled").
    JobResult run(const Band& band, std::uint64_t band_key, std::uint64_t incidence_key, const JobSpec& job,
                  double budget_seconds, const std::function<bool(double)>& progress) const;

    int batches() const { return m_batches; }
    double tileSideUm() const { return m_tile_side_um; }

private:
    const Recipe& m_recipe;
    McSettings m_settings;
    int m_batches = 1;
    std::vector<std::vector<std::unique_ptr<FlakeTile>>> m_tiles;  // [batch][layer]
    std::vector<std::vector<TiltIndex>> m_tilts;                   // [batch][layer], for every band
    std::vector<std::vector<FlakeGroups>> m_groups;                // [batch][layer] (first_flake_walks)
    std::vector<LastFlakeLaw> m_last_flake;                        // [layer] (last_flake_connections)
    double m_tile_side_um = 1.0;
};

// A run's bands in the order its jobs ask for them, built as many at a time
// as there are cores, in parallel, when the first of each group is asked
// for: much of a band's build (its stack, a flake-free bottom's operator)
// runs on one core, and built one by one between the jobs it left the
// other core idle. At most one group is held.
class BandsInTurn {
public:
    BandsInTurn(const McEngine& engine, std::vector<double> wavelengths_nm);
    // Band b; b = 0, 1, 2, ... in turn.
    const McEngine::Band& band(std::size_t b);

private:
    const McEngine& m_engine;
    std::vector<double> m_wavelengths_nm;
    std::size_t m_group;
    std::vector<McEngine::Band> m_built;  // bands m_first .. m_first + size - 1
    std::size_t m_first = 0;
};

}  // namespace paintlab::mc
