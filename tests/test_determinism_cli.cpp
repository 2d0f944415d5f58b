// The program's outputs do not depend on the thread count: `particles run --trace
// --stats` writes the same bytes with --threads 1, --threads 3 and PARTICLES_THREADS=2
// (src/app/thread_count.hpp), and `particles render` the same frames with --threads 1 (everything
// on the calling thread) and 3 (the simulation, llvmpipe and x264 on 3 threads each). The
// in-process checks of every integrator are in test_determinism.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <numeric>
#include <string>

#include "cli_support.hpp"
#include "support/video_probe.hpp"

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

const std::string kScenarioFolder = std::string(PARTICLES_SOURCE_DIR) + "/scenarios/";

}  // namespace

TEST_CASE("determinism: particles run writes the same trace on 1, 2 and 3 threads") {
  // The demo cloth through the mouse's drag (from 1.5 s): 625 particles, 60 ticks a second.
  checkRunOutputs("'" + kScenarioFolder + "cloth.yaml' --duration 2", 625 * 120);
  // The 100² cloth (3 chunks per pass), the mouse pulling from the start: RK4 and backward Euler
  // (5 s of CPU under ASan, where test_determinism.cpp steps it anyway).
  const std::string big = "'" + kScenarioFolder + "cloth.yaml' --set 'grids.0.size=[100, 100]' --set mouse.0.from=0";
  checkRunOutputs(big + " --duration 0.05", 10000 * 3);
  if (!particles::test::kUnderSanitizer) {
    checkRunOutputs(big + " --duration 0.05 --integrator backward_euler --dt 0.01", 10000 * 3);
  }
}

TEST_CASE("determinism: particles render draws the same frames on 1 and 3 threads") {
  // The 100² cloth (3 chunks per pass), a third of a second at 60 fps. LP_NUM_THREADS unset, so
  // that --threads sets llvmpipe's (an LP_NUM_THREADS the user set would win).
  Scratch s;
  const std::string cloth = "'" + kScenarioFolder + "cloth.yaml' --set 'grids.0.size=[100, 100]' --set mouse.0.from=0";
  const std::string common = " --duration 0.3 --size 320x240 --quiet";
  for (const std::string threads : {"1", "3"}) {
    const Result png = s.run("render " + cloth + " -o frames" + threads + "/ --threads " + threads + common,
                             "-u LP_NUM_THREADS -u PARTICLES_THREADS");
    REQUIRE_MESSAGE(png.code == 0, png.err);
    const Result mp4 = s.run("render " + cloth + " -o video" + threads + ".mp4 --threads " + threads + common,
                             "-u LP_NUM_THREADS -u PARTICLES_THREADS");
    REQUIRE_MESSAGE(mp4.code == 0, mp4.err);
  }
  long frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(s.dir / "frames1")) {
    ++frames;
    CAPTURE(entry.path().filename());
    CHECK(slurp(entry.path()) == slurp(s.dir / "frames3" / entry.path().filename()));
  }
  CHECK(frames == 18);
  // x264 ran on as many threads as asked: its settings note in the first frame says so. Its
  // pictures are the same; that note is the one difference between the files.
  const std::string one = slurp(s.dir / "video1.mp4"), three = slurp(s.dir / "video3.mp4");
  CHECK(one.find(" threads=1 ") != std::string::npos);
  CHECK(three.find(" threads=3 ") != std::string::npos);
  REQUIRE(one.size() == three.size());
  CHECK(std::inner_product(one.begin(), one.end(), three.begin(), 0L, std::plus<>(), std::not_equal_to<>()) == 1);
  CHECK(particles::test::probeVideo(s.dir / "video3.mp4").frames == 18);
}
