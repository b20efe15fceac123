// fitRecipe: multi-start search, polish, report (fit.h).

#include "paintlab/engine/fit/fit.h"

#include "fit_problem.h"
#include "trial_cost.h"
#include "uncertainty.h"

#include <ceres/ceres.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace paintlab::fit {

namespace {

// Two minima are distinct when some parameter differs by more than this share
// of its bound range (in the optimiser's u).
constexpr double kDistinct = 0.05;

constexpr double kPolishCostFactor = 4.0;
constexpr int kSearchFlakeMaxNodes = 24;
constexpr int kSearchFlakeMaxOrders = 16;

struct Candidate {
    std::vector<double> u;
    double cost = std::numeric_limits<double>::infinity();
};

double distance(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0.0;
    for (std::size_t j = 0; j < a.size(); ++j) d = std::max(d, std::abs(a[j] - b[j]));
    return d;
}

// Progress, cancel and cost history from Ceres' iterations.
class Monitor final : public ceres::IterationCallback {
public:
    Monitor(const FitProgressCallback& progress, FitCounters& counters, FitResult& result, FitProgress& state,
            double fraction_from, double fraction_to, int iterations)
        : m_progress(progress), m_counters(counters), m_result(result), m_state(state), m_from(fraction_from),
          m_to(fraction_to), m_iterations(iterations) {}

    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
        const double best = m_result.cost_history.empty()
                                ? summary.cost
                                : std::min(m_result.cost_history.back(), summary.cost);
        m_result.cost_history.push_back(best);
        m_state.best_cost = std::min(m_state.best_cost, summary.cost);
        m_state.evaluations = m_counters.evaluations.load();
        const double share = std::min(1.0, static_cast<double>(summary.iteration + 1) / m_iterations);
        m_state.fraction = m_from + share * (m_to - m_from);
        if (m_progress && !m_progress(m_state)) {
            m_counters.cancelled = true;
            return ceres::SOLVER_ABORT;
        }
        return ceres::SOLVER_CONTINUE;
    }

private:
    const FitProgressCallback& m_progress;
    FitCounters& m_counters;
    FitResult& m_result;
    FitProgress& m_state;
    double m_from;
    double m_to;
    int m_iterations;
};

ceres::Solver::Options solverOptions(int iterations, bool polish) {
    ceres::Solver::Options o;
    o.minimizer_type = ceres::TRUST_REGION;
    o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    o.linear_solver_type = ceres::DENSE_QR;
    o.max_num_iterations = iterations;
    // The search only has to find the right basin; the polish converges.
    // The fast model's discretisation makes the cost rough below ~1e-6 of
    // its value: tighter tolerances only spend evaluations.
    o.function_tolerance = polish ? 1e-6 : 1e-3;
    o.parameter_tolerance = polish ? 1e-5 : 1e-3;
    o.logging_type = ceres::SILENT;
    o.minimizer_progress_to_stdout = false;
    o.num_threads = 1;  // the Jacobian's displaced recipes run in parallel (trial_cost.cpp)
    o.update_state_every_iteration = false;
    // No projected line search after each step: it evaluates the gradient
    // (a whole Jacobian of displaced recipes) at every trial length, and the
    // projection onto the bounds alone keeps the steps feasible. It more than
    // halved a fit's evaluations without changing its minimum.
    o.max_num_line_search_step_size_iterations = 0;
    return o;
}

// One bounded local solve from c.u; updates c.
void solve(const Recipe& recipe, const PreparedProblem& prepared, const FastModelSettings& settings,
           int iterations, bool polish, Monitor& monitor, FitCounters& counters, Candidate& c) {
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    TrialCost cost(recipe, prepared, settings, counters, /*central=*/polish);
    problem.AddResidualBlock(&cost, nullptr, c.u.data());
    for (int j = 0; j < static_cast<int>(c.u.size()); ++j) {
        problem.SetParameterLowerBound(c.u.data(), j, 0.0);
        problem.SetParameterUpperBound(c.u.data(), j, 1.0);
    }
    ceres::Solver::Options options = solverOptions(iterations, polish);
    options.callbacks.push_back(&monitor);
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    if (counters.cancelled) throw FitCancelled();
    c.cost = summary.final_cost >= 0.0 && std::isfinite(summary.final_cost)
                 ? summary.final_cost
                 : std::numeric_limits<double>::infinity();
}

}  // namespace

