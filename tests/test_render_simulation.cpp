// Rendering as a library call (render/video/render_simulation.hpp), driven in process: what each kind of
// output holds, when the hooks are called, and that a stop, an explosion or bad options leave no
// output behind.

#include <doctest/doctest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"
#include "core/forces/damped_spring_force.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "render/video/frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/video/render_simulation.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"
#include "support/video_probe.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::probeVideo;
using particles::test::ScratchDir;
using particles::test::VideoInfo;

namespace {

// A tenth of the 1/fps = 0.1 s between frames: every frame falls on a step.
constexpr double kDt = 0.025;

// The falling particles for 0.5 s at 10 fps (5 frames) in 64 × 48 pixels.
RenderJob smallJob(const std::filesystem::path& output) {
  RenderJob job;
  job.output = output;
  job.duration = 0.5;
  job.fps = 10;
  job.camera = {Vec2(0, 0), 3.0};
  job.look = particles::test::smallRenderOptions(64, 48);
  job.look.particleRadius = {3.0, Length::Unit::pixels};
  job.video.preset = "ultrafast";
  return job;
}

// A stiff spring with explicit Euler at a huge step: blows up at step 5 (t = 0.5 s).
System explodingSystem() {
  SystemBuilder b;
  const int anchor = b.addParticle({Vec2(0, 0), Vec2::Zero(), 1.0, true, "a"});
  const int bob = b.addParticle({Vec2(1.1, 0), Vec2::Zero(), 1.0, false, "b"});
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(bob), Endpoint::ofParticle(anchor), 1.0, 1e4, 0.0});
  return b.build();
}

}  // namespace

TEST_CASE("render simulation: an MP4 of fps × duration frames, onFrame and progress once per frame") {
  ScratchDir dir;
  setLibavVerbose(false);
  System system = particles::test::fallingParticles();
  std::vector<double> frameTimes;
  std::vector<std::pair<long, long>> progress;
  RenderHooks hooks;
  hooks.onFrame = [&](const System& s) { frameTimes.push_back(s.time()); };
  hooks.progress = [&](long done, long total, const System&) { progress.emplace_back(done, total); };

  const RenderSummary summary = renderSimulation(system, Integrator::rk4, kDt, smallJob(dir / "out.mp4"), hooks);
  CHECK_FALSE(summary.stopped);
  CHECK(summary.frames == 5);
  CHECK(summary.steps == 16);  // to t = 0.4 s, the last frame
  CHECK(summary.wallSeconds > 0.0);
  REQUIRE(frameTimes.size() == 5);
  for (size_t i = 0; i < frameTimes.size(); ++i) {
    CAPTURE(i);
    CHECK(frameTimes[i] == doctest::Approx(double(i) / 10).epsilon(1e-12));
  }
  REQUIRE(progress.size() == 5);
  CHECK(progress.front() == std::pair{1L, 5L});
  CHECK(progress.back() == std::pair{5L, 5L});

  const VideoInfo info = probeVideo(dir / "out.mp4");
  CHECK(info.codec == "h264");
  CHECK(info.width == 64);
  CHECK(info.height == 48);
  CHECK(info.frames == 5);
  CHECK(dir.entries() == std::set<std::string>{"out.mp4"});
}

TEST_CASE("render simulation: a PNG sequence holds the single PNGs of the frames' times, decorated") {
  ScratchDir dir;
  // decorate draws over the rendered frame before it is written: a white top-left pixel.
  RenderHooks hooks;
  int decorated = 0;
  hooks.decorate = [&](Image& frame, const System&) {
    ++decorated;
    std::fill(frame.pixel(0, 0), frame.pixel(0, 0) + 3, std::uint8_t(255));
  };
  System system = particles::test::fallingParticles();
  const RenderSummary summary = renderSimulation(system, Integrator::rk4, kDt, smallJob(dir / "frames/"), hooks);
  CHECK(summary.frames == 5);
  CHECK(decorated == 5);
  CHECK(ScratchDir::listing(dir / "frames") == std::set<std::string>{"frame_000000.png", "frame_000001.png",
                                                                     "frame_000002.png", "frame_000003.png",
                                                                     "frame_000004.png"});

  // Frame 3 is the state at t = 0.3 s; a fresh system rendered to one PNG at 0.3 s is the same.
  System fresh = particles::test::fallingParticles();
  RenderJob single = smallJob(dir / "at.png");
  single.at = 0.3;
  std::vector<double> frameTimes;
  hooks.onFrame = [&](const System& s) { frameTimes.push_back(s.time()); };
  const RenderSummary one = renderSimulation(fresh, Integrator::rk4, kDt, single, hooks);
  CHECK(one.frames == 1);
  CHECK(one.steps == 12);
  REQUIRE(frameTimes.size() == 1);
  CHECK(frameTimes[0] == doctest::Approx(0.3).epsilon(1e-12));
  const Image at = readPng(dir / "at.png");
  CHECK(at == readPng(dir / "frames" / "frame_000003.png"));
  CHECK(at != readPng(dir / "frames" / "frame_000002.png"));
  CHECK(at.pixel(0, 0)[0] == 255);
}

