#pragma once
// The full model's BRDF tabulated on the fast model's own basis (issue 4,
// "a tabulated BRDF on the fast model's own basis"), so that every tool that
// takes a LayeredBrdf (eval, albedo, multi-angle colours, plots, relight)
// works on either model.
//
// Escapes are projected into cells around the fast model's node cosines
// (cell averages, not node values: see mc_table.cpp for the method and its
// bias; the node on the normal holds 0 in every order m >= 1, so the BRDF is
// continuous there); standard errors per entry, and per-batch tables for
// anything derived from the table.

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
