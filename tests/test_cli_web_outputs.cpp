// `particles render` to the web's formats end to end: an animated GIF (one palette, centisecond
// delays), VP9 WebM (with alpha under --background transparent), transparent PNGs, what is refused
// (exit 2, nothing written), determinism and interruption.
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "render/video/frame_writer.hpp"
#include "render/png_io.hpp"
#include "render_support.hpp"
#include "support/video_probe.hpp"

using namespace particles::test;
namespace fs = std::filesystem;

using particles::test::outputs;

namespace {


// ffprobe's `entry` (e.g. "packet=duration") of the video stream, one value per line.
std::vector<std::string> probeEntries(const fs::path& video, const std::string& entry, const std::string& extra = "") {
  bool succeeded = false;
  const std::string text = commandOutput("ffprobe -v error " + extra + " -select_streams v:0 -show_entries " + entry +
                                             " -of csv=p=0 '" + video.string() + "'",
                                         succeeded);
  REQUIRE_MESSAGE(succeeded, "ffprobe failed on " << video << " (scripts/deps installs ffmpeg)");
  return lines(text);
}

// The GIF's frame delays in centiseconds (its packets' durations in the gif demuxer's 1/100 s).
std::vector<int> gifDelays(const fs::path& gif) {
  std::vector<int> delays;
  for (const std::string& line : probeEntries(gif, "packet=duration")) delays.push_back(std::stoi(line));
  return delays;
}

// The swing's bob at t = 0 is at (1, 0): pixel (120, 40) of its 160 × 120 frame (view centre
// (0, −0.5), 3 units high: 40 px a unit); the bottom-left corner is far from every shape.
constexpr int kBobX = 120, kBobY = 40, kEmptyX = 2, kEmptyY = 117;

}  // namespace