TEST_CASE("render simulation: one PNG at a time is the frame `particles render --at` writes") {
  particles::test::Scratch s;
  const auto yaml = s.write("s.yaml", particles::test::kSwingScenario);
  const particles::test::Result r = s.run("render s.yaml -o cli.png --at 0.37 --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.err);

  // The program's defaults: the scenario's size and view, 4 samples, the dark theme.
  scenario::Scenario scenario = scenario::loadScenarioFile(yaml);
  RenderJob job;
  job.output = s.dir / "library.png";
  job.at = 0.37;
  job.look.width = scenario.render.width;
  job.look.height = scenario.render.height;
  job.camera = {scenario.render.viewCenter, scenario.render.viewHeight};
  renderSimulation(scenario.system, scenario.simulation.integrator, scenario.simulation.dt, job);
  const Image library = readPng(s.dir / "library.png");
  CHECK(library.width == 160);
  CHECK(library == readPng(s.dir / "cli.png"));
}

TEST_CASE("render simulation: the overlapped loop (threads ≠ 1) draws the plain loop's frames, in order") {
  // With threads 1 each frame is drawn as soon as it is reached; otherwise the next frame's state is
  // stepped to while another thread draws (render/video/render_simulation.cpp, OverlappedFrames). The
  // falling particles move every frame, so a frame drawn from another frame's state would show.
  // The third run reads frames back ahead (EGL's two pixel-pack buffers, as on a GPU): each frame
  // is handed on when the next one is drawn, the last one at the end.
  ScratchDir dir;
  std::vector<Image> sequences[3];
  for (int run : {0, 1, 2}) {
    const int threads = run == 0 ? 1 : 3;
    CAPTURE(run);
    System system = particles::test::fallingParticles();
    RenderJob job = smallJob(dir / ("frames" + std::to_string(run) + "/"));
    job.duration = 1.0;
    job.threads = threads;
    if (run == 2) {
      if (!render::glBackendBuilt(render::GlBackend::egl)) continue;
      job.gl.backend = render::GlBackend::egl;
      job.gl.readBack = render::GlRequest::ReadBack::ahead;
    }
    std::vector<double> times;
    RenderHooks hooks;
    hooks.onFrame = [&](const System& s) { times.push_back(s.time()); };
    CHECK(renderSimulation(system, Integrator::rk4, kDt, job, hooks).frames == 10);
    CHECK(times.size() == 10);
    for (int i = 0; i < 10; ++i) {
      sequences[run].push_back(readPng(job.output / fmt::format("frame_{:06d}.png", i)));
    }
  }
  for (size_t i = 0; i < 10; ++i) {
    CAPTURE(i);
    CHECK(sequences[0][i] == sequences[1][i]);
    if (!sequences[2].empty()) CHECK(sequences[0][i] == sequences[2][i]);
    if (i > 0) CHECK(sequences[1][i] != sequences[1][i - 1]);
  }
}

TEST_CASE("render simulation: a stop request leaves no output, and an earlier output untouched") {
  ScratchDir dir;
  setLibavVerbose(false);
  for (const char* name : {"out.mp4", "frames/"}) {
    CAPTURE(name);
    System system = particles::test::fallingParticles();
    int asked = 0;
    RenderHooks hooks;
    hooks.shouldStop = [&] { return ++asked > 2; };  // after two frames
    const RenderSummary summary = renderSimulation(system, Integrator::rk4, kDt, smallJob(dir / name), hooks);
    CHECK(summary.stopped);
    CHECK(summary.frames == 2);
    CHECK(asked == 3);
    CHECK(dir.entries().empty());
  }
  std::ofstream(dir / "old.mp4") << "an earlier video";
  System system = particles::test::fallingParticles();
  RenderHooks hooks;
  hooks.shouldStop = [] { return true; };
  CHECK(renderSimulation(system, Integrator::rk4, kDt, smallJob(dir / "old.mp4"), hooks).stopped);
  CHECK(dir.entries() == std::set<std::string>{"old.mp4"});
  CHECK(particles::test::slurp(dir / "old.mp4") == "an earlier video");
}

TEST_CASE("render simulation: an explosion throws SimulationError and leaves no output") {
  ScratchDir dir;
  setLibavVerbose(false);
  for (const char* name : {"boom.mp4", "frames/", "boom.png"}) {
    CAPTURE(name);
    System system = explodingSystem();
    RenderJob job = smallJob(dir / name);
    job.duration = 2.0;
    if (std::string(name) == "boom.png") job.at = 1.5;
    long frames = 0;
    RenderHooks hooks;
    hooks.onFrame = [&](const System&) { ++frames; };
    CHECK_THROWS_AS(renderSimulation(system, Integrator::euler, 0.1, job, hooks), SimulationError);
    CHECK(frames == (job.at ? 0 : 5));  // frames 0 … 4 reached; t = 0.5 s is not
    CHECK(dir.entries().empty());
  }
}

TEST_CASE("render simulation: bad options are std::invalid_argument and write nothing") {
  ScratchDir dir;
  System system = particles::test::fallingParticles();
  auto fails = [&](const RenderJob& job, double dt = kDt) {
    CHECK_THROWS_AS(renderSimulation(system, Integrator::rk4, dt, job), std::invalid_argument);
  };
  fails(smallJob(dir / "one.png"));  // a single PNG needs a time
  RenderJob job = smallJob(dir / "out.mp4");
  job.at = 0.2;  // a time is for a single PNG only
  fails(job);
  fails(smallJob(dir / "out.mp4"), 0.0);  // no time step
  job = smallJob(dir / "out.mp4");
  job.look.width = 65;  // H.264 needs even sizes
  fails(job);
  job = smallJob(dir / "out.mp4");
  job.fps = 0;
  fails(job);
  job = smallJob(dir / "out.mp4");
  job.look.msaa = 3;
  fails(job);
  fails(smallJob(dir / "out.avi"));
  CHECK(dir.entries().empty());
  CHECK(system.time() == 0.0);  // nothing was stepped
}
