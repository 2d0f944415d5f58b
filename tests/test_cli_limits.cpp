// Issue 26, rows 10 and 11: concat joins only what decodes whole, and opens its segments one at a
// time. The runs are bounded as tests/test_hostile_input.cpp's are (an address-space cap and a
// wall-clock guard); under AddressSanitizer there is no cap and memory is not checked.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "render/video_probe.hpp"

using namespace particles::test;

namespace {

constexpr double kMaxPeakMiB = 200.0;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("issue 26 row 10: concat refuses a segment that does not decode whole, naming it, and writes nothing") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o a.mp4 --frames 0:9 --size 64x48 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o b.mp4 --frames 0:5 --size 64x48 --quiet").code == 0);
  const std::string a = slurp(s.dir / "a.mp4");
  REQUIRE(a.size() > 2300);
  std::ofstream(s.dir / "cut.mp4", std::ios::binary) << a.substr(0, a.size() - 300);  // its last frames cut short
  std::ofstream(s.dir / "head.mp4", std::ios::binary) << a.substr(0, 2000);           // its index, few frames

  const Result whole = s.run("concat a.mp4 b.mp4 -o joined.mp4");
  REQUIRE_MESSAGE(whole.code == 0, whole.err);
  CHECK(whole.out == "2 segments, 14 frames, 1.4 s → joined.mp4\n");
  CHECK(particles::render::probeVideo(s.dir / "joined.mp4").frames == 14);
  fs::remove(s.dir / "joined.mp4");

  for (const char* args : {"b.mp4 cut.mp4", "cut.mp4 b.mp4", "cut.mp4", "b.mp4 head.mp4", "head.mp4"}) {
    CAPTURE(args);
    const Result r = s.run(std::string("concat ") + args + " -o joined.mp4");
    CHECK(r.code == 2);
    const std::string bad = contains(args, "cut") ? "cut.mp4" : "head.mp4";
    CHECK_MESSAGE(contains(r.err, "error: " + bad + ": truncated or damaged"), r.err);
    CHECK_MESSAGE(!contains(r.err, "pixel format"), r.err);
    CHECK(!fs::exists(s.dir / "joined.mp4"));
  }
}

TEST_CASE("issue 26 row 11: concat opens one segment at a time: 2000 segments join in bounded memory") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o part.mp4 --frames 0:2 --size 64x48 --quiet").code == 0);
  std::string args = "concat";
  for (int i = 0; i < 2000; ++i) args += " part.mp4";
  Scratch::Usage usage;
  const Result r = s.runBounded(args + " -o joined.mp4", usage);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(r.out == "2000 segments, 4000 frames, 400 s → joined.mp4\n");
  if (!kSanitized) CHECK(usage.peakMiB < kMaxPeakMiB);  // every segment open at once: 780 MiB
  CHECK(particles::render::probeVideo(s.dir / "joined.mp4").frames == 4000);
}
