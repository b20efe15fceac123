#pragma once
// A run's time budget (McSettings::max_seconds) shared by its jobs in the
// order they run. Each job gets a share of what is left when it starts, so
// the set-up before it (flake tiles, the band's stack) and an earlier job's
// overrun come out of the later jobs' shares and the run as a whole keeps
// its budget. The shares follow each job kind's need learned from the jobs
// already done (the work-normalised variance W = seconds x error^2: a job
// given W / e^2 seconds ends near the error e), so that the jobs end near a
// common error instead of the cheap ones far below it (a flake paint's
// normal-incidence jobs need a small part of its oblique ones' time;
// docs/PERFORMANCE.md, "Budgets shared by each job kind's need").

#include <chrono>
#include <cstddef>
#include <span>
#include <vector>

namespace paintlab::mc {

// A forecast need is trusted within these multiples of an even share: one
// earlier job of another band forecasts the next, and a cone whose f is
// near zero can read a relative error far from the job's real need.
inline constexpr double kMinShareOfEven = 0.1;
inline constexpr double kMaxShareOfEven = 4.0;
// Once some kinds are seen, the first job of another gets this many times
// the share its forecast (their mean need) gives: its need is the least
// known, and a job given too little stays at a large error while one given
// too much takes a little from each of the many jobs after it. Before any
// kind is seen, shares are even.
inline constexpr double kFirstOfKindShare = 2.0;

// The share of what is left that the first of the remaining jobs gets, from
// their forecast needs (each >= 0): its need over their sum, within
// [kMinShareOfEven, kMaxShareOfEven] / count and at most 1; an even share
// when their needs sum to zero.
double jobShare(std::span<const double> remaining_needs);

class RunDeadline {
public:
    // `kinds`: per job in the order they run, its kind (jobs of a kind, such
    // as an incidence over the bands, are forecast from each other).
    RunDeadline(double max_seconds, std::vector<std::size_t> kinds);
    // The next job's budget in seconds (0: none); call once per job, in order.
    double nextJobBudget();
    // The job last given a budget took `seconds` and ended at `error`, its
    // largest relative standard error (0 when it had none to measure).
    void jobDone(double seconds, double error);

private:
    // The mean need of the kinds seen so far (negative: none).
    double meanSeenNeed() const;

    std::chrono::steady_clock::time_point m_start;
    std::chrono::steady_clock::time_point m_first_job;
    double m_max_seconds;
    // The seconds the jobs done reported: the rest of the time since the
    // first job (each band's stack, between jobs) is forecast per job to come
    // and kept out of the shares, or the last jobs would pay for it all.
    double m_job_seconds = 0.0;
    std::vector<std::size_t> m_kinds;
    std::size_t m_next = 0;
    // Per kind the need of its latest job done (negative: none yet).
    std::vector<double> m_need;
};

}  // namespace paintlab::mc
