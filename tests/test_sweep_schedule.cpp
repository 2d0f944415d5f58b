// The order and threads of a sweep's jobs run here (src/app/sweep_schedule.hpp) and the cost
// estimate that orders them (src/app/job_cost.hpp). The sweep itself, with a program that logs how
// each job was started, is tested in test_sweep.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "app/job_cost.hpp"
#include "app/sweep_schedule.hpp"
#include "scenario/scenario.hpp"
#include "source_tree.hpp"

using particles::test::kSource;

namespace {

using particles::app::estimatedJobCost;
using particles::app::fastestAngularFrequency;
using particles::app::JobEstimate;
using particles::app::jobSpreadsOverThreads;
using particles::app::longestFirst;
using particles::app::runsAlone;
using particles::app::threadShare;
using particles::scenario::loadScenarioFile;
using particles::scenario::loadScenarioText;
using particles::scenario::Override;


std::vector<JobEstimate> estimatesOf(const std::vector<double>& costs) {
  std::vector<JobEstimate> out;
  for (double cost : costs) out.push_back({cost, true});
  return out;
}

}  // namespace

TEST_CASE("sweep schedule: the longest first, equal costs in their own order") {
  CHECK(longestFirst(estimatesOf({1, 5, 3, 5, 0})) == std::vector<size_t>{1, 3, 2, 0, 4});
  CHECK(longestFirst(estimatesOf({2, 2, 2})) == std::vector<size_t>{0, 1, 2});
  CHECK(longestFirst({}).empty());
}

TEST_CASE("sweep schedule: a job that would outlast the others left runs alone on every core") {
  // Two workers: alone when longer than all the others together (the example sweep's studies, by
  // their estimates 4.38 : 2.19 : 1.10 : 1, each in turn), not when the others can match it.
  CHECK(runsAlone({4.38, true}, 2.19 + 1.10 + 1.0, 2, 0));
  CHECK(runsAlone({2.19, true}, 1.10 + 1.0, 2, 0));
  CHECK(runsAlone({1.10, true}, 1.0, 2, 0));
  CHECK_FALSE(runsAlone({3, true}, 1 + 1 + 1, 2, 0));  // the others fill the other worker: side by side
  CHECK(runsAlone({1, true}, 0, 2, 0));                // the last job, nothing running: every core
  // Four workers: longer than the others' share of three.
  CHECK(runsAlone({10, true}, 27, 4, 0));
  CHECK_FALSE(runsAlone({10, true}, 30, 4, 0));
  // Never beside a running job, with one worker (it has every core anyway), or for a job that
  // would leave the other cores idle.
  CHECK_FALSE(runsAlone({10, true}, 1, 2, 1));
  CHECK_FALSE(runsAlone({10, true}, 1, 1, 0));
  CHECK_FALSE(runsAlone({10, false}, 1, 2, 0));
}

TEST_CASE("sweep schedule: studies and renders spread over threads, runs of a large scene too") {
  const std::string cloth = kSource + "/scenarios/cloth.yaml";
  auto small = loadScenarioFile(cloth, {});
  CHECK(jobSpreadsOverThreads(small, "stability"));
  CHECK(jobSpreadsOverThreads(small, "render"));
  CHECK_FALSE(jobSpreadsOverThreads(small, "run"));  // 625 points: one chunk
  const std::vector<Override> hundred = {{"grids[0].size", "[100, 100]", "test"}};
  auto large = loadScenarioFile(cloth, hundred);
  CHECK(jobSpreadsOverThreads(large, "run"));
}

TEST_CASE("sweep schedule: each job's share of the cores, and more for the last ones") {
  // Two cores, two at once: one thread each while two or more remain; a job that will run alone
  // (nothing running, nothing after it) gets both.
  CHECK(threadShare(2, 2, 0, 4) == 1);
  CHECK(threadShare(2, 2, 1, 1) == 1);
  CHECK(threadShare(2, 2, 0, 1) == 2);
  // Sixteen cores, four at once: four each, then the idle workers' cores for the last jobs.
  CHECK(threadShare(16, 4, 0, 10) == 4);
  CHECK(threadShare(16, 4, 3, 1) == 4);
  CHECK(threadShare(16, 4, 2, 1) == 5);
  CHECK(threadShare(16, 4, 1, 1) == 8);
  CHECK(threadShare(16, 1, 0, 10) == 16);  // --jobs 1: every core for each job
  CHECK(threadShare(2, 8, 0, 8) == 1);     // more jobs at once than cores: one thread each, no fewer
  CHECK(threadShare(0, 0, 0, 0) == 1);
}

