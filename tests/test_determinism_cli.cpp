// The program's outputs do not depend on the thread count (issue 28): `particles run --trace
// --stats` writes the same bytes with --threads 1, --threads 3 and PARTICLES_THREADS=2
// (src/app/thread_count.hpp). The in-process checks of every integrator are in test_determinism.cpp.
#include <doctest/doctest.h>

#include <string>

#include "cli_support.hpp"

using particles::test::Result;
using particles::test::Scratch;
using particles::test::slurp;

namespace {

// Runs `particles run ARGS` three ways and checks that their trace and stats files are the same
// bytes; `rows` is the least number of lines the trace must have (so that an empty trace does not
// pass as "the same").
void checkRunOutputs(const std::string& args, size_t rows) {
  CAPTURE(args);
  Scratch s;
  struct Way {
    std::string name, options, environment;
  };
  // PARTICLES_THREADS left out of the first two: --threads must win over it, and CI may set it.
  const Way ways[] = {{"1", "--threads 1", "PARTICLES_THREADS=4"},
                      {"3", "--threads 3", "-u PARTICLES_THREADS"},
                      {"2", "", "PARTICLES_THREADS=2"}};
  std::string trace1, stats1;
  for (const Way& way : ways) {
    CAPTURE(way.name);
    const Result r = s.run(
        "run " + args + " --quiet --trace trace" + way.name + ".csv --stats stats" + way.name + ".csv " + way.options,
        way.environment);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const std::string trace = slurp(s.dir / ("trace" + way.name + ".csv"));
    const std::string stats = slurp(s.dir / ("stats" + way.name + ".csv"));
    if (way.name == "1") {
      REQUIRE(particles::test::lines(trace).size() >= rows);
      REQUIRE(particles::test::lines(stats).size() >= 3);
      trace1 = trace;
      stats1 = stats;
      continue;
    }
    // Not CHECK(trace == trace1): megabytes of text in the message.
    CHECK_MESSAGE(trace == trace1, "the trace on " << way.name << " threads differs from 1 thread's");
    CHECK_MESSAGE(stats == stats1, "the stats on " << way.name << " threads differ from 1 thread's");
  }
}

const std::string kScenarios = std::string(PARTICLES_SOURCE_DIR) + "/scenarios/";

}  // namespace

TEST_CASE("determinism: particles run writes the same trace on 1, 2 and 3 threads") {
  // The demo cloth through the mouse's drag (from 1.5 s): 625 particles, 60 ticks a second.
  checkRunOutputs("'" + kScenarios + "cloth.yaml' --duration 2", 625 * 120);
  // The 100² cloth (3 chunks per pass), the mouse pulling from the start: RK4 and backward Euler
  // (5 s of CPU under ASan, where test_determinism.cpp steps it anyway).
  const std::string big = "'" + kScenarios + "cloth.yaml' --set 'grids.0.size=[100, 100]' --set mouse.0.from=0";
  checkRunOutputs(big + " --duration 0.05", 10000 * 3);
  if (!particles::test::kUnderSanitizer) {
    checkRunOutputs(big + " --duration 0.05 --integrator backward_euler --dt 0.01", 10000 * 3);
  }
}
