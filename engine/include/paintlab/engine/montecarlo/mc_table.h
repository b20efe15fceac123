#pragma once
// The full model's BRDF tabulated on the fast model's own basis (issue 4,
// "a tabulated BRDF on the fast model's own basis"), so that every tool that
// takes a LayeredBrdf (eval, albedo, multi-angle colours, plots, relight)
// works on either model.
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
// Standard errors: per entry over paths (or over batch means with explicit
// flakes, monte_carlo.h); for anything derived from the table (eval at a
// direction pair, colours) from the spread of the per-batch tables
// (batchEstimate), which accounts for the correlation between the entries
// that one path feeds.

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/montecarlo/monte_carlo.h"
#include "paintlab/engine/recipe.h"

#include <Eigen/Dense>

#include <cstdint>
#include <span>
#include <vector>

namespace paintlab::mc {

struct McTable {
    LayeredBrdf brdf;  // the full model's estimates on the grid's basis
    // One table per batch (McSettings::batches), each from that batch's paths
    // alone; empty if some batch got no paths (fewer paths than batches).
    std::vector<LayeredBrdf> batch_brdfs;
    // Standard errors in the layout of brdf.bands(): [band][m](i_out, j_in) and [band](j).
    std::vector<std::vector<Eigen::MatrixXd>> f_std_error;
    std::vector<Eigen::VectorXd> albedo_std_error;
    // Transmittance into a transparent substrate at each node cosine (0 for other substrates).
    std::vector<std::vector<Estimate>> transmittance;
    std::int64_t total_paths = 0;
    double seconds = 0.0;  // full model only (the grid's fast model is not counted)
};

// Runs the fast model with `grid` for the basis, then the full model at
// every band and node (settings.max_paths / target_rel_error per node; a
// max_seconds budget is shared evenly by bands x nodes; the error target
// applies to the albedo and the order-0 entries). Throws as
// computeLayeredBrdf and runMonteCarlo; Error("cancelled") when progress
// returns false.
McTable tabulateMonteCarlo(const Recipe& recipe, const FastModelSettings& grid, const McSettings& settings,
                           const ProgressCallback& progress = {});

// Mean and standard error of a quantity computed from each batch's table
// (e.g. eval or a colour of batch_brdfs[k]): mean and spread of those values
// (batches of equal size; the standard error has batches - 1 degrees of freedom).
Estimate batchEstimate(std::span<const double> per_batch);

}  // namespace paintlab::mc
