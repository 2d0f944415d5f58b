// The order and the threads of a sweep's jobs: see sweep_schedule.hpp.
#include "app/sweep_schedule.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include "app/job_cost.hpp"
#include "app/sweep_plan.hpp"

namespace particles::app {

namespace {

// Up to this many jobs of one scenario, each job's own scenario is loaded for its estimate. Past it,
// loading each would delay the first job by seconds of planning (a large scenario written point by
// point takes a noticeable fraction of a second to load: bench/README.md, "Measurements behind
// choices in the source"), while the estimate only orders the jobs longest first and decides
// whether one runs alone on every core: with many more jobs than cores, every job of a scenario is
// taken at the cost of its first one.
constexpr size_t kJobsEstimatedEach = 64;

}  // namespace

std::vector<JobEstimate> estimateJobs(const SweepPlan& plan, const std::vector<size_t>& jobs,
                                      std::uintmax_t maxInputMiB) {
  std::map<size_t, std::string> texts;  // by scenario, read once
  std::map<size_t, size_t> jobsOf;      // by scenario
  for (const size_t index : jobs) ++jobsOf[plan.jobs[index].scenarioIndex];
  std::map<size_t, JobEstimate> firstOf;  // by scenario, where it has more than kJobsEstimatedEach
  std::vector<JobEstimate> estimates;
  for (const size_t index : jobs) {
    const SweepJob& job = plan.jobs[index];
    JobEstimate estimate;
    const bool shared = jobsOf[job.scenarioIndex] > kJobsEstimatedEach;
    if (job.stage != "concat" && shared && firstOf.count(job.scenarioIndex)) {
      estimate = firstOf.at(job.scenarioIndex);
    } else if (job.stage != "concat") {
      try {
        auto text = texts.find(job.scenarioIndex);
        const std::filesystem::path& file = plan.spec.scenarios[job.scenarioIndex].path;
        if (text == texts.end())
          text = texts.emplace(job.scenarioIndex, scenario::readScenarioText(file, maxInputMiB)).first;
        scenario::Scenario loaded = scenario::loadScenarioText(text->second, file.string(), job.overrides);
        estimate.cost = estimatedJobCost(loaded, plan.spec.command);
        estimate.spreads = jobSpreadsOverThreads(loaded, plan.spec.command);
      } catch (const scenario::ScenarioError&) {
        estimate = {};
      }
      if (shared) firstOf.emplace(job.scenarioIndex, estimate);
    }
    estimates.push_back(estimate);
  }
  return estimates;
}

std::vector<size_t> longestFirst(const std::vector<JobEstimate>& estimates) {
  std::vector<size_t> order(estimates.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return estimates[a].cost > estimates[b].cost; });
  return order;
}

bool runsAlone(const JobEstimate& job, double othersCost, int parallel, size_t running) {
  return running == 0 && parallel > 1 && job.spreads && job.cost > othersCost / double(parallel - 1);
}

int threadShare(int cores, int parallel, size_t running, size_t toStart) {
  const size_t sharing = std::min<size_t>(size_t(std::max(parallel, 1)), running + std::max<size_t>(toStart, 1));
  return std::max(1, int(size_t(std::max(cores, 1)) / sharing));
}

}  // namespace particles::app