TEST_CASE("cli render -o x.gif: the scenario's fps up to 30, delays in whole centiseconds, exact length") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);  // 1 s at 10 fps
  Result r = s.run("render s.yaml -o swing.gif --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto info = particles::test::probeVideo(s.dir / "swing.gif");
  checkVideo(info, "gif", 160, 120, 10);
  CHECK(info.durationSeconds == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(probeEntries(s.dir / "swing.gif", "stream=nb_read_frames", "-count_frames") == std::vector<std::string>{"10"});
  CHECK(gifDelays(s.dir / "swing.gif") == std::vector<int>(10, 10));

  // A 60 fps scenario gives a 30 fps GIF without --fps: every other frame of its MP4, shown from
  // round(100·i / 30) cs, so the delays run 3, 4, 3 and add up to the second exactly.
  r = s.run("render s.yaml -o thirty.gif --set render.fps=60 --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const std::vector<int> delays = gifDelays(s.dir / "thirty.gif");
  REQUIRE(delays.size() == 30);
  CHECK(std::accumulate(delays.begin(), delays.end(), 0) == 100);
  for (size_t i = 0; i < delays.size(); ++i) {
    CAPTURE(i);
    CHECK(delays[i] == (i % 3 == 1 ? 4 : 3));
  }
  CHECK(particles::test::probeVideo(s.dir / "thirty.gif").frames == 30);

  // --fps is taken as given up to 50 (2 cs a frame) ...
  r = s.run("render s.yaml -o fifty.gif --set render.fps=60 --fps 50 --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(gifDelays(s.dir / "fifty.gif") == std::vector<int>(50, 2));
  // ... and refused above: browsers show delays under 2 cs as 10 cs.
  checkRefused(s, "render s.yaml -o sixty.gif --fps 60", "--fps 60");
  CHECK(outputs(s) == std::vector<std::string>{"fifty.gif", "swing.gif", "thirty.gif"});
}

TEST_CASE("cli render -o x.webm: VP9 frames, keyframes as --keyint asks, --crf in VP9's range") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  Result r = s.run("render s.yaml -o swing.webm --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto info = particles::test::probeVideo(s.dir / "swing.webm");
  checkVideo(info, "vp9", 160, 120, 10);
  CHECK(info.pixelFormat == "yuv420p");
  CHECK(info.durationSeconds == doctest::Approx(1.0).epsilon(0.01));
  bool decoded = false;
  const std::string complaints =
      commandOutput("ffmpeg -v error -i '" + (s.dir / "swing.webm").string() + "' -f null - 2>&1", decoded);
  CHECK(decoded);
  CHECK(complaints.empty());

  // 3 s at 10 fps with a keyframe at least every 0.5 s.
  REQUIRE(s.run("render s.yaml -o keys.webm --duration 3 --keyint 0.5 --quiet").code == 0);
  const std::vector<double> keys = keyframeTimes(s.dir / "keys.webm");
  CHECK(longestKeyframeGap(keys, 3.0) <= 0.5 + 1e-6);
  CHECK(keys.size() >= 6);

  // crf: VP9's 0 … 63; a lower crf is a larger file.
  REQUIRE(s.run("render s.yaml -o fine.webm --crf 10 --quiet").code == 0);
  CHECK(fs::file_size(s.dir / "fine.webm") > fs::file_size(s.dir / "swing.webm"));
  for (const char* bad : {"-o bad.webm --crf 64", "-o bad.mp4 --crf 52", "-o bad.gif --crf 20"}) {
    checkRefused(s, std::string("render s.yaml ") + bad, "--crf");
  }
  CHECK(outputs(s) == std::vector<std::string>{"fine.webm", "keys.webm", "swing.webm"});
}

TEST_CASE("cli render --background transparent: RGBA PNGs and VP9 alpha, refused for MP4, GIF and --hud") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  particles::render::setLibavVerbose(false);  // libvpx's decoder announces itself at "info"
  Result r = s.run("render s.yaml -o clear.png --at 0 --background transparent --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto clear = particles::render::readPng(s.dir / "clear.png");
  REQUIRE(clear.width == 160);
  CHECK(int(clear.pixel(kBobX, kBobY)[3]) == 255);
  CHECK(int(clear.pixel(kEmptyX, kEmptyY)[3]) == 0);
  // Opaque, the same pixels show the particle and the theme's background.
  REQUIRE(s.run("render s.yaml -o opaque.png --at 0 --quiet").code == 0);
  const auto opaque = particles::render::readPng(s.dir / "opaque.png");
  CHECK(std::equal(opaque.pixel(kBobX, kBobY), opaque.pixel(kBobX, kBobY) + 4, clear.pixel(kBobX, kBobY)));
  CHECK(int(opaque.pixel(kEmptyX, kEmptyY)[3]) == 255);
  // A sequence's frames are the same RGBA pictures.
  r = s.run("render s.yaml -o frames/ --background transparent --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(particles::render::readPng(s.dir / "frames" / "frame_000000.png") == clear);

  r = s.run("render s.yaml -o clear.webm --background transparent --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto alpha = particles::test::probeVideo(s.dir / "clear.webm", 0, "libvpx-vp9");
  CHECK(alpha.alphaMode == "1");
  CHECK(alpha.decodedPixelFormat == "yuva420p");
  CHECK(alpha.frames == 10);
  REQUIRE(alpha.sample.width == 160);
  CHECK(int(alpha.sample.pixel(kBobX, kBobY)[3]) >= 250);
  CHECK(int(alpha.sample.pixel(kEmptyX, kEmptyY)[3]) <= 5);

  for (const char* refused : {"-o v.mp4 --background transparent", "-o v.gif --background transparent",
                              "-o v.png --at 0 --background transparent --hud", "-o v.png --at 0 --background none"}) {
    checkRefused(s, std::string("render s.yaml ") + refused, "--background");
  }
  CHECK(outputs(s) == std::vector<std::string>{"clear.png", "clear.webm", "frames", "opaque.png"});
}

TEST_CASE("cli render --frames: split renders are refused for GIF and WebM") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  for (const char* out : {"a.gif", "a.webm"})
    checkRefused(s, std::string("render s.yaml --frames 0:5 -o ") + out, "--frames");
  CHECK(outputs(s).empty());
}

TEST_CASE("cli render: a GIF and a WebM are the same bytes twice, and an interrupted one leaves nothing") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  for (const char* ext : {"gif", "webm"}) {
    CAPTURE(ext);
    const std::string a = std::string("a.") + ext, b = std::string("b.") + ext;
    REQUIRE(s.run("render s.yaml --quiet -o " + a).code == 0);
    REQUIRE(s.run("render s.yaml --quiet -o " + b).code == 0);
    CHECK(slurp(s.dir / a) == slurp(s.dir / b));
    // On one core (taskset, run through `env`): the same bytes again. libvpx's output depends on its
    // thread count, so that count must not follow the machine's cores (webm_writer.cpp).
    const std::string c = std::string("c.") + ext;
    REQUIRE(s.run("render s.yaml --quiet --size 640x360 -o " + c, "taskset -c 0").code == 0);
    REQUIRE(s.run("render s.yaml --quiet --size 640x360 -o " + b).code == 0);
    CHECK(slurp(s.dir / c) == slurp(s.dir / b));
    fs::remove(s.dir / c);
    fs::remove(s.dir / a);
    fs::remove(s.dir / b);
    for (const auto& [signal, code] : {std::pair{"INT", 130}, std::pair{"KILL", 137}}) {
      CAPTURE(signal);
      const Result r =
          s.interrupt(std::string("render s.yaml -o long.") + ext + " --quiet --duration 20 --size 640x480", signal);
      CHECK(r.code == code);
      CHECK(outputs(s).empty());
    }
  }
}
