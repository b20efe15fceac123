#include "uncertainty.h"

#include "paintlab/engine/io/number_format.h"

#include <ceres/covariance.h>

#include <Eigen/SVD>

#include <cmath>
#include <limits>

namespace paintlab::fit {

namespace {

using io::formatNumber;

// Singular values of J below this share of the largest are the null space:
// the eigenvalues of J^T J that Ceres' DENSE_SVD drops (its default
// min_reciprocal_condition_number 1e-14 is this squared).
constexpr double kNullRatio = 1e-7;
// A parameter takes part in a null direction when its component there is larger than this.
constexpr double kNullComponent = 0.1;
// Within this share of the bound range of a bound: at the bound.
constexpr double kAtBound = 1e-4;
// A log-scaled parameter known to worse than this in ln(value) is not determined.
constexpr double kMaxSigmaLn = 1.0;

std::vector<bool> nullSpaceParameters(const TrialCost& cost, std::size_t rows, std::size_t n) {
    std::vector<bool> null(n, false);
    const std::vector<double>& j = cost.lastJacobian();
    if (j.size() != rows * n) {
        null.assign(n, true);  // no Jacobian: nothing is known to be determined
        return null;
    }
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
        j.data(), static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(n));
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
    const Eigen::VectorXd& s = svd.singularValues();
    const double largest = s.size() > 0 ? s(0) : 0.0;
    for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(n); ++k) {
        const bool dropped = k >= s.size() || !(s(k) > kNullRatio * largest);
        if (!dropped) continue;
        for (std::size_t p = 0; p < n; ++p)
            if (std::abs(svd.matrixV()(static_cast<Eigen::Index>(p), k)) > kNullComponent) null[p] = true;
    }
    return null;
}

std::string shortValue(const FittedParameter& p) {
    std::string unit = p.unit == "1" ? "" : " " + p.unit;
    return formatNumber(p.value) + unit;
}

}  // namespace

void fillUncertainty(ceres::Problem& problem, double* u, const TrialCost& cost,
                     const PreparedProblem& prepared, double sigma_scale, double correlation_threshold,
                     FitResult& result) {
    const std::size_t n = prepared.dims.size();
    ceres::Covariance::Options options;
    options.algorithm_type = ceres::DENSE_SVD;
    options.null_space_rank = -1;  // drop the eigenvalues below min_reciprocal_condition_number
    options.num_threads = 1;
    ceres::Covariance covariance(options);
    std::vector<double> cov(n * n, 0.0);
    const std::vector<std::pair<const double*, const double*>> blocks{{u, u}};
    const bool computed =
        covariance.Compute(blocks, &problem) && covariance.GetCovarianceBlock(u, u, cov.data());
    const std::vector<bool> null = computed
                                       ? nullSpaceParameters(cost, prepared.observations.residual_count, n)
                                       : std::vector<bool>(n, true);

    constexpr double kInf = std::numeric_limits<double>::infinity();
    result.correlation.assign(n * n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t j = 0; j < n; ++j) {
        FittedParameter& p = result.parameters[j];
        const FreeDimension& d = prepared.dims[j];
        p.at_bound = u[j] <= kAtBound || u[j] >= 1.0 - kAtBound;
        const double var = cov[j * n + j];
        // Compared with the bound range on the scale the fit searches (u,
        // logarithmic for a log-scaled thickness): a sigma of 1500 µm on
        // 27 µm within 1-5000 µm is a factor of 50, not a confident number.
        const double sigma_u = null[j] || !(var >= 0.0) ? kInf : sigma_scale * std::sqrt(var);
        p.sigma = std::isfinite(sigma_u) ? sigma_u * d.valuePerUnit(u[j]) : kInf;
        // On a log scale, also when 1 sigma of ln(value) exceeds 1: known only
        // to a factor e either way (14.8 ± 41 µm of an opaque layer).
        const double sigma_ln = d.log ? sigma_u * std::log(d.upper / d.lower) : 0.0;
        const bool spans_range = !(sigma_u <= 1.0);
        p.determined = !spans_range && sigma_ln <= kMaxSigmaLn;
        const std::string range =
            formatNumber(d.lower) + " to " + formatNumber(d.upper) + (d.log ? " (log scale)" : "");
        if (!p.determined) {
            const std::string why =
                !std::isfinite(p.sigma) ? std::string("the measurements do not change with it")
                : spans_range
                    ? "1 sigma " + formatNumber(p.sigma) + " spans more than its bound range " + range
                    : "1 sigma " + formatNumber(p.sigma) + " is larger than the value itself";
            result.identifiability.push_back({IdentifiabilityKind::Undetermined,
                                              {p.path},
                                              0.0,
                                              p.path + " is not determined by these measurements: " + why +
                                                  " (best value " + shortValue(p) + ", do not trust it)"});
        }
        if (p.at_bound)
            result.identifiability.push_back(
                {IdentifiabilityKind::AtBound,
                 {p.path},
                 0.0,
                 p.path + " is at its " + (u[j] < 0.5 ? "lower" : "upper") + " bound " + shortValue(p) +
                     ": the measurements would move it further; its sigma is not a two-sided interval"});
    }
    for (std::size_t a = 0; a < n; ++a) {
        if (null[a]) continue;
        for (std::size_t b = 0; b < n; ++b) {
            if (null[b]) continue;
            const double denom = std::sqrt(cov[a * n + a] * cov[b * n + b]);
            result.correlation[a * n + b] = a == b ? 1.0 : (denom > 0.0 ? cov[a * n + b] / denom : 0.0);
        }
    }
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b) {
            const double c = result.correlation[a * n + b];
            if (!(std::abs(c) > correlation_threshold)) continue;
            result.parameters[a].determined = false;
            result.parameters[b].determined = false;
            result.identifiability.push_back(
                {IdentifiabilityKind::Correlated,
                 {result.parameters[a].path, result.parameters[b].path},
                 c,
                 result.parameters[a].path + " and " + result.parameters[b].path +
                     " are not separately determined: correlation " + formatNumber(c) +
                     " (a change of one is compensated by the other)"});
        }
}

}  // namespace paintlab::fit
