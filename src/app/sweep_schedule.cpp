// The order and the threads of a sweep's jobs: see sweep_schedule.hpp.
#include "app/sweep_schedule.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include "app/job_cost.hpp"
#include "app/sweep_plan.hpp"

namespace particles::app {

std::vector<double> estimatedCosts(const SweepPlan& plan, const std::vector<size_t>& jobs, std::uintmax_t maxInputMiB) {
  std::map<size_t, std::string> texts;  // by scenario, read once
  std::vector<double> costs;
  for (const size_t index : jobs) {
    const SweepJob& job = plan.jobs[index];
    double cost = 0.0;
    if (job.stage != "concat") {
      try {
        auto text = texts.find(job.scenarioIndex);
        const std::filesystem::path& file = plan.spec.scenarios[job.scenarioIndex].path;
        if (text == texts.end())
          text = texts.emplace(job.scenarioIndex, scenario::readScenarioText(file, maxInputMiB)).first;
        scenario::Scenario loaded = scenario::loadScenarioText(text->second, file.string(), job.overrides);
        cost = estimatedJobCost(loaded, plan.spec.command);
      } catch (const scenario::ScenarioError&) {
        cost = 0.0;
      }
    }
    costs.push_back(cost);
  }
  return costs;
}

std::vector<size_t> longestFirst(const std::vector<double>& costs) {
  std::vector<size_t> order(costs.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return costs[a] > costs[b]; });
  return order;
}

int threadShare(int cores, int parallel, size_t running, size_t toStart) {
  const size_t sharing = std::min<size_t>(size_t(std::max(parallel, 1)), running + std::max<size_t>(toStart, 1));
  return std::max(1, int(size_t(std::max(cores, 1)) / sharing));
}

}  // namespace particles::app
