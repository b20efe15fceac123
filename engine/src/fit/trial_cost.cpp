#include "trial_cost.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace paintlab::fit {

namespace {

// Central-difference step in u (a thousandth of the bound range, or of its
// logarithm): far above the fast model's rounding, small against the
// curvature of the residuals over a bound range.
constexpr double kStep = 1e-3;

}  // namespace

TrialCost::TrialCost(const Recipe& recipe, const PreparedProblem& problem, FastModelSettings settings,
                     FitCounters& counters)
    : m_recipe(recipe), m_problem(problem), m_settings(std::move(settings)), m_counters(counters),
      m_residuals(problem.observations.residual_count), m_parameters(problem.dims.size()) {
    set_num_residuals(static_cast<int>(m_residuals));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(m_parameters));
}

bool TrialCost::residualsAt(std::span<const double> u, std::span<double> out) const {
    if (m_counters.cancelled.load()) return false;
    const Recipe recipe = recipeAt(m_recipe, m_problem.dims, u);
    const std::optional<SideBrdfs> brdfs = modelBrdfs(recipe, m_problem.observations, m_settings);
    if (!brdfs) return false;
    whitenedResiduals(*brdfs, m_problem.observations, out);
    m_counters.evaluations += (brdfs->top ? 1 : 0) + (brdfs->bottom ? 1 : 0);
    return std::all_of(out.begin(), out.end(), [](double r) { return std::isfinite(r); });
}

bool TrialCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
    // Wall time in the model: the whole evaluation (a few recipe copies
    // besides the fast model and its eval()), parallel parts counted once.
    const auto start = std::chrono::steady_clock::now();
    const bool ok = evaluate(parameters, residuals, jacobians);
    m_counters.model_nanoseconds += static_cast<long>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
            .count());
    return ok;
}

bool TrialCost::evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
    const std::span<const double> u(parameters[0], m_parameters);
    const std::span<double> r(residuals, m_residuals);
    if (jacobians == nullptr || jacobians[0] == nullptr) return residualsAt(u, r);

    // The centre and the 2n displaced points, all in parallel.
    const std::size_t n = m_parameters;
    std::vector<std::vector<double>> points(2 * n + 1, std::vector<double>(u.begin(), u.end()));
    std::vector<double> lo(n);
    std::vector<double> hi(n);
    for (std::size_t j = 0; j < n; ++j) {
        hi[j] = std::min(u[j] + kStep, 1.0);
        lo[j] = std::max(u[j] - kStep, 0.0);
        points[1 + 2 * j][j] = hi[j];
        points[2 + 2 * j][j] = lo[j];
    }
    std::vector<std::vector<double>> values(points.size(), std::vector<double>(m_residuals));
    std::vector<char> ok(points.size(), 0);
    tbb::parallel_for(std::size_t{0}, points.size(),
                      [&](std::size_t k) { ok[k] = residualsAt(points[k], values[k]) ? 1 : 0; });
    if (ok[0] == 0) return false;
    std::copy(values[0].begin(), values[0].end(), r.begin());
    double* J = jacobians[0];
    for (std::size_t j = 0; j < n; ++j) {
        // A displaced recipe that does not validate: the one-sided difference
        // from the centre on the other side.
        const bool up = ok[1 + 2 * j] != 0;
        const bool down = ok[2 + 2 * j] != 0;
        const std::vector<double>& a = up ? values[1 + 2 * j] : values[0];
        const std::vector<double>& b = down ? values[2 + 2 * j] : values[0];
        const double h = (up ? hi[j] : u[j]) - (down ? lo[j] : u[j]);
        for (std::size_t i = 0; i < m_residuals; ++i) J[i * n + j] = h > 0.0 ? (a[i] - b[i]) / h : 0.0;
    }
    m_jacobian.assign(J, J + m_residuals * n);
    m_jacobian_at.assign(u.begin(), u.end());
    return true;
}

}  // namespace paintlab::fit
