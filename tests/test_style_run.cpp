// Styles over a run (render/styled_run.hpp, src/style/): the quantities a style colours by, their
// ranges, the camera's modes and the trails, checked by numbers; and that a styled render steps the
// same bits as a plain one and a split render equals the whole render, byte for byte.

#include <doctest/doctest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "render/errors.hpp"
#include "render/styled_run.hpp"
#include "render/video/render_simulation.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"
#include "style/camera_path.hpp"
#include "style/quantity.hpp"
#include "style/trail_history.hpp"

using namespace particles;
using particles::test::ScratchDir;

namespace {

// A small cloth on a rail, pulled by a scripted mouse, with a rigid body on a spring: every kind of
// shape a style colours, and constraint forces (whose warm start must survive the pass).
constexpr const char* kScene = R"(
name: styled
simulation: {integrator: rk4, dt: 0.01, duration: 1}
render: {size: [96, 64], fps: 10, view: {center: [0, 0], height: 3}}
grids:
  - name: cloth
    origin: [-0.5, 0.5]
    size: [6, 5]
    spacing: [0.2, 0.2]
    mass: 0.01
    springs:
      structural: {ks: 20, kd: 0.01}
rigid_bodies:
  - {name: box, pos: [0.8, -0.6], size: [0.3, 0.1], mass: 0.2, vel: [0.5, 0.5], omega: 2}
particles:
  - {name: hook, pos: [0.8, 0.2], fixed: true}
forces:
  - {type: gravity}
  - {type: spring, a: hook, b: "box@[0.15, 0]", rest: 0.5, ks: 30, kd: 0.1}
constraints:
  - {type: horizontal_line, particles: "cloth[0][*]", y: 0.5}
mouse:
  - {grab: "cloth[4][2]", from: 0.2, to: 0.7, path: [[0, -0.6], [0.6, -0.4]], ks: 1}
)";

scenario::Scenario scene() {
  return scenario::loadScenarioText(kScene, "styled.yaml");
}

// Particle indices of the grid's row `row` (grids are numbered row by row from the top).
std::vector<int> gridRow(int row) {
  std::vector<int> out;
  for (int c = 0; c < 6; ++c) out.push_back(row * 6 + c);
  return out;
}

style::Style colourfulStyle() {
  style::Style s;
  s.particles.colorBy = style::ParticleQuantity::speed;
  s.springs.colorBy = style::SpringQuantity::tension;
  s.springs.colormap = style::Colormap{style::ColormapName::coolwarm, false};
  s.bodies.colorBy = style::BodyQuantity::angularSpeed;
  s.colorbar = style::ColorbarStyle{};
  s.title = "styled";
  s.scaleBar = true;
  style::Selection corner;
  corner.particlesSelector = "cloth[4][2]";
  corner.particles = {4 * 6 + 2};
  corner.trail = style::TrailStyle{};
  corner.trail->seconds = 0.5;
  corner.arrow = style::ArrowStyle{};
  corner.label = "corner";
  s.select.push_back(corner);
  style::Selection box;
  box.bodiesSelector = "box";
  box.bodies = {0};
  box.trail = style::TrailStyle{};
  box.arrow = style::ArrowStyle{};
  box.arrow->of = style::ArrowQuantity::force;
  box.arrow->scale = 0.05;
  s.select.push_back(box);
  return s;
}

render::RenderJob styledJob(const scenario::Scenario& s, const std::filesystem::path& output) {
  render::RenderJob job;
  job.output = output;
  job.duration = s.simulation.duration;
  job.fps = 10;
  job.camera = {s.render.viewCenter, s.render.viewHeight};
  job.look = particles::test::smallRenderOptions(96, 64);
  job.look.raster = Raster::cpu;
  job.style = colourfulStyle();
  job.view.mode = style::ViewStyle::Mode::follow;
  job.view.followParticle = 4 * 6 + 2;
  job.view.smoothing = 0.2;
  return job;
}

