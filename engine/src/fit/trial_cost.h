#pragma once
// The fit's Ceres cost function: the whitened residuals of the recipe at u
// (fit_problem.h) and their Jacobian by central differences in u, the 2n
// displaced recipes evaluated in parallel. Private to the fitter.

#include "fit_problem.h"

#include <ceres/cost_function.h>

#include <atomic>
#include <vector>

namespace paintlab::fit {

// Shared by every cost function of one fit: counters and the cancel flag.
struct FitCounters {
    std::atomic<long> evaluations{0};
    std::atomic<long> model_nanoseconds{0};
    std::atomic<bool> cancelled{false};
};

class TrialCost final : public ceres::CostFunction {
public:
    TrialCost(const Recipe& recipe, const PreparedProblem& problem, FastModelSettings settings,
              FitCounters& counters);

    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

    // The residuals at u; false if the recipe there does not validate or the
    // fit was cancelled. Thread-safe.
    bool residualsAt(std::span<const double> u, std::span<double> out) const;
    // The Jacobian (row-major, residuals x parameters) of the last Evaluate
    // that asked for one, and its u.
    const std::vector<double>& lastJacobian() const { return m_jacobian; }
    const std::vector<double>& lastJacobianAt() const { return m_jacobian_at; }

private:
    bool evaluate(double const* const* parameters, double* residuals, double** jacobians) const;

    const Recipe& m_recipe;
    const PreparedProblem& m_problem;
    FastModelSettings m_settings;
    FitCounters& m_counters;
    std::size_t m_residuals = 0;
    std::size_t m_parameters = 0;
    mutable std::vector<double> m_jacobian;
    mutable std::vector<double> m_jacobian_at;
};

}  // namespace paintlab::fit