FastModelSettings fitSettings(Preset preset) {
    FastModelSettings settings = presetSettings(preset);
    settings.max_start_tau = std::min(settings.max_start_tau, kFitMaxStartTau);
    return settings;
}

std::string_view sideName(Side side) { return side == Side::Top ? "top" : "bottom"; }

double defaultBrdfLogNoise(const std::vector<double>& values, double cos_i) {
    double mean = 0.0;
    for (const double v : values) mean += v;
    if (!values.empty()) mean /= static_cast<double>(values.size());
    const double x = std::max(0.0, mean * cos_i);
    return std::max(kDefaultBrdfLogNoise * x / (1.0 + x), kDefaultBrdfLogNoiseFloor);
}

void validateFitProblem(const FitProblem& problem) { (void)prepareProblem(problem); }

FitResult fitRecipe(const FitProblem& problem, const FitProgressCallback& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const PreparedProblem prepared = prepareProblem(problem);
    const FitSettings& s = problem.settings;
    const std::size_t n = prepared.dims.size();
    // The scatter and the searches only rank and find basins: narrow flakes
    // on a grid of at most 24 nodes and 16 orders there (a start at a 1.5°
    // spread would otherwise cost ~50 ordinary evaluations); the polish and
    // the report run on the grid that resolves them (layered_brdf.h).
    FastModelSettings search = fitSettings(s.search_preset);
    search.flake_max_nodes = std::max(search.nodes, kSearchFlakeMaxNodes);
    search.flake_max_orders = std::max(search.orders, kSearchFlakeMaxOrders);
    const FastModelSettings polish = fitSettings(s.polish_preset);
    FitCounters counters;
    FitResult result;
    FitProgress state;
    state.best_cost = std::numeric_limits<double>::infinity();

    // Starts: the template's own values first (the user's guess), then a
    // low-discrepancy scatter inside the bounds.
    std::vector<Candidate> candidates;
    Candidate first;
    for (const FreeDimension& d : prepared.dims) first.u.push_back(d.toUnit(d.info.value));
    candidates.push_back(first);
    if (s.starts > 1)
        for (auto& u : haltonStarts(static_cast<std::size_t>(s.starts - 1), n, s.seed))
            candidates.push_back({u});

    // Scatter: one cost per start (the template's kept whatever its cost);
    // the local searches go from the best.
    if (static_cast<int>(candidates.size()) > s.searches) {
        const TrialCost scatter(problem.recipe, prepared, search, counters);
        std::vector<double> costs(candidates.size(), std::numeric_limits<double>::infinity());
        tbb::parallel_for(std::size_t{1}, candidates.size(), [&](std::size_t i) {
            std::vector<double> r(prepared.observations.residual_count);
            if (!scatter.residualsAt(candidates[i].u, r)) return;
            double sum = 0.0;
            for (double v : r) sum += v * v;
            costs[i] = 0.5 * sum;
        });
        if (counters.cancelled) throw FitCancelled();
        std::vector<std::size_t> order(candidates.size() - 1);
        std::iota(order.begin(), order.end(), std::size_t{1});
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return costs[a] < costs[b]; });
        std::vector<Candidate> kept{candidates.front()};
        for (std::size_t k = 0; k + 1 < static_cast<std::size_t>(s.searches) && k < order.size(); ++k)
            kept.push_back(candidates[order[k]]);
        candidates = std::move(kept);
    }

    // Search: 0 .. 0.6 of the progress; polish 0.6 .. 0.95; report the rest.
    state.stage = "search";
    state.starts = static_cast<int>(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        state.start = static_cast<int>(i);
        const double from = 0.6 * static_cast<double>(i) / static_cast<double>(candidates.size());
        const double to = 0.6 * static_cast<double>(i + 1) / static_cast<double>(candidates.size());
        Monitor monitor(progress, counters, result, state, from, to, s.search_iterations);
        solve(problem.recipe, prepared, search, s.search_iterations, false, monitor, counters, candidates[i]);
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
    if (!std::isfinite(candidates.front().cost))
        throw Error("fit: no start could be evaluated (every trial recipe failed validation)");

    // Polish the best distinct minima, but not one whose search cost is far
    // above the best's (more than kPolishCostFactor x it plus 10 alternative
    // margins): it cannot become an alternative, and polishing it cost the
    // pearl's fit two thirds of its time. The factor leaves room for the
    // search preset's own model error, which the polish removes.
    const double polish_limit = kPolishCostFactor * candidates.front().cost + 10.0 * s.alternative_cost_abs;
    std::vector<Candidate> polished;
    for (const Candidate& c : candidates) {
        if (static_cast<int>(polished.size()) >= s.polish_count || !std::isfinite(c.cost)) break;
        if (!polished.empty() && c.cost > polish_limit) break;
        const bool distinct = std::all_of(polished.begin(), polished.end(),
                                          [&](const Candidate& p) { return distance(p.u, c.u) > kDistinct; });
        if (distinct) polished.push_back(c);
    }
    state.stage = "polish";
    state.starts = static_cast<int>(polished.size());
    for (std::size_t i = 0; i < polished.size(); ++i) {
        state.start = static_cast<int>(i);
        const double from = 0.6 + 0.35 * static_cast<double>(i) / static_cast<double>(polished.size());
        const double to = 0.6 + 0.35 * static_cast<double>(i + 1) / static_cast<double>(polished.size());
        Monitor monitor(progress, counters, result, state, from, to, s.polish_iterations);
        solve(problem.recipe, prepared, polish, s.polish_iterations, true, monitor, counters, polished[i]);
    }
    std::sort(polished.begin(), polished.end(),
              [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
    Candidate best = polished.front();

    // Report at the polish preset: residuals, colours, covariance.
    state.stage = "report";
    state.fraction = 0.95;
    if (progress && !progress(state)) throw FitCancelled();
    TrialCost cost(problem.recipe, prepared, polish, counters);
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem report(problem_options);
    report.AddResidualBlock(&cost, nullptr, best.u.data());
    result.recipe = recipeAt(problem.recipe, prepared.dims, best.u);
    const std::optional<SideBrdfs> brdfs = modelBrdfs(result.recipe, prepared.observations, polish);
    if (!brdfs) throw Error("fit: the best recipe does not validate");
    std::vector<double> r(prepared.observations.residual_count);
    whitenedResiduals(*brdfs, prepared.observations, r);
    double sum = 0.0;
    for (double v : r) sum += v * v;
    result.cost = 0.5 * sum;
    result.residual_count = r.size();
    const double dof = std::max(1.0, static_cast<double>(r.size()) - static_cast<double>(n));
    result.reduced_chi_square = 2.0 * result.cost / dof;
    observationDetails(*brdfs, prepared.observations, result.residuals, result.geometries);
    for (std::size_t j = 0; j < n; ++j) {
        const FreeDimension& d = prepared.dims[j];
        result.parameters.push_back({d.info.path, d.info.label, std::string(d.info.decl->unit), d.info.value,
                                     d.toValue(best.u[j]), 0.0, d.lower, d.upper, false, true});
    }
    fillUncertainty(report, best.u.data(), cost, prepared,
                    std::sqrt(std::max(1.0, result.reduced_chi_square)), s.correlation_threshold, result);
    if (counters.cancelled) throw FitCancelled();

    // Alternatives: the other polished minima, distinct and nearly as good.
    const double limit = result.cost + std::max(s.alternative_cost_abs, s.alternative_cost_rel * result.cost);
    for (std::size_t i = 1; i < polished.size(); ++i) {
        const Candidate& c = polished[i];
        if (!(c.cost <= limit) || distance(c.u, best.u) <= kDistinct) continue;
        AlternativeMinimum alt;
        alt.recipe = recipeAt(problem.recipe, prepared.dims, c.u);
        alt.cost = c.cost;
        for (std::size_t j = 0; j < n; ++j) alt.values.push_back(prepared.dims[j].toValue(c.u[j]));
        if (const auto alt_brdfs = modelBrdfs(alt.recipe, prepared.observations, polish)) {
            std::vector<ObservationResidual> ignored;
            std::vector<GeometryMatch> geometries;
            observationDetails(*alt_brdfs, prepared.observations, ignored, geometries);
            for (const GeometryMatch& g : geometries)
                alt.max_delta_e00 = std::max(alt.max_delta_e00, g.delta_e00);
        }
        result.alternatives.push_back(std::move(alt));
    }
    result.evaluations = counters.evaluations.load();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    result.model_seconds = static_cast<double>(counters.model_nanoseconds.load()) * 1e-9;
    return result;
}

}  // namespace paintlab::fit
