// `particles render`, `stability` and `plot` end to end: outputs decoded and checked, bad input
// and unwritable outputs, interruption, and that a failure leaves no file behind.
#include <doctest/doctest.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli_support.hpp"
#include "plot/palette.hpp"
#include "plot_support.hpp"
#include "render/png_io.hpp"
#include "render_support.hpp"
#include "support/library_names.hpp"
#include "support/video_probe.hpp"

using namespace particles::test;
namespace fs = std::filesystem;

using particles::test::outputs;

namespace {

const std::string& kSwing = kSwingScenario;


}  // namespace

TEST_CASE("cli render: an MP4 with fps × duration H.264 frames") {
  Scratch s;
  s.write("s.yaml", kSwing);
  const Result r = s.run("render s.yaml -o swing.mp4 --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto info = particles::test::probeVideo(s.dir / "swing.mp4");
  checkVideo(info, "h264", 160, 120, 10);
  CHECK(info.pixelFormat == "yuv420p");
  CHECK(info.durationSeconds == doctest::Approx(1.0).epsilon(0.1));
  CHECK(outputs(s) == std::vector<std::string>{"swing.mp4"});
  // Command-line size and fps win over the scenario's.
  REQUIRE(s.run("render s.yaml -o big.mp4 --size 320x240 --fps 20 --quiet").code == 0);
  const auto big = particles::test::probeVideo(s.dir / "big.mp4");
  CHECK(big.width == 320);
  CHECK(big.frames == 20);
}

namespace {

// x264's thread count, from the options it writes into the first frame ("… threads=3 …").
int x264Threads(const std::string& mp4) {
  constexpr std::string_view kOption = " threads=";
  const size_t at = mp4.find(kOption);
  if (at == std::string::npos) return -1;
  return std::atoi(mp4.c_str() + at + kOption.size());
}

}  // namespace

TEST_CASE("cli render: FFmpeg's libraries are loaded for a video alone, and one that cannot be is exit 3 naming it") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  // Checking a scenario and rendering PNG frames start no FFmpeg library, nor x264.
  for (const char* args : {"check s.yaml", "render s.yaml -o frame.png --at 0.5 --quiet",
                           "render s.yaml -o frames/ --frames 0:2 --quiet"}) {
    CAPTURE(args);
    const Result r = s.run(args, "LD_DEBUG=libs");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(loaderStarted(r.err, "libc.so"), r.err);  // the log is there
    for (const char* library : {"libavutil", "libavcodec", "libavformat", "libavfilter", "libx264"}) {
      CAPTURE(library);
      CHECK(!loaderStarted(r.err, library));
    }
  }
  Result r = s.run("render s.yaml -o video.mp4 --duration 0.1 --quiet", "LD_DEBUG=libs");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  for (const char* library : {"libavutil", "libavcodec", "libavformat", "libx264"}) {
    CAPTURE(library);
    CHECK(loaderStarted(r.err, library));
  }
  // A library that cannot be opened (here an empty file found first) is an error naming it and
  // Debian's packages, exit 3 and no output; PNG frames do not notice.
  const std::string soname(libavcodecSoname());
  fs::create_directory(s.dir / "lib");
  s.write("lib/" + soname, "");
  for (const char* video : {"broken.mp4", "broken.webm", "broken.gif"}) {
    CAPTURE(video);
    r = s.run(std::string("render s.yaml -o ") + video + " --duration 0.1", "LD_LIBRARY_PATH=lib");
    CHECK(r.code == 3);
    CHECK_MESSAGE(r.err.starts_with("error: FFmpeg's library " + soname + " could not be loaded ("), r.err);
    CHECK_MESSAGE(contains(r.err, "MP4, WebM and GIF need FFmpeg's libraries (Debian: libavutil"), r.err);
    CHECK_MESSAGE(contains(r.err, "PNG frames do not"), r.err);
  }
  r = s.run("concat -o joined.mp4 video.mp4 video.mp4", "LD_LIBRARY_PATH=lib");
  CHECK(r.code == 3);
  CHECK_MESSAGE(contains(r.err, "FFmpeg's library " + soname + " could not be loaded ("), r.err);
  r = s.run("render s.yaml -o still.png --at 0.5", "LD_LIBRARY_PATH=lib");
  CHECK_MESSAGE(r.code == 0, r.err);
  std::vector<std::string> expected = {"frame.png", "frames", "lib", "still.png", "video.mp4"};
  CHECK(outputs(s) == expected);
}

