#pragma once
// The uncertainty of a fit at its optimum: Ceres' covariance (rank-revealing
// DENSE_SVD) in the optimiser's u, the Jacobian's null space (directions the
// data do not see, which a pseudo-inverse would report as certain), then per
// parameter sigma, the correlation matrix and the identifiability verdicts.

#include "trial_cost.h"

#include <ceres/problem.h>

namespace paintlab::fit {

// Fills result.parameters[j].sigma / at_bound / determined, result.correlation
// and result.identifiability. `problem` holds `cost` on the block u (the
// optimum); result.parameters holds path, value and bounds already.
// sigma_scale multiplies every sigma (sqrt of the reduced chi-square when > 1).
void fillUncertainty(ceres::Problem& problem, double* u, const TrialCost& cost,
                     const PreparedProblem& prepared, double sigma_scale, double correlation_threshold,
                     FitResult& result);

}  // namespace paintlab::fit
