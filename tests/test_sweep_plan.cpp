// A sweep file turned into jobs (src/app/sweep_plan.hpp), on its own: nothing runs and nothing is
// written. The jobs' order (scenarios outermost, the last group fastest), each job's values, command
// line and overrides, and a split render's segments with the join that waits for them.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "app/job_table.hpp"
#include "app/sweep_plan.hpp"
#include "cli_support.hpp"
#include "scenario/sweep_spec.hpp"

namespace {

using particles::app::planSweep;
using particles::app::SweepJob;
using particles::app::SweepPlan;
using particles::test::Scratch;
namespace fs = std::filesystem;

SweepPlan planOf(const Scratch& s, const std::string& sweep) {
  s.write("swing.yaml", particles::test::kSwingScenario);
  s.write("other.yaml", particles::test::kSwingScenario);
  const fs::path file = s.write("sweep.yaml", sweep);
  return planSweep(particles::scenario::loadSweepFile(file, 1), s.dir / "out", "/opt/particles", 1);
}

// The value after `option` in a job's arguments, or "" when it has none.
std::string argumentAfter(const SweepJob& job, const std::string& option) {
  for (size_t k = 0; k + 1 < job.args.size(); ++k) {
    if (job.args[k] == option) return job.args[k + 1];
  }
  return {};
}

}  // namespace

TEST_CASE("sweep plan: scenarios outermost, the last group fastest, zipped values together") {
  Scratch s;
  const SweepPlan plan = planOf(s,
                                "scenarios: [swing.yaml, other.yaml]\ncommand: run\n"
                                "parameters:\n"
                                "  - {key: integrator, values: [euler, rk4]}\n"
                                "  - zip:\n"
                                "    - {key: dt, values: [0.01, 0.02]}\n"
                                "    - {key: 'constraints[0].length', name: length, values: [1, 1.5]}\n");
  CHECK(plan.columns == std::vector<std::string>{"integrator", "dt", "length"});
  REQUIRE(plan.jobs.size() == 8);
  CHECK(plan.firstStageCount == 8);
  const std::vector<std::vector<std::string>> values = {
      {"euler", "0.01", "1"}, {"euler", "0.02", "1.5"}, {"rk4", "0.01", "1"}, {"rk4", "0.02", "1.5"}};
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    CAPTURE(i);
    CHECK(job.index == i);
    CHECK(job.stage == "run");
    CHECK(job.scenarioIndex == i / 4);
    CHECK(job.scenario == (i < 4 ? "swing.yaml" : "other.yaml"));
    CHECK(job.values == values[i % 4]);
    CHECK(job.dir == fs::path(particles::app::jobFolder(i)));
    // The command line: the command, the scenario by its absolute path, the values as options, the
    // outputs and the record in the job's folder.
    REQUIRE(job.args.size() >= 2);
    CHECK(job.args[0] == "run");
    CHECK(job.args[1] == (s.dir / job.scenario).string());
    CHECK(argumentAfter(job, "--integrator") == values[i % 4][0]);
    CHECK(argumentAfter(job, "--dt") == values[i % 4][1]);
    CHECK(argumentAfter(job, "--set") == "constraints[0].length=" + values[i % 4][2]);
    CHECK(argumentAfter(job, "--stats") == (plan.outDir / job.dir / "stats.csv").string());
    CHECK(job.record == plan.outDir / job.dir / "record.txt");
    CHECK(argumentAfter(job, "--record") == job.record.string());
    // What the job changes in its scenario, as the planning checked it.
    REQUIRE(job.overrides.size() == 3);
    CHECK(job.overrides[0].path == "simulation.integrator");
    CHECK(job.overrides[1].path == "simulation.dt");
    CHECK(job.overrides[2].path == "constraints[0].length");
    CHECK(job.after.empty());
  }
}

TEST_CASE("sweep plan: a split render's segments cover its frames, and one join per video waits for them") {
  Scratch s;
  // swing: 1 s at 10 fps, 10 frames; with --duration 2, 20.
  const SweepPlan plan = planOf(s,
                                "scenarios: [swing.yaml]\ncommand: render\nsplit: 3\n"
                                "parameters:\n  - {key: duration, values: [1, 2]}\n");
  REQUIRE(plan.jobs.size() == 8);  // 2 videos × 3 segments, then 2 joins
  CHECK(plan.firstStageCount == 6);
  const std::vector<std::string> frames = {"0:3", "3:6", "6:10", "0:6", "6:13", "13:20"};
  for (size_t i = 0; i < 6; ++i) {
    const SweepJob& job = plan.jobs[i];
    CAPTURE(i);
    CHECK(job.stage == "segment");
    CHECK(job.segment == std::to_string(i % 3 + 1) + "/3");
    CHECK(argumentAfter(job, "--frames") == frames[i]);
    CHECK(argumentAfter(job, "-o") == (plan.outDir / job.dir / "segment.mp4").string());
  }
  for (size_t v = 0; v < 2; ++v) {
    const SweepJob& join = plan.jobs[6 + v];
    CAPTURE(v);
    CHECK(join.stage == "concat");
    CHECK(join.values == std::vector<std::string>{v == 0 ? "1" : "2"});
    CHECK(join.after == std::vector<size_t>{3 * v, 3 * v + 1, 3 * v + 2});
    REQUIRE(join.args.size() == 8);  // concat, three segments, -o, the video, --record, the record
    CHECK(join.args[0] == "concat");
    for (size_t k = 0; k < 3; ++k) CHECK(join.args[1 + k] == plan.jobs[3 * v + k].outputs.front());
    CHECK(argumentAfter(join, "-o") == (plan.outDir / join.dir / "video.mp4").string());
    CHECK(join.overrides.empty());
  }
}