// The threads of the jobs running at once never exceed the cores (when no more run at once than
// there are cores): a job started with R jobs unfinished shares with at most min(parallel, R) of
// them, and a job started later saw no more unfinished jobs than that. Checked over many finishing
// orders, each job ending after a pseudo-random number of ticks.
TEST_CASE("sweep schedule: jobs × threads ≤ cores at every moment, whatever order the jobs end in") {
  unsigned seed = 12345;
  auto random = [&seed](unsigned below) {
    seed = seed * 1103515245u + 12345u;
    return (seed >> 16) % below;
  };
  for (int cores = 1; cores <= 24; ++cores) {
    for (int parallel = 1; parallel <= cores; ++parallel) {
      for (int trial = 0; trial < 4; ++trial) {
        const size_t jobs = 1 + random(12);
        struct Running {
          int threads;
          unsigned ticksLeft;
        };
        std::vector<Running> running;
        size_t started = 0;
        while (started < jobs || !running.empty()) {
          while (started < jobs && running.size() < size_t(parallel)) {
            running.push_back({threadShare(cores, parallel, running.size(), jobs - started), 1 + random(5)});
            ++started;
            int threads = 0;
            for (const Running& r : running) threads += r.threads;
            CAPTURE(cores);
            CAPTURE(parallel);
            CAPTURE(jobs);
            REQUIRE(threads <= cores);
          }
          for (Running& r : running) --r.ticksLeft;
          std::erase_if(running, [](const Running& r) { return r.ticksLeft == 0; });
        }
      }
    }
  }
}

namespace {

// ω_max of a one-second scenario with these particles and forces (YAML list entries).
double omegaOf(const std::string& particles, const std::string& forces) {
  auto s = loadScenarioText(
      "name: probe\nsimulation: {dt: 0.01, duration: 1}\nparticles:\n" + particles + "forces:\n" + forces,
      "probe.yaml");
  return fastestAngularFrequency(s.system);
}

}  // namespace

TEST_CASE("sweep schedule: the fastest angular frequency of a spring and mass, and of two masses") {
  // ω = √(k/m) = √(50/2) = 5 rad/s; a spring at its rest length, so K is exactly −k l̂l̂ᵀ.
  CHECK(omegaOf("  - {name: hook, pos: [0, 0], fixed: true}\n  - {name: bob, pos: [0, -1], mass: 2}\n",
                "  - {type: spring, a: hook, b: bob, rest: 1, ks: 50}\n") == doctest::Approx(5).epsilon(1e-4));
  // Two free masses m joined by k: the stretching mode, ω = √(2k/m) = √(2·8/1) = 4 rad/s.
  CHECK(omegaOf("  - {name: a, pos: [0, 0]}\n  - {name: b, pos: [1, 0]}\n",
                "  - {type: spring, a: a, b: b, rest: 1, ks: 8}\n") == doctest::Approx(4).epsilon(1e-4));
  // Nothing stiff: gravity alone.
  CHECK(omegaOf("  - {pos: [0, 0]}\n", "  - {type: gravity}\n") == 0);
}

TEST_CASE("sweep schedule: a job's cost is steps × evaluations × size, a stability study's steps at 2/ω_max") {
  const std::string cloth = kSource + "/scenarios/cloth.yaml";
  auto cost = [&](const std::string& command, std::vector<Override> overrides) {
    auto s = loadScenarioFile(cloth, overrides);
    return estimatedJobCost(s, command);
  };
  // 625 particles + 1200 springs; 10 s at 0.01 s; RK4's 4 evaluations per step.
  CHECK(cost("run", {}) == doctest::Approx(1000.0 * 4 * 1825));
  CHECK(cost("render", {{"simulation.integrator", "euler", "test"}}) == doctest::Approx(1000.0 * 1 * 1825));
  CHECK(cost("run", {{"simulation.dt", "0.005", "test"}}) == doctest::Approx(2000.0 * 4 * 1825));

  // The cloth_stiffness sweep's studies (3 s): the stiffest springs, the most steps. At ×16 and ×4
  // the limit 2/ω_max is below dt = 0.01 s, and four times the stiffness halves it; at ×0.25 it is
  // above, and the study counts dt's steps.
  auto study = [&](const std::string& ks) {
    return cost("stability", {{"simulation.duration", "3", "test"}, {"grids[0].springs.structural.ks", ks, "test"}});
  };
  const double soft = study("[6.25, 0.25]"), base = study("[25, 1]"), stiff = study("[100, 4]"),
               stiffest = study("[400, 16]");
  CHECK(soft == doctest::Approx(300.0 * 1825));
  CHECK(soft < base);
  CHECK(base < stiff);
  CHECK(stiffest == doctest::Approx(2 * stiff).epsilon(0.05));
}
