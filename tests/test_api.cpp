// The public C++ API (include/particles/): what a program that embeds particles sees.
// Every case calls the public headers alone, as a user's program would; reading a PNG back to
// compare it uses the renderer's reader.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <thread>

#include <particles/particles.hpp>

#include "cli_support.hpp"
#include "render/png_io.hpp"
#include "support/video_probe.hpp"
#include "source_tree.hpp"

using namespace particles::test;

namespace {

std::string scenarioPath(const std::string& name) { return (kScenarios / (name + ".yaml")).string(); }

// A stiff spring stepped by explicit Euler far past its stable step: it blows up within steps.
const std::string kExplodingScenario =
    "name: explodes\n"
    "simulation: {integrator: euler, dt: 0.5, duration: 100}\n"
    "particles:\n"
    "  - {name: hook, pos: [0, 0], fixed: true}\n"
    "  - {name: bob, pos: [1, 0]}\n"
    "forces:\n"
    "  - {type: spring, a: hook, b: bob, rest: 0.5, ks: 1000000}\n";

// One trace row of `particles run --trace`, parsed back to the doubles it was written from.
struct TraceRow {
  double x, y, vx, vy, angle, omega;
};

// The last row of each name in a trace (the state at the run's end).
std::map<std::string, TraceRow> lastRows(const std::string& csv) {
  std::map<std::string, TraceRow> out;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    REQUIRE(cells.size() == 8);
    auto number = [](const std::string& s) { return std::strtod(s.c_str(), nullptr); };
    out[cells[1]] = {number(cells[2]), number(cells[3]), number(cells[4]),
                     number(cells[5]), number(cells[6]), number(cells[7])};
  }
  return out;
}

}  // namespace

TEST_CASE("api: a scenario loads with its settings, and set() takes --set's key paths and the shorthands") {
  particles::Scenario cloth = particles::Scenario::load(scenarioPath("cloth"));
  CHECK(cloth.name() == "cloth");
  CHECK(cloth.file() == scenarioPath("cloth"));
  CHECK(cloth.integrator() == particles::Integrator::rk4);
  CHECK(cloth.dt() == 0.01);
  CHECK(cloth.particleCount() == 625);
  CHECK(cloth.bodyCount() == 0);
  CHECK(cloth.summary().find("ok: 'cloth'") != std::string::npos);
  {
    Scratch scratch;  // one text for both: scenario::checkSummary
    const Result r = scratch.run("check " + scenarioPath("cloth"));
    REQUIRE(r.code == 0);
    CHECK(r.out == cloth.summary() + "\n");
  }

  cloth.set("dt", 0.005).set("integrator", "midpoint").set("simulation.duration", "2");
  CHECK(cloth.dt() == 0.005);
  CHECK(cloth.integrator() == particles::Integrator::midpoint);
  CHECK(cloth.duration() == 2.0);
  CHECK(cloth.steps() == 400);
  // A double set reads back as the same double.
  cloth.set("dt", 0.1 / 3.0);
  CHECK(cloth.dt() == 0.1 / 3.0);

  // A copy is its own: set() on it leaves the original.
  particles::Scenario copy = cloth;
  copy.set("dt", 0.002);
  CHECK(copy.dt() == 0.002);
  CHECK(cloth.dt() == 0.1 / 3.0);

  const particles::Scenario text = particles::Scenario::fromText(kSwingScenario, "swing.yaml");
  CHECK(text.name() == "swing");
  CHECK(text.particleCount() == 2);
  CHECK(text.fps() == 10.0);
}