std::string bytesOf(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("style quantities: speed, kinetic energy, tension and energy of springs, body speeds, by their formulas") {
  scenario::Scenario s = scene();
  Stepper(s.system, Integrator::rk4, 0.01).advanceTo(0.3);
  Drawing d;
  s.system.draw(d, SpringDetail::topology, {.velocities = true, .accelerations = false, .masses = true});
  REQUIRE(d.particleVelocities.size() == d.particles.size());
  std::vector<double> v;
  style::particleValues(d, style::ParticleQuantity::speed, v);
  const StateView state = s.system.view();
  for (size_t i = 0; i < d.particles.size(); ++i) CHECK(v[i] == state.vel(int(i)).norm());
  style::particleValues(d, style::ParticleQuantity::kineticEnergy, v);
  CHECK(v[7] == doctest::Approx(0.5 * 0.01 * state.vel(7).squaredNorm()));
  style::particleValues(d, style::ParticleQuantity::height, v);
  CHECK(v[3] == state.pos(3).y());
  // Springs: one has an end on the body, so all come by position, each with its rest and stiffness.
  std::vector<double> tension, energy, strain;
  style::springValues(d, style::SpringQuantity::tension, tension);
  style::springValues(d, style::SpringQuantity::energy, energy);
  style::springValues(d, style::SpringQuantity::strain, strain);
  REQUIRE(d.springsByIndex() == 0);
  REQUIRE(tension.size() == d.springs.size());
  int hooks = 0;
  for (size_t k = 0; k < tension.size(); ++k) {
    const Drawing::Spring& spring = d.springs[k];
    const double length = (spring.a - spring.b).norm();
    CHECK(spring.stiffness == (spring.rest == 0.5 ? 30.0 : 20.0));
    CHECK(tension[k] == doctest::Approx(spring.stiffness * (length - spring.rest)));
    CHECK(energy[k] == doctest::Approx(0.5 * spring.stiffness * (length - spring.rest) * (length - spring.rest)));
    CHECK(strain[k] == spring.strain);
    hooks += spring.rest == 0.5;
  }
  CHECK(hooks == 1);
  // By index (a drawing of the cloth alone), the same values from the topology's rest and stiffness.
  scenario::Scenario cloth = scenario::loadScenarioFile(PARTICLES_SOURCE_DIR "/scenarios/cloth.yaml");
  Stepper(cloth.system, Integrator::rk4, 0.01).advanceTo(0.2);
  Drawing byIndex, byPosition;
  cloth.system.draw(byIndex, SpringDetail::topology);
  cloth.system.draw(byPosition, SpringDetail::positions);
  REQUIRE(byIndex.springsByIndex() == byPosition.springs.size());
  std::vector<double> fromTopology, fromPositions;
  style::springValues(byIndex, style::SpringQuantity::tension, fromTopology);
  style::springValues(byPosition, style::SpringQuantity::tension, fromPositions);
  CHECK(fromTopology == fromPositions);
  style::bodyValues(d, style::BodyQuantity::angularSpeed, v);
  CHECK(v[0] == std::abs(state.omega(0)));
  // Without the detail asked for, a clear error rather than a read past the end.
  Drawing plain;
  s.system.draw(plain, SpringDetail::topology);
  CHECK_THROWS_AS(style::particleValues(plain, style::ParticleQuantity::speed, v), std::invalid_argument);
}

TEST_CASE("style quantities: accelerations are F/m with constraint forces, and looking at them changes no step") {
  scenario::Scenario a = scene(), b = scene();
  Stepper stepA(a.system, Integrator::rk4, 0.01), stepB(b.system, Integrator::rk4, 0.01);
  Drawing d;
  for (int k = 0; k < 40; ++k) {
    stepA.step();
    stepB.step();
    b.system.addAccelerations(d);
  }
  CHECK(a.system.state() == b.system.state());  // bit for bit: the warm start was put back
  // The rail holds the top row: its vertical acceleration is zero up to the solver's tolerance,
  // while gravity alone would give −9.81.
  for (int i : gridRow(0)) CHECK(std::abs(d.particleAccelerations[size_t(i)].y()) < 1e-6);
  // A free particle of the cloth's middle feels gravity and its springs: not −g exactly, but finite.
  CHECK(std::isfinite(d.particleAccelerations[14].norm()));
}

TEST_CASE("System::checkpoint: stepping again from a restored checkpoint gives the same bits") {
  scenario::Scenario s = scene();
  Stepper(s.system, Integrator::rk4, 0.01).advanceTo(0.25);
  const System::Checkpoint c = s.system.checkpoint();
  Stepper(s.system, Integrator::rk4, 0.01).advanceTo(0.6);
  const Eigen::VectorXd first = s.system.state();
  s.system.restore(c);
  CHECK(s.system.time() == c.t);
  Stepper(s.system, Integrator::rk4, 0.01).advanceTo(0.6);
  CHECK(s.system.state() == first);
}

TEST_CASE("colour scales: given ranges, auto ranges widened where flat, log scales") {
  style::Range automatic;
  style::ValueRange seen;
  CHECK(style::scaleOf(automatic, seen).lo == 0.0);  // nothing seen: [0, 1]
  seen.add({2.0, 5.0, std::nan(""), 3.0}, false);
  style::ColorScale s = style::scaleOf(automatic, seen);
  CHECK(s.lo == 2.0);
  CHECK(s.hi == 5.0);
  CHECK(s.position(3.5) == doctest::Approx(0.5));
  CHECK(s.position(-1.0) == 0.0);
  CHECK(s.position(9.0) == 1.0);
  style::ValueRange flat;
  flat.add({4.0, 4.0}, false);
  s = style::scaleOf(automatic, flat);
  CHECK(s.lo == 2.0);
  CHECK(s.hi == 6.0);
  style::Range log{.automatic = false, .lo = 0.01, .hi = 100.0, .logScale = true};
  s = style::scaleOf(log, seen);
  CHECK(s.position(1.0) == doctest::Approx(0.5));
  CHECK(s.position(0.0) == 0.0);
  style::ValueRange positive;
  positive.add({-3.0, 0.0, 0.5, 8.0}, true);  // a log scale sees the positive values only
  CHECK(positive.lo == 0.5);
}

TEST_CASE("camera path: follow lags a steady mover by 2τv, 0 locks on, keys ease, fit holds the box") {
  // A lone particle moving at 1 m/s: the critically damped camera settles 2τ behind it.
  scenario::Scenario s = scenario::loadScenarioText(
      "name: mover\nsimulation: {integrator: euler, dt: 0.001, duration: 5}\nparticles:\n  - {name: p, pos: [0, 0], "
      "vel: [1, 0]}\n",
      "mover.yaml");
  style::ViewStyle view;
  view.mode = style::ViewStyle::Mode::follow;
  view.followParticle = 0;
  view.smoothing = 0.25;
  style::CameraPath camera(view, {Vec2::Zero(), 3.0}, 1.5);
  style::ViewStyle lockedView = view;
  lockedView.smoothing = 0.0;
  style::CameraPath locked(lockedView, {Vec2::Zero(), 3.0}, 1.5);
  camera.start(s.system);
  locked.start(s.system);
  Stepper stepper(s.system, Integrator::euler, 0.001);
  double lastX = 0.0;
  bool overshot = false;
  for (int k = 0; k < 4000; ++k) {
    stepper.step();
    camera.afterStep(s.system, 0.001);
    locked.afterStep(s.system, 0.001);
    overshot = overshot || camera.at(s.system.time()).center.x() > s.system.view().pos(0).x();
    CHECK(camera.at(0).center.x() >= lastX);  // moves one way only
    lastX = camera.at(0).center.x();
  }
  const double lag = s.system.view().pos(0).x() - camera.at(4.0).center.x();
  CHECK(lag == doctest::Approx(2 * 0.25).epsilon(0.01));
  CHECK_FALSE(overshot);
  CHECK(locked.at(4.0).center == s.system.view().pos(0));
  CHECK(camera.at(4.0).height == 3.0);

  style::ViewStyle keys;
  keys.mode = style::ViewStyle::Mode::keys;
  keys.keys = {{0.0, Vec2(0, 0), 1.0}, {2.0, Vec2(4, 2), 4.0}};
  const style::CameraPath keyed(keys, {Vec2::Zero(), 3.0}, 1.5);
  CHECK(keyed.at(-1.0).height == 1.0);
  CHECK(keyed.at(1.0).center.x() == doctest::Approx(2.0));  // smoothstep(½) = ½
  CHECK(keyed.at(1.0).height == doctest::Approx(2.0));      // the geometric mean
  CHECK(keyed.at(0.5).center.x() == doctest::Approx(4 * 0.15625));
  CHECK(keyed.at(9.0).center == Vec2(4, 2));

  style::ViewStyle fit;
  fit.mode = style::ViewStyle::Mode::fit;
  fit.fitAll = true;
  fit.margin = 0.0;
  style::CameraPath fitted(fit, {Vec2::Zero(), 3.0}, 2.0);
  Drawing a, b;
  a.particles = {Vec2(0, 0), Vec2(1, 1)};
  b.particles = {Vec2(-1, 0.5), Vec2(3, 0)};
  fitted.observe(a);
  fitted.observe(b);
  fitted.endPass();
  CHECK(fitted.at(0).center == Vec2(1, 0.5));
  CHECK(fitted.at(0).height == doctest::Approx(2.0));  // 4 m wide at an aspect of 2
}

TEST_CASE("trails: a sample per step within their window, and more than the limit refused before the run") {
  scenario::Scenario s = scene();
  style::Style st = colourfulStyle();
  style::TrailHistory trails(st, 0.01, 100);
  REQUIRE(trails.trails().size() == 2);
  trails.start(s.system);
  Stepper stepper(s.system, Integrator::rk4, 0.01);
  for (int k = 0; k < 100; ++k) {
    stepper.step();
    trails.afterStep(s.system);
  }
  CHECK(trails.trails()[0].samples.size() == 52);   // 0.5 s of 0.01 s steps, and one before
  CHECK(trails.trails()[1].samples.size() == 101);  // the whole run, from its start
  CHECK(trails.trails()[0].samples.back().p == s.system.view().pos(4 * 6 + 2));

  style::Style huge = st;
  huge.select[0].particles.assign(1'000'000, 0);
  huge.select[0].trail->seconds = 1e6;
  CHECK_THROWS_AS(style::TrailHistory(huge, 0.01, 100'000'000), style::TrailLimitError);
  const scenario::Scenario cloth = scene();
  CHECK_THROWS_AS(render::StyledRun(huge, {}, {}, particles::test::smallRenderOptions(96, 64), 0.01, 100'000'000),
                  render::OutOfMemory);
}

TEST_CASE("styled render: the state after it is a plain render's, and a split render equals the whole, byte for byte") {
  ScratchDir dir;
  render::setLibavVerbose(false);
  scenario::Scenario whole = scene();
  render::RenderJob job = styledJob(whole, dir / "whole/");
  const render::RenderSummary all = render::renderSimulation(whole.system, Integrator::rk4, 0.01, job);
  CHECK(all.frames == 10);
  scenario::Scenario plain = scene();
  render::RenderJob plainJob = job;
  plainJob.output = dir / "plain/";
  plainJob.style = {};
  plainJob.view = {};
  render::renderSimulation(plain.system, Integrator::rk4, 0.01, plainJob);
  CHECK(plain.system.state() == whole.system.state());  // the pass and the accelerations step nothing

  scenario::Scenario part = scene();
  render::RenderJob split = job;
  split.output = dir / "part/";
  split.frames = std::pair<long, long>{6, 9};
  render::renderSimulation(part.system, Integrator::rk4, 0.01, split);
  for (int k = 6; k < 9; ++k) {
    const std::string name = fmt::format("frame_{:06d}.png", k);
    INFO(name);
    CHECK(bytesOf(dir / "part" / name) == bytesOf(dir / "whole" / name));
    CHECK(bytesOf(dir / "plain" / name) != bytesOf(dir / "whole" / name));
  }
  // On more threads, the same frames.
  scenario::Scenario threaded = scene();
  threaded.system.setThreads(3);
  render::RenderJob onThreads = job;
  onThreads.output = dir / "threads/";
  onThreads.threads = 3;
  render::renderSimulation(threaded.system, Integrator::rk4, 0.01, onThreads);
  for (int k = 0; k < 10; ++k) {
    const std::string name = fmt::format("frame_{:06d}.png", k);
    INFO(name);
    CHECK(bytesOf(dir / "threads" / name) == bytesOf(dir / "whole" / name));
  }
}

TEST_CASE("styled render on the command line: a trail of 10⁶ s on every particle exits 3 with the limit, bounded") {
  particles::test::Scratch s;
  // 10⁶ s of 0.01 s steps on the cloth's 625 particles: 6·10¹⁰ samples, refused before the run.
  particles::test::Scratch::Usage usage;
  const particles::test::Result r =
      s.runBounded("render '" PARTICLES_SOURCE_DIR
                   "/scenarios/cloth.yaml' -o cloth.mp4 --duration 1000000 "
                   "--set 'style.select=[{particles: \"cloth[*][*]\", trail: {seconds: 1000000}}]'",
                   usage);
  CHECK(r.code == 3);
  CHECK_MESSAGE(r.err.find("16000000 positions") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find("style.select[0].trail") != std::string::npos, r.err);
  // Refused before any trail is kept: the program's start-up and the scene, far from the 16
  // million positions (384 MB) the trails would hold at the limit. ASan's own memory hides it.
  if (!particles::test::kSanitized) CHECK(usage.peakMiB < 512);
  CHECK(s.files().empty());
}

TEST_CASE("styled render on the command line: --frames pieces equal the whole render with range: auto and follow") {
  particles::test::Scratch s;
  s.write("look.yaml",
          "particles: {color_by: speed}\n"
          "colorbar: {for: particles}\n"
          "title: swing\n"
          "select:\n"
          "  - {particles: bob, trail: {seconds: 0.5}, arrow: velocity, label: bob}\n");
  const std::string scene = s.write("swing.yaml", particles::test::kSwingScenario).string();
  const std::string common = "render '" + scene + "' --style look.yaml --set 'render.view.follow=bob' ";
  REQUIRE(s.run(common + "-o whole/").code == 0);
  REQUIRE(s.run(common + "-o part/ --frames 4:7").code == 0);
  for (int k = 4; k < 7; ++k) {
    const std::string name = fmt::format("frame_{:06d}.png", k);
    INFO(name);
    CHECK(bytesOf(s.dir / "part" / name) == bytesOf(s.dir / "whole" / name));
  }
  // A frame drawn alone (--at) is its own output: its range is its own frame's, so it may differ
  // from the video's frame in colour, but its trail and camera are the run's.
  REQUIRE(s.run(common + "-o at.png --at 0.5").code == 0);
  CHECK(std::filesystem::exists(s.dir / "at.png"));
}
