#pragma once
// The order in which `particles sweep` starts its jobs here, and the threads each one gets
// (docs/sweeps.md, "Order and threads"). Only when and on how many threads a job runs change:
// its command line, record and row in results.csv are the same whatever the order, since the
// core's results are the same bits for every thread count.
//
// Longest first (Graham's LPT rule): with N workers, a sweep whose longest job starts last ends
// up to that whole job after the others; started first, it runs beside the rest. The example
// sweep's stiffest study takes half the sweep's work alone (bench/README.md, "Sweeps").

#include <cstddef>
#include <cstdint>
#include <vector>

namespace particles::app {

struct SweepPlan;

struct JobEstimate {
  double cost = 0.0;     // app/job_cost.hpp's estimatedJobCost
  bool spreads = false;  // app/job_cost.hpp's jobSpreadsOverThreads
};

// The estimate (app/job_cost.hpp) of each of `jobs` (indices into plan.jobs): its scenario loaded
// with what its command line overrides; for a scenario with more than 64 jobs, the first job's
// estimate for all of them (sweep_schedule.cpp: loading each would delay the first job). Cost 0 for a concat job (nothing to simulate) and for a
// job whose scenario does not load (it fails at once, saying why).
std::vector<JobEstimate> estimateJobs(const SweepPlan& plan, const std::vector<size_t>& jobs,
                                      std::uintmax_t maxInputMiB);

// The positions 0 … estimates.size() − 1, by decreasing cost; equal costs keep their order.
std::vector<size_t> longestFirst(const std::vector<JobEstimate>& estimates);

// Whether the next job to start, the longest left, runs alone on every core: when no job is
// running, more than one may run at once (`parallel`), it spreads over threads, and it would
// outlast the others left even if they kept every other worker busy: cost > Σ others /
// (parallel − 1). Started beside them on its share of the cores it alone would set the end of
// the sweep; alone on all of them it ends sooner, and the others follow. The example sweep's
// stiffest study is over half of its work (bench/README.md, "Sweeps").
bool runsAlone(const JobEstimate& job, double othersCost, int parallel, size_t running);

// The threads of a job started with `running` others under way and `toStart` − 1 still to start
// after it, at most `parallel` at once, on `cores` CPUs: the cores split evenly between the jobs
// that will run beside it, max(1, cores / min(parallel, running + toStart)). While jobs are plenty
// that is cores / parallel (so jobs × threads ≤ cores); once fewer remain than there are
// workers, the last ones get the idle workers' cores too.
int threadShare(int cores, int parallel, size_t running, size_t toStart);

}  // namespace particles::app