TEST_CASE("api: a scenario that cannot be used is a ScenarioError with the file, line, column and key") {
  SUBCASE("a missing file") {
    try {
      (void)particles::Scenario::load("no/such/file.yaml");
      FAIL("no exception");
    } catch (const particles::ScenarioError& e) {
      CHECK(e.file() == "no/such/file.yaml");
      CHECK(std::string(e.what()).find("no/such/file.yaml") != std::string::npos);
    }
  }
  SUBCASE("a bad value in the text") {
    try {
      (void)particles::Scenario::fromText("name: x\nsimulation: {dt: -1}\n", "mine.yaml");
      FAIL("no exception");
    } catch (const particles::ScenarioError& e) {
      CHECK(e.file() == "mine.yaml");
      CHECK(e.line() == 2);
      CHECK(e.column() > 0);
      CHECK(e.keyPath() == "simulation.dt");
      CHECK(std::string(e.what()).rfind("mine.yaml:2:", 0) == 0);
    }
  }
  SUBCASE("set() with a wrong key, type or value throws, and the scenario stays as it was") {
    particles::Scenario cloth = particles::Scenario::load(scenarioPath("cloth"));
    const std::pair<const char*, const char*> bad[] = {
        {"simulation.dtt", "0.1"}, {"dt", "fast"}, {"dt", "-1"}, {"integrator", "rk5"}, {"forces[99].ks", "1"}, {"", "1"}};
    for (const auto& [path, value] : bad) {
      CAPTURE(path);
      CAPTURE(value);
      CHECK_THROWS_AS(cloth.set(path, value), particles::Error);
      CHECK(cloth.dt() == 0.01);
      CHECK(cloth.integrator() == particles::Integrator::rk4);
    }
    try {
      cloth.set("integrator", "rk5");
    } catch (const particles::ScenarioError& e) {
      CHECK(e.keyPath() == "simulation.integrator");
      CHECK(std::string(e.what()).find("rk4") != std::string::npos);  // the names it knows
    }
    // The scenario still steps with its own settings.
    particles::Simulation sim(cloth);
    sim.step(2);
    CHECK(sim.time() == 0.02);
  }
}

