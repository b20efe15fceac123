#include "run_deadline.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace paintlab::mc {

double jobShare(std::span<const double> remaining_needs) {
    if (remaining_needs.empty()) return 1.0;
    const auto count = static_cast<double>(remaining_needs.size());
    const double sum = std::accumulate(remaining_needs.begin(), remaining_needs.end(), 0.0);
    if (!(sum > 0.0)) return 1.0 / count;
    const double share = remaining_needs.front() / sum;
    return std::min(1.0, std::clamp(share, kMinShareOfEven / count, kMaxShareOfEven / count));
}

RunDeadline::RunDeadline(double max_seconds, std::vector<std::size_t> kinds)
    : m_start(std::chrono::steady_clock::now()), m_max_seconds(max_seconds), m_kinds(std::move(kinds)) {
    const std::size_t kind_count =
        m_kinds.empty() ? 0 : *std::max_element(m_kinds.begin(), m_kinds.end()) + 1;
    m_need.assign(kind_count, -1.0);
}

double RunDeadline::meanSeenNeed() const {
    double sum = 0.0;
    int seen = 0;
    for (const double need : m_need)
        if (need >= 0.0) {
            sum += need;
            ++seen;
        }
    return seen > 0 ? sum / seen : -1.0;
}

double RunDeadline::nextJobBudget() {
    const std::size_t job = m_next++;
    if (!(m_max_seconds > 0.0) || job >= m_kinds.size()) return 0.0;
    const auto now = std::chrono::steady_clock::now();
    if (job == 0) m_first_job = now;
    double left = m_max_seconds - std::chrono::duration<double>(now - m_start).count();
    if (job > 0) {
        const double between = std::chrono::duration<double>(now - m_first_job).count() - m_job_seconds;
        left -=
            std::max(0.0, between) / static_cast<double>(job) * static_cast<double>(m_kinds.size() - job - 1);
    }
    // A kind not seen yet is forecast as the mean of those seen (1 before any: even shares).
    const double mean_seen = meanSeenNeed();
    const double unseen = mean_seen >= 0.0 ? mean_seen : 1.0;
    std::vector<double> needs;
    for (std::size_t j = job; j < m_kinds.size(); ++j)
        needs.push_back(m_need[m_kinds[j]] >= 0.0 ? m_need[m_kinds[j]] : unseen);
    double share = jobShare(needs);
    if (mean_seen >= 0.0 && m_need[m_kinds[job]] < 0.0) share = std::min(1.0, kFirstOfKindShare * share);
    // Past the deadline a job still runs its pilot round (a result needs paths): a tiny positive budget.
    return std::max(left * share, 1e-6);
}

void RunDeadline::jobDone(double seconds, double error) {
    if (m_next == 0 || m_next > m_kinds.size()) return;
    if (std::isfinite(seconds) && std::isfinite(error))
        m_need[m_kinds[m_next - 1]] = std::max(0.0, seconds) * error * error;
    if (std::isfinite(seconds)) m_job_seconds += std::max(0.0, seconds);
}

}  // namespace paintlab::mc