// A thread count the user gives caps x264; without one x264 picks its own (about 1.5 per
// CPU, at least 1), which encodes faster than one per CPU.
TEST_CASE("cli render: --threads and PARTICLES_THREADS cap x264's threads, without them x264 chooses") {
  Scratch s;
  s.write("s.yaml", kSwing);
  REQUIRE(s.run("render s.yaml -o capped.mp4 --quiet --threads 1").code == 0);
  CHECK(x264Threads(slurp(s.dir / "capped.mp4")) == 1);
  REQUIRE(s.run("render s.yaml -o env.mp4 --quiet", "PARTICLES_THREADS=1").code == 0);
  CHECK(x264Threads(slurp(s.dir / "env.mp4")) == 1);
  REQUIRE(s.run("render s.yaml -o own.mp4 --quiet", "-u PARTICLES_THREADS").code == 0);
  const int own = x264Threads(slurp(s.dir / "own.mp4"));
  cpu_set_t cpus;  // the CPUs x264 counts: this process's affinity mask
  REQUIRE(sched_getaffinity(0, sizeof cpus, &cpus) == 0);
  CHECK(own >= 1);
  if (CPU_COUNT(&cpus) >= 2) CHECK(own > 1);
}

TEST_CASE("cli render: a PNG sequence, one PNG at --at, and per-frame stats") {
  Scratch s;
  s.write("s.yaml", kSwing);
  Result r = s.run("render s.yaml -o frames/ --stats stats.csv --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  std::vector<std::string> frames;
  for (const auto& e : fs::directory_iterator(s.dir / "frames")) frames.push_back(e.path().filename().string());
  std::sort(frames.begin(), frames.end());
  REQUIRE(frames.size() == 10);
  CHECK(frames.front() == "frame_000000.png");
  CHECK(frames.back() == "frame_000009.png");
  const auto statsLines = lines(slurp(s.dir / "stats.csv"));
  CHECK(statsLines.front() == "t,kinetic,potential,total,constraint_error,penetration");
  CHECK(statsLines.size() == 11);  // one row per frame
  CHECK(statsLines[5].rfind("0.4,", 0) == 0);

  r = s.run("render s.yaml -o at.png --at 0.4 --theme light --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto single = particles::render::readPng(s.dir / "at.png");
  CHECK(single.width == 160);
  // The single frame at 0.4 s is the sequence's frame 4 in another theme: same size, and the
  // dark sequence frame re-rendered with --at matches it byte for byte.
  REQUIRE(s.run("render s.yaml -o at_dark.png --at 0.4 --quiet").code == 0);
  CHECK(particles::render::readPng(s.dir / "at_dark.png") ==
        particles::render::readPng(s.dir / "frames" / "frame_000004.png"));
}

TEST_CASE("cli render: bad input is exit 2 and writes nothing") {
  Scratch s;
  s.write("s.yaml", kSwing);
  CHECK(s.run("render s.yaml -o one.png").code == 2);                  // a PNG needs --at
  CHECK(s.run("render s.yaml -o v.mp4 --at 0.5").code == 2);           // --at needs a PNG
  CHECK(s.run("render s.yaml -o v.mp4 --size 161x120").code == 2);     // odd size for H.264
  CHECK(s.run("render s.yaml -o v.mp4 --size big").code == 2);
  CHECK(s.run("render s.yaml -o v.mp4 --theme neon").code == 2);
  CHECK(s.run("render s.yaml -o v.mp4 --msaa 64").code != 0);
  CHECK(s.run("render s.yaml -o v.avi").code == 2);
  CHECK(s.run("render s.yaml -o f.png --at 5").code == 2);             // past the duration
  const Result r = s.run("render s.yaml -o v.mp4 --set simulation.dt=0");
  CHECK(r.code == 2);
  CHECK(r.err.find("simulation.dt") != std::string::npos);
  CHECK(outputs(s).empty());
}

TEST_CASE("cli render: an unwritable output is exit 3 and leaves no file") {
  Scratch s;
  s.write("s.yaml", kSwing);
  s.write("blocker", "a file where a directory should be");
  for (const char* out : {"blocker/v.mp4", "blocker/f.png --at 0.5", "blocker/frames/"}) {
    CAPTURE(out);
    const Result r = s.run(std::string("render s.yaml --quiet -o ") + out);
    CHECK(r.code == 3);
    CHECK(r.err.find("blocker") != std::string::npos);
  }
  auto files = outputs(s);
  CHECK(files == std::vector<std::string>{"blocker"});
}

TEST_CASE("cli render: an explosion is exit 1, names the step, and leaves no file") {
  Scratch s;
  s.write("s.yaml",
          "name: boom\n"
          "simulation: {integrator: euler, dt: 0.1, duration: 10}\n"
          "render: {size: [64, 64], fps: 10}\n"
          "particles:\n"
          "  - {name: a, pos: [0, 0], fixed: true}\n"
          "  - {name: b, pos: [1.1, 0]}\n"
          "forces:\n"
          "  - {type: spring, a: a, b: b, rest: 1, ks: 10000}\n");
  const Result r = s.run("render s.yaml -o boom.mp4 --quiet");
  CHECK(r.code == 1);
  CHECK(r.err.find("exploded at step") != std::string::npos);
  CHECK(outputs(s).empty());
}

TEST_CASE("cli render: SIGINT, SIGTERM and SIGKILL stop the render and leave no partial output") {
  Scratch s;
  // Long enough (600 frames at 640×480) to still be running when the signal arrives.
  s.write("s.yaml", kSwing);
  for (const auto& [signal, code] : {std::pair{"INT", 130}, std::pair{"TERM", 143}, std::pair{"KILL", 137}}) {
    CAPTURE(signal);
    const Result r = s.interrupt("render s.yaml -o long.mp4 --quiet --duration 20 --size 640x480 --fps 30", signal);
    CHECK(r.code == code);
    if (code != 137) CHECK(r.err.find("interrupted") != std::string::npos);
    CHECK(outputs(s).empty());
  }
}

TEST_CASE("cli stability and plot: the table as CSV and figures") {
  Scratch s;
  s.write("s.yaml", kSwing);
  Result r = s.run("stability s.yaml --integrators midpoint,rk4 --csv table.csv --plot table.svg --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto rows = lines(slurp(s.dir / "table.csv"));
  REQUIRE(rows.size() == 3);
  CHECK(rows[0] == "integrator,evals_per_step,max_stable_dt,max_smooth_dt,cost_dt,evals_per_sim_second,speed_vs_euler,"
                   "wall_seconds_per_sim_second");
  CHECK(rows[1].rfind("midpoint,2,", 0) == 0);
  CHECK(rows[2].rfind("rk4,4,", 0) == 0);
  for (size_t i = 1; i < rows.size(); ++i) {
    CHECK(std::stod(rows[i].substr(rows[i].rfind(',') + 1)) > 0.0);  // measured wall time per simulated second
  }
  CHECK(slurp(s.dir / "table.svg").find("<svg") != std::string::npos);
  CHECK(s.run("stability s.yaml --integrators leapfrog").code == 2);

  REQUIRE(s.run("run s.yaml --stats stats.csv --quiet").code == 0);
  r = s.run("plot stats.csv -o energy.png --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(particles::render::readPng(s.dir / "energy.png").width == 1200);
  s.write("bad.csv", "t,kinetic\n0,1\n");
  r = s.run("plot bad.csv -o bad.svg");
  CHECK(r.code == 2);
  CHECK(r.err.find("bad.csv:1:") != std::string::npos);
  CHECK_FALSE(fs::exists(s.dir / "bad.svg"));
}

TEST_CASE("cli plot --scenario and stability --reference: titles, mouse bands, references, and their errors") {
  Scratch s;
  const std::string man = std::string(PARTICLES_SOURCE_DIR) + "/scenarios/soft_body.yaml";
  REQUIRE(s.run("run " + man + " --dt 0.1 --duration 30 --stats man.csv --quiet").code == 0);
  Result r = s.run("plot man.csv --scenario " + man + " --dt 0.1 -o man.svg --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const std::string svg = slurp(s.dir / "man.svg");
  CHECK(svg.find("<title>Energy and constraint error: soft_body, rk4, dt = 0.1 s</title>") != std::string::npos);
  // Both mouse drags (12–22 s and 32–42 s) as bands: the second lies past the data's 30 s, so only
  // the first is drawn, in each of the two panels (energy, penetration).
  const auto elements = particles::test::parseXml(std::vector<std::uint8_t>(svg.begin(), svg.end()));
  const auto bands = std::count_if(elements.begin(), elements.end(), [](const particles::test::XmlElement& e) {
    return e.name == "path" &&
           particles::test::sameColour(particles::test::styleProperty(e, "fill"), particles::plot::kBand);
  });
  CHECK(bands == 2);
  r = s.run("plot man.csv -o man.pdf --quiet");  // no scenario: the CSV's name in the title
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(slurp(s.dir / "man.pdf").rfind("%PDF-", 0) == 0);
  r = s.run("plot man.csv --dt 0.1 -o x.svg");  // the run's --dt means nothing without its scenario
  CHECK(r.code == 2);
  CHECK(r.err.find("--scenario") != std::string::npos);
  r = s.run("plot man.csv --scenario nowhere.yaml -o x.svg");
  CHECK(r.code == 2);
  CHECK(r.err.find("nowhere.yaml") != std::string::npos);
  CHECK_FALSE(fs::exists(s.dir / "x.svg"));

  s.write("s.yaml", kSwing);
  r = s.run("stability s.yaml --integrators midpoint,rk4 --plot dt.svg --quiet --reference rk4=0.05:0.08,midpoint=0.02 "
            "--reference-name book");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  for (const auto& [options, says] : std::vector<std::pair<std::string, std::string>>{
           {"--plot dt.svg --reference euler=0.01", "'euler' is not an integrator studied here (midpoint, rk4)"},
           {"--plot dt.svg --reference rk4=fast", "'fast' is not a positive number of seconds"},
           {"--plot dt.svg --reference rk4=0.2:0.1", "LO is larger than HI"},
           {"--plot dt.svg --reference rk4", "no integrator name"},
           {"--plot dt.svg --reference rk4=0.1,rk4=0.2", "a second value for rk4"},
           {"--reference rk4=0.1", "give --plot too"}}) {
    CAPTURE(options);
    r = s.run("stability s.yaml --integrators midpoint,rk4 --quiet " + options);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find(says) != std::string::npos, r.err);
  }
}

TEST_CASE("cli render --hud: text in the top-left corner, the rest of the frame untouched") {
  Scratch s;
  s.write("s.yaml", kSwing);
  REQUIRE(s.run("render s.yaml -o plain.png --at 0.5 --size 480x360 --quiet").code == 0);
  const Result r = s.run("render s.yaml -o hud.png --at 0.5 --size 480x360 --hud --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto plain = particles::render::readPng(s.dir / "plain.png");
  const auto hud = particles::render::readPng(s.dir / "hud.png");
  REQUIRE(plain.width == hud.width);
  int changedInCorner = 0, brightInCorner = 0, changedElsewhere = 0;
  for (int y = 0; y < hud.height; ++y) {
    for (int x = 0; x < hud.width; ++x) {
      const size_t i = (size_t(y) * size_t(hud.width) + size_t(x)) * 4;
      const bool changed = !std::equal(&hud.rgba[i], &hud.rgba[i] + 3, &plain.rgba[i]);
      // The panel: three lines of 10 px text at 360 px height, inside 400 × 70 px.
      if (x < 400 && y < 70) {
        changedInCorner += changed;
        brightInCorner += hud.rgba[i] > 200 && hud.rgba[i + 1] > 200 && hud.rgba[i + 2] > 200;
      } else {
        changedElsewhere += changed;
      }
    }
  }
  CHECK(changedInCorner > 1000);  // the translucent panel darkens the corner
  CHECK(brightInCorner > 100);    // light glyphs on it (dark theme)
  CHECK(changedElsewhere == 0);
}

TEST_CASE("cli render --keyint: a keyframe at least every 2 s by default, or as asked, bad values refused") {
  Scratch s;
  // A still picture for 7 s at 10 fps: x264 adds keyframes of its own at scene cuts, and a still
  // picture has none, so every keyframe here is the interval's. x264 puts one at most keyint
  // frames after the last (a frame early where the frame due would be a B-frame), and with its
  // own default, 250 frames, there would be one keyframe in these 70 frames.
  s.write("s.yaml",
          "name: still\n"
          "simulation: {integrator: rk4, dt: 0.01, duration: 7}\n"
          "render: {size: [160, 120], fps: 10}\n"
          "particles:\n"
          "  - {name: pin, pos: [0, 0], fixed: true}\n");
  REQUIRE(s.run("render s.yaml -o default.mp4 --quiet").code == 0);
  const std::vector<double> byDefault = keyframeTimes(s.dir / "default.mp4");
  CHECK(longestKeyframeGap(byDefault, 7.0) <= 2.0 + 1e-6);
  CHECK(byDefault.size() >= 4);
  CHECK(byDefault.size() <= 5);
  REQUIRE(s.run("render s.yaml -o half.mp4 --set simulation.duration=3 --keyint 0.5 --quiet").code == 0);
  const std::vector<double> half = keyframeTimes(s.dir / "half.mp4");
  CHECK(longestKeyframeGap(half, 3.0) <= 0.5 + 1e-6);
  CHECK(half.size() >= 6);
  // Shorter than a frame: every frame is a keyframe.
  REQUIRE(s.run("render s.yaml -o every.mp4 --keyint 0.01 --quiet").code == 0);
  CHECK(keyframeTimes(s.dir / "every.mp4").size() == 70);
  for (const char* bad : {"0", "-1", "nan", "inf", "3601", "two"}) {
    CAPTURE(bad);
    const Result r = s.run(std::string("render s.yaml -o bad.mp4 --keyint ") + bad);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("--keyint") != std::string::npos, r.err);
  }
  CHECK(!fs::exists(s.dir / "bad.mp4"));
}

TEST_CASE("cli render --raster: the five paths by name, anything else refused") {
  Scratch s;
  s.write("s.yaml", kSwing);
  for (const char* raster : {"auto", "triangles", "tiles", "resident", "cpu"}) {
    CAPTURE(raster);
    const Result r = s.run(std::string("render s.yaml -o f.png --at 0.5 --quiet --raster ") + raster);
    CHECK_MESSAGE(r.code == 0, r.err);
  }
  for (const char* bad : {"quads", "1", "TILES"}) {
    CAPTURE(bad);
    const Result r = s.run(std::string("render s.yaml -o g.png --at 0.5 --raster ") + bad);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("--raster") != std::string::npos, r.err);
  }
  CHECK(!fs::exists(s.dir / "g.png"));
}

TEST_CASE("cli render --frames: a split render's frames are the whole render's, byte for byte") {
  // The demo cloth for 2 s at its 60 fps: 120 frames, 0:60 and 60:120 rendered apart (the second
  // first, into the same directory) against one render of all of them.
  Scratch s;
  const std::string cloth = std::string(PARTICLES_SOURCE_DIR) + "/scenarios/cloth.yaml";
  const std::string common = " --set simulation.duration=2 --size 160x120 --quiet";
  REQUIRE(s.run("render '" + cloth + "' -o whole/" + common).code == 0);
  const Result late = s.run("render '" + cloth + "' -o split/ --frames 60:120" + common);
  REQUIRE_MESSAGE(late.code == 0, late.err);
  REQUIRE(s.run("render '" + cloth + "' -o split/ --frames 0:60" + common).code == 0);
  long frames = 0;
  for (const auto& entry : fs::directory_iterator(s.dir / "whole")) {
    ++frames;
    const fs::path other = s.dir / "split" / entry.path().filename();
    CAPTURE(other);
    REQUIRE(fs::exists(other));
    CHECK(slurp(entry.path()) == slurp(other));
  }
  CHECK(frames == 120);
  CHECK(std::distance(fs::directory_iterator(s.dir / "split"), fs::directory_iterator{}) == 120);
  // "A:" runs to the end; the frames before are left alone and named by their index in the whole.
  REQUIRE(s.run("render '" + cloth + "' -o tail/ --frames 118:" + common).code == 0);
  CHECK(fs::exists(s.dir / "tail" / "frame_000118.png"));
  CHECK(fs::exists(s.dir / "tail" / "frame_000119.png"));
  CHECK(std::distance(fs::directory_iterator(s.dir / "tail"), fs::directory_iterator{}) == 2);
  CHECK(slurp(s.dir / "tail" / "frame_000119.png") == slurp(s.dir / "whole" / "frame_000119.png"));
}

TEST_CASE("cli concat: two MP4 segments of a split render join into one 120-frame H.264 video") {
  Scratch s;
  const std::string cloth = std::string(PARTICLES_SOURCE_DIR) + "/scenarios/cloth.yaml";
  const std::string common = " --set simulation.duration=2 --size 160x120 --quiet";
  REQUIRE(s.run("render '" + cloth + "' -o a.mp4 --frames 0:60" + common).code == 0);
  REQUIRE(s.run("render '" + cloth + "' -o b.mp4 --frames 60:120" + common).code == 0);
  CHECK(particles::test::probeVideo(s.dir / "a.mp4").frames == 60);
  const Result joined = s.run("concat a.mp4 b.mp4 -o all.mp4");
  REQUIRE_MESSAGE(joined.code == 0, joined.err);
  CHECK(joined.out == "2 segments, 120 frames, 2 s → all.mp4\n");
  CHECK(joined.err.empty());
  const auto info = particles::test::probeVideo(s.dir / "all.mp4");  // decodes every frame
  CHECK(info.codec == "h264");
  CHECK(info.frames == 120);
  CHECK(info.fps == doctest::Approx(60.0));
  CHECK(info.durationSeconds == doctest::Approx(2.0).epsilon(1e-3));
  // Each segment starts with a keyframe: the second one's is at 1 s in the joined video.
  const std::vector<double> keys = keyframeTimes(s.dir / "all.mp4");
  CHECK(std::find_if(keys.begin(), keys.end(), [](double t) { return std::abs(t - 1.0) < 1e-6; }) != keys.end());
  // ffmpeg's own decoder reads it without a complaint.
  bool decoded = false;
  const std::string complaints =
      commandOutput("ffmpeg -v error -i '" + (s.dir / "all.mp4").string() + "' -f null - 2>&1", decoded);
  CHECK(decoded);
  CHECK(complaints.empty());
}

TEST_CASE("cli render --frames and concat: bad ranges and unlike segments are refused, nothing written") {
  Scratch s;
  s.write("s.yaml", kSwing);  // 1 s at 10 fps: 10 frames
  for (const char* bad : {"5:3", "0:11", "3:3", "abc", "1-4", ":4", "-1:4"}) {
    CAPTURE(bad);
    const Result r = s.run(std::string("render s.yaml -o bad.mp4 --frames ") + bad);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("--frames") != std::string::npos, r.err);
  }
  CHECK(s.run("render s.yaml -o bad.png --at 0.5 --frames 0:1").code == 2);
  CHECK(!fs::exists(s.dir / "bad.mp4"));
  CHECK(!fs::exists(s.dir / "bad.png"));

  REQUIRE(s.run("render s.yaml -o small.mp4 --frames 0:5 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o big.mp4 --frames 5: --size 320x240 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o fast.mp4 --frames 5: --fps 20 --quiet").code == 0);
  s.write("text.mp4", "not a video\n");
  const std::pair<const char*, const char*> refused[] = {
      {"small.mp4 big.mp4 -o joined.mp4", "error: big.mp4 cannot follow small.mp4: 320×240, not 160×120\n"},
      {"small.mp4 fast.mp4 -o joined.mp4", "fast.mp4 cannot follow small.mp4: 20/1 frames/s, not 10/1"},
      {"small.mp4 missing.mp4 -o joined.mp4", "cannot open missing.mp4"},
      {"small.mp4 text.mp4 -o joined.mp4", "text.mp4"},
      {"small.mp4 -o joined.avi", "must be a .mp4 file"},
  };
  for (const auto& [args, message] : refused) {
    CAPTURE(args);
    const Result r = s.run(std::string("concat ") + args);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find(message) != std::string::npos, r.err);
  }
  CHECK(!fs::exists(s.dir / "joined.mp4"));
  CHECK(!fs::exists(s.dir / "joined.avi"));
  // One segment is a (trivial) join.
  CHECK(s.run("concat small.mp4 -o one.mp4 --quiet").code == 0);
  CHECK(particles::test::probeVideo(s.dir / "one.mp4").frames == 5);
}