TEST_CASE("api: a bad argument is an ArgumentError naming the call and the value, never a crash") {
  particles::Scenario swing = particles::Scenario::fromText(kSwingScenario, "swing.yaml");
  particles::Simulation sim(swing);
  CHECK_THROWS_WITH_AS(sim.step(-1), doctest::Contains("Simulation::step"), particles::ArgumentError);
  CHECK_THROWS_AS(sim.step(2'000'000'000), particles::ArgumentError);
  CHECK_THROWS_AS(sim.advance(std::nan("")), particles::ArgumentError);
  CHECK_THROWS_AS(sim.advance(std::numeric_limits<double>::infinity()), particles::ArgumentError);
  CHECK_THROWS_AS(sim.advance(1e300), particles::ArgumentError);
  CHECK_THROWS_AS(sim.advance(-1.0), particles::ArgumentError);
  CHECK_THROWS_WITH_AS((void)sim.position(2), doctest::Contains("out of range 0 to 1"), particles::ArgumentError);
  CHECK_THROWS_AS((void)sim.velocity(-1), particles::ArgumentError);
  CHECK_THROWS_WITH_AS((void)sim.body(0), doctest::Contains("has none"), particles::ArgumentError);
  CHECK_THROWS_WITH_AS((void)sim.particleIndex("bobb"), doctest::Contains("did you mean 'bob'"),
                       particles::ArgumentError);
  CHECK_THROWS_AS((void)sim.bodyIndex("bob"), particles::ArgumentError);
  CHECK_THROWS_AS(sim.setPosition(1, {std::nan(""), 0.0}), particles::ArgumentError);
  CHECK_THROWS_AS(sim.setVelocity(5, {0.0, 0.0}), particles::ArgumentError);
  CHECK_THROWS_AS(sim.setThreads(0), particles::ArgumentError);
  CHECK_THROWS_AS(particles::Simulation(swing, 100000), particles::ArgumentError);
  // Nothing above changed the simulation.
  CHECK(sim.steps() == 0);
  CHECK(sim.time() == 0.0);
  CHECK(sim.position(1).x == 1.0);

  // A moved-from object says so.
  particles::Simulation moved = std::move(sim);
  CHECK_THROWS_WITH_AS(sim.step(), doctest::Contains("moved from"), particles::ArgumentError);
  CHECK_NOTHROW(moved.step());
  particles::Scenario taken = std::move(swing);
  CHECK_THROWS_AS(swing.set("dt", 0.1), particles::ArgumentError);
}

TEST_CASE("api: positions and velocities are views of the state itself, which stepping updates in place") {
  particles::Simulation sim(particles::Scenario::load(scenarioPath("cloth")));
  const std::span<const double> x = sim.positions();
  const std::span<const double> v = sim.velocities();
  REQUIRE(x.size() == 2 * 625);
  REQUIRE(v.size() == 2 * 625);
  const double* before = x.data();
  const int corner = sim.particleIndex("cloth[24][24]");
  const double y0 = x[2 * size_t(corner) + 1];
  sim.step(10);
  CHECK(sim.positions().data() == before);  // no copy, and no new buffer after steps
  CHECK(x[2 * size_t(corner) + 1] != y0);   // the old span sees the new state
  CHECK(x[2 * size_t(corner)] == sim.position(corner).x);
  CHECK(v[2 * size_t(corner) + 1] == sim.velocity(corner).y);

  sim.setPosition(corner, {0.25, -0.5});
  sim.setVelocity(corner, {1.0, 2.0});
  CHECK(x[2 * size_t(corner)] == 0.25);
  CHECK(v[2 * size_t(corner) + 1] == 2.0);
  CHECK(sim.particleNames().size() == 625);
  CHECK(sim.particleNames()[size_t(corner)] == "cloth[24][24]");

  // Rigid bodies: the chain's links, as their names say.
  particles::Simulation chain(particles::Scenario::load(scenarioPath("rigid_chain")));
  REQUIRE(chain.bodyCount() > 0);
  const std::vector<particles::BodyState> bodies = chain.bodies();
  CHECK(bodies.size() == size_t(chain.bodyCount()));
  const int link = chain.bodyIndex(chain.bodyNames()[0]);
  CHECK(chain.body(link).x == bodies[size_t(link)].x);
  const particles::Energy e = chain.energy();
  CHECK(e.total == doctest::Approx(e.kinetic + e.potential));
  CHECK(chain.constraintError() >= 0.0);
}

// One truth: the API steps the command line's way. Each scenario for a short while,
// on 1 and 2 threads, against `particles run --trace`'s last rows, every number to the bit.
TEST_CASE("api: stepping gives the bits of particles run --trace, for the demos and the stiff cloth, on 1 and 2 threads") {
  const std::pair<const char*, const char*> runs[] = {
      {"cloth", "0.5"}, {"soft_body", "3"}, {"rigid_chain", "0.3"}, {"cloth_stiff", "0.5"}};
  Scratch scratch;
  for (const auto& [name, duration] : runs) {
    for (int threads : {1, 2}) {
      CAPTURE(name);
      CAPTURE(threads);
      const Result r = scratch.run(std::string("run ") + scenarioPath(name) + " --quiet --trace trace.csv --duration " +
                                   duration + " --threads " + std::to_string(threads));
      REQUIRE_MESSAGE(r.code == 0, r.err);
      const auto rows = lastRows(slurp(scratch.dir / "trace.csv"));

      particles::Scenario scenario = particles::Scenario::load(scenarioPath(name));
      scenario.set("duration", duration);
      particles::Simulation sim(scenario, threads);
      sim.step(scenario.steps());
      const std::vector<std::string> names = sim.particleNames(), bodyNames = sim.bodyNames();
      REQUIRE(rows.size() == names.size() + bodyNames.size());
      int mismatches = 0;
      for (int i = 0; i < sim.particleCount(); ++i) {
        const TraceRow& row = rows.at(names[size_t(i)]);
        const particles::Point p = sim.position(i), u = sim.velocity(i);
        mismatches += !(row.x == p.x && row.y == p.y && row.vx == u.x && row.vy == u.y);
      }
      for (int j = 0; j < sim.bodyCount(); ++j) {
        const TraceRow& row = rows.at(bodyNames[size_t(j)]);
        const particles::BodyState b = sim.body(j);
        mismatches += !(row.x == b.x && row.y == b.y && row.angle == b.angle && row.omega == b.omega);
      }
      CHECK(mismatches == 0);
    }
  }
}

TEST_CASE("api: a blow-up is a SimulationError with the step, time, integrator and dt, at the last good state") {
  particles::Simulation sim(particles::Scenario::fromText(kExplodingScenario, "explodes.yaml"));
  try {
    sim.advance(100.0);
    FAIL("no exception");
  } catch (const particles::SimulationError& e) {
    CHECK(e.integrator() == particles::Integrator::euler);
    CHECK(e.dt() == 0.5);
    CHECK(e.step() >= 1);
    CHECK(std::string(e.what()).find("simulation exploded at step " + std::to_string(e.step())) != std::string::npos);
  }
  CHECK(std::isfinite(sim.position(1).x));
  CHECK(sim.time() < 100.0);
}

TEST_CASE("api: a Simulation driven by two threads at once refuses the second's call") {
  particles::Simulation sim(particles::Scenario::load(scenarioPath("cloth")));
  std::atomic<bool> stepping{false}, done{false};
  int refused = 0;
  std::thread worker([&] {
    stepping = true;
    for (;;) {  // the other thread's call may come first: then this one is refused, and tries again
      try {
        sim.step(400);  // long enough for the other thread to try
        break;
      } catch (const particles::Error&) {
      }
    }
    done = true;
  });
  while (!stepping) std::this_thread::yield();
  while (!done && refused == 0) {
    try {
      sim.step(0);
    } catch (const particles::Error& e) {
      CHECK(std::string(e.what()).find("in use by another thread") != std::string::npos);
      ++refused;
    }
  }
  worker.join();
  CHECK(refused == 1);
  CHECK(sim.steps() == 400);
}

TEST_CASE("api: version() is the headers' version") {
  CHECK(std::string(particles::version()) == PARTICLES_VERSION_STRING);
  CHECK(std::string(PARTICLES_VERSION_STRING) == std::to_string(PARTICLES_VERSION_MAJOR) + "." +
                                                      std::to_string(PARTICLES_VERSION_MINOR) + "." +
                                                      std::to_string(PARTICLES_VERSION_PATCH));
}

// One truth: a frame drawn through the API is the frame `particles render --at` writes,
// byte for byte, for the three demos at a time each, in the golden checks' size.
TEST_CASE("api: render() draws the pixels of particles render --at, and Image::savePng writes them") {
  const std::pair<const char*, const char*> frames[] = {{"cloth", "1.5"}, {"soft_body", "12"}, {"rigid_chain", "1"}};
  Scratch scratch;
  particles::Renderer renderer({.width = 320, .height = 180, .theme = particles::Theme::light, .msaa = 4});
  for (const auto& [name, time] : frames) {
    CAPTURE(name);
    const Result r = scratch.run(std::string("render ") + scenarioPath(name) + " -o cli.png --size 320x180 --theme light " +
                                 "--msaa 4 --quiet --at " + time);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const particles::render::Image expected = particles::render::readPng(scratch.dir / "cli.png");

    particles::Simulation sim(particles::Scenario::load(scenarioPath(name)));
    sim.advance(std::strtod(time, nullptr));
    const particles::Image frame = renderer.render(sim);
    REQUIRE(frame.width == 320);
    REQUIRE(frame.height == 180);
    CHECK(frame.rgba == expected.rgba);

    frame.savePng((scratch.dir / "api.png").string());
    CHECK(particles::render::readPng(scratch.dir / "api.png").rgba == expected.rgba);
  }
  CHECK(renderer.glDescription() == "none (the cpu raster)");  // auto without a GPU: no GL context
  particles::Renderer onGl({.width = 320, .height = 180, .msaa = 1, .raster = particles::Raster::resident});
  particles::Simulation swingOnGl(particles::Scenario::fromText(kSwingScenario, "swing.yaml"));
  onGl.render(swingOnGl);
  CHECK(onGl.glDescription().find("llvmpipe") != std::string::npos);

  // Without a size, the scenario's own.
  particles::Renderer bySceneSize({.msaa = 1});
  particles::Simulation swing(particles::Scenario::fromText(kSwingScenario, "swing.yaml"));
  const particles::Image small = bySceneSize.render(swing);
  CHECK(small.width == 160);
  CHECK(small.height == 120);
  CHECK(small.rgba.size() == size_t(160 * 120 * 4));
}

TEST_CASE("api: encodePng gives the bytes savePng writes, and a Renderer draws from any thread") {
  Scratch scratch;
  particles::Simulation sim(particles::Scenario::load(scenarioPath("cloth")));
  particles::Renderer renderer({.width = 64, .height = 48, .msaa = 1});
  const particles::Image frame = renderer.render(sim);
  frame.savePng((scratch.dir / "frame.png").string());
  const std::string saved = slurp(scratch.dir / "frame.png");
  CHECK(frame.encodePng() == std::vector<std::uint8_t>(saved.begin(), saved.end()));
  CHECK(frame.encodePng(true) != frame.encodePng(false));
  const particles::Image empty{2, 2, std::vector<std::uint8_t>()};
  CHECK_THROWS_AS(empty.encodePng(), particles::ArgumentError);
  // EGL binds a context to one thread at a time: the API lets it go after each frame.
  particles::Image fromThread;
  std::thread([&] { fromThread = renderer.render(sim); }).join();
  CHECK(fromThread.rgba == frame.rgba);
  CHECK(renderer.render(sim).rgba == frame.rgba);
}

TEST_CASE("api: keepGoing stops step and advance at a whole step, and the steps are the same bits") {
  const particles::Scenario cloth = particles::Scenario::load(scenarioPath("cloth"));
  particles::Simulation plain(cloth), asked(cloth);
  plain.advance(0.3);
  int calls = 0;
  CHECK(asked.advance(0.3, [&] { return ++calls > 0; }));
  CHECK(calls == 30);
  CHECK(asked.steps() == plain.steps());
  CHECK(std::equal(asked.positions().begin(), asked.positions().end(), plain.positions().begin()));
  CHECK_FALSE(asked.step(100, [&, left = 7]() mutable { return left-- > 0; }));
  CHECK(asked.steps() == 37);
  CHECK_FALSE(asked.advance(1.0, [] { return false; }));
  CHECK(asked.steps() == 37);
  // An exception the callback throws passes through as it is, at a whole step.
  struct Stop {};
  CHECK_THROWS_AS(asked.step(10, [] () -> bool { throw Stop{}; }), Stop);
  CHECK(asked.steps() == 37);
  CHECK_THROWS_AS(asked.step(-1, [] { return true; }), particles::ArgumentError);
}

TEST_CASE("api: defaultThreads() reads PARTICLES_THREADS as the command line does") {
  const char* before = std::getenv("PARTICLES_THREADS");
  const std::string saved = before ? before : "";
  ::setenv("PARTICLES_THREADS", "3", 1);
  CHECK(particles::defaultThreads() == 3);
  ::setenv("PARTICLES_THREADS", "0", 1);
  CHECK_THROWS_WITH_AS(particles::defaultThreads(), doctest::Contains("PARTICLES_THREADS"), particles::ArgumentError);
  ::unsetenv("PARTICLES_THREADS");
  CHECK(particles::defaultThreads() >= 1);
  if (before) ::setenv("PARTICLES_THREADS", saved.c_str(), 1);
}

// Moving the mouse target: a mouse taken over is the scripted mouse held at that target.
TEST_CASE("api: setMouseTarget holds the scenario's mouse at a target, the bits of the same script") {
  particles::Scenario cloth = particles::Scenario::load(scenarioPath("cloth"));
  particles::Simulation moved(cloth);
  particles::Scenario held = cloth;
  held.set("mouse[0].from", 0.0).set("mouse[0].to", 1e9).set("mouse[0].path", "[[1, -1]]");
  particles::Simulation scripted(held);
  CHECK(moved.mouseCount() == 1);
  CHECK_FALSE(moved.mouseTarget().has_value());
  moved.setMouseTarget({1.0, -1.0});
  REQUIRE(moved.mouseTarget().has_value());
  CHECK(moved.mouseTarget()->x == 1.0);
  moved.advance(1.0);
  scripted.advance(1.0);
  CHECK(std::equal(moved.positions().begin(), moved.positions().end(), scripted.positions().begin()));
  moved.releaseMouse();
  CHECK_FALSE(moved.mouseTarget().has_value());
  CHECK_THROWS_WITH_AS(moved.setMouseTarget({0, 0}, 1), doctest::Contains("out of range"), particles::ArgumentError);
  CHECK_THROWS_WITH_AS(moved.setMouseTarget({std::nan(""), 0}), doctest::Contains("finite"), particles::ArgumentError);
  particles::Simulation lone(particles::Scenario::fromText(kSwingScenario, "swing.yaml"));
  CHECK_THROWS_WITH_AS(lone.releaseMouse(), doctest::Contains("has none"), particles::ArgumentError);
}

// golden::check is `particles golden check`: the same function (golden/check_report.hpp).
TEST_CASE("api: golden::check checks a manifest into its report, and refuses bad options and folders") {
  Scratch scratch;
  const std::string manifest = (std::filesystem::path(kSource) / "golden" / "golden.yaml").string();
  const particles::golden::Report report =
      particles::golden::check(manifest, {.output = (scratch.dir / "report").string(), .only = {"cloth_t0.5"}, .jobs = 1});
  CHECK(report.allPassed());
  REQUIRE(report.frames.size() == 1);
  CHECK(report.frames[0].outcome == particles::golden::Outcome::passed);
  CHECK(report.frames[0].pixels == 320 * 240);
  CHECK(report.html == (scratch.dir / "report" / "report.html").string());
  CHECK(slurp(scratch.dir / "report" / "results.json").find("cloth_t0.5") != std::string::npos);
  CHECK(report.summary.find("1 passed") != std::string::npos);
  CHECK_THROWS_WITH_AS(particles::golden::check(manifest, {.output = (scratch.dir / "r2").string(),
                                                            .shard = particles::golden::Shard{3, 2}}),
                       doctest::Contains("shard"), particles::ArgumentError);
  CHECK_THROWS_WITH_AS(particles::golden::check(manifest, {.output = (scratch.dir / "r2").string(), .only = {"nope"}}),
                       doctest::Contains("nope"), particles::ArgumentError);
  CHECK_THROWS_AS(particles::golden::check((scratch.dir / "none.yaml").string()), particles::ScenarioError);
}

TEST_CASE("api: bad render settings and images are ArgumentErrors naming what each takes") {
  // A value outside an enum, cast in from a number, is refused as a bad name would be.
  CHECK_THROWS_WITH_AS(particles::Renderer({.theme = static_cast<particles::Theme>(7)}),
                       doctest::Contains("dark or light"), particles::ArgumentError);
  CHECK_THROWS_WITH_AS(particles::Renderer({.msaa = 3}), doctest::Contains("msaa"), particles::ArgumentError);
  CHECK_THROWS_AS(particles::Renderer({.width = 320}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::Renderer({.width = -5, .height = 10}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::Renderer({.width = 100000, .height = 10}), particles::Error);
  CHECK_THROWS_AS(particles::Renderer({.raster = static_cast<particles::Raster>(-1)}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::Renderer({.gl = static_cast<particles::GlBackend>(9)}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::Renderer({.background = static_cast<particles::Background>(2)}), particles::ArgumentError);

  Scratch scratch;
  particles::Image wrong{4, 4, std::vector<std::uint8_t>(10)};
  CHECK_THROWS_AS(wrong.savePng((scratch.dir / "x.png").string()), particles::ArgumentError);
  particles::Image fine{2, 2, std::vector<std::uint8_t>(16, 200)};
  CHECK_THROWS_AS(fine.savePng((scratch.dir / "no" / "such" / "x.png").string()), particles::OutputError);
  CHECK(scratch.files().empty());  // nothing half-written
}

TEST_CASE("api: VideoWriter writes MP4, WebM and GIF from frames, whole or not at all") {
  Scratch scratch;
  particles::Simulation sim(particles::Scenario::load(scenarioPath("cloth")));
  particles::Renderer renderer({.width = 160, .height = 90, .msaa = 1});
  for (const char* name : {"cloth.mp4", "cloth.webm", "cloth.gif"}) {
    CAPTURE(name);
    const fs::path path = scratch.dir / name;
    particles::VideoWriter video(path.string(), {.fps = 10});
    for (int i = 0; i < 5; ++i) {
      video.write(renderer.render(sim));
      sim.advance(0.1);
    }
    CHECK(video.frames() == 5);
    CHECK_FALSE(fs::exists(path));  // under a temporary name until finish()
    video.finish();
    const particles::test::VideoInfo info = particles::test::probeVideo(path);
    CHECK(info.frames == 5);
    CHECK(info.width == 160);
    CHECK(info.height == 90);
  }
  // Destroyed or aborted before finish(): nothing left, and an existing file untouched.
  const fs::path kept = scratch.write("kept.mp4", "an earlier video");
  {
    particles::VideoWriter video(kept.string(), {.fps = 10});
    video.write(renderer.render(sim));
  }
  CHECK(slurp(kept) == "an earlier video");
  {
    particles::VideoWriter video((scratch.dir / "aborted.mp4").string());
    video.write(renderer.render(sim));
    video.abort();
  }
  CHECK_FALSE(fs::exists(scratch.dir / "aborted.mp4"));
  std::vector<std::string> files = scratch.files();
  std::sort(files.begin(), files.end());
  CHECK(files == std::vector<std::string>{"cloth.gif", "cloth.mp4", "cloth.webm", "kept.mp4"});
}

TEST_CASE("api: a bad video path, setting or frame is an ArgumentError") {
  Scratch scratch;
  const std::string mp4 = (scratch.dir / "v.mp4").string();
  CHECK_THROWS_AS(particles::VideoWriter((scratch.dir / "v.avi").string()), particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter((scratch.dir / "v.png").string()), particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter(mp4, {.fps = -1}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter(mp4, {.fps = 1001}), particles::ArgumentError);
  // fps 0 is the format's default; GIF's default and its most are its own (no --fps in the message).
  CHECK_NOTHROW(particles::VideoWriter(mp4, {.fps = 0}));
  CHECK_NOTHROW(particles::VideoWriter((scratch.dir / "v.gif").string()));
  CHECK_THROWS_WITH_AS(particles::VideoWriter((scratch.dir / "v.gif").string(), {.fps = 60}),
                       "VideoWriter: fps for GIF must be 1 to 50 (or 0, the format's default): its delays are whole "
                       "centiseconds, and browsers slow delays under 2 cs down to 10 cs, got 60",
                       particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter(mp4, {.crf = 99}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter(mp4, {.preset = "warp"}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter(mp4, {.keyintSeconds = std::nan("")}), particles::ArgumentError);
  CHECK_THROWS_AS(particles::VideoWriter(mp4, {.alpha = true}), particles::ArgumentError);

  particles::VideoWriter video(mp4, {.fps = 10});
  CHECK_THROWS_AS(video.finish(), particles::ArgumentError);  // no frame yet
  CHECK_THROWS_AS(video.write(particles::Image{4, 4, std::vector<std::uint8_t>(3)}), particles::ArgumentError);
  CHECK_THROWS_AS(video.write(particles::Image{5, 4, std::vector<std::uint8_t>(80)}), particles::ArgumentError);  // odd side
  video.write(particles::Image{4, 4, std::vector<std::uint8_t>(64, 100)});
  CHECK_THROWS_WITH_AS(video.write(particles::Image{8, 4, std::vector<std::uint8_t>(128, 100)}),
                       doctest::Contains("like the first"), particles::ArgumentError);
  video.finish();
  CHECK(fs::exists(mp4));
  CHECK_THROWS_AS(video.write(particles::Image{4, 4, std::vector<std::uint8_t>(64, 100)}), particles::ArgumentError);
}
