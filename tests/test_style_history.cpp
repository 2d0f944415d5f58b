// What a style keeps of a run (render/style_history.hpp) and the StyledRun that draws from it
// (render/styled_run.hpp): a history fed elsewhere (the library's Simulation) draws the frames of a
// StyledRun that keeps its own (`particles render`), byte for byte, and a one-frame output is fitted
// to its own frame, whatever was fitted before.

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "core/solver.hpp"
#include "render/renderer.hpp"
#include "render/style_history.hpp"
#include "render/styled_run.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"

using namespace particles;

namespace {

// A small cloth whose corner is followed, with a trail on it and one on a body.
constexpr const char* kFollowed = R"(
name: followed
simulation: {integrator: rk4, dt: 0.01, duration: 1}
render: {size: [96, 64], fps: 10, view: {center: [0, 0], height: 3, follow: "cloth[3][2]", smoothing: 0.2}}
grids:
  - {name: cloth, origin: [-0.5, 0.5], size: [5, 4], spacing: [0.2, 0.2], mass: 0.01, springs: {structural: {ks: 20, kd: 0.01}}}
rigid_bodies:
  - {name: box, pos: [0.8, -0.6], size: [0.3, 0.1], mass: 0.2, vel: [0.5, 0.5], omega: 2}
particles:
  - {name: hook, pos: [0, 0.5], fixed: true}
forces:
  - {type: gravity}
  - {type: spring, a: hook, b: "cloth[0][2]", rest: 0.1, ks: 30, kd: 0.1}
style:
  particles: {color_by: speed}
  select:
    - {particles: "cloth[3][2]", trail: {seconds: 0.3}}
    - {bodies: box, trail: {seconds: all}, arrow: velocity}
)";

render::Camera fixedCamera(const scenario::Scenario& s) {
  return {s.render.viewCenter, s.render.viewHeight};
}

}  // namespace

TEST_CASE("style history: a StyledRun drawing from a history fed elsewhere draws the frames of one keeping its own") {
  scenario::Scenario owner = scenario::loadScenarioText(kFollowed, "followed.yaml");
  scenario::Scenario fed = scenario::loadScenarioText(kFollowed, "followed.yaml");
  REQUIRE(render::StyleHistory::needed(fed.style, fed.render.view));
  const render::RenderOptions look = test::smallRenderOptions(96, 64, 1);
  const double dt = owner.simulation.dt;
  render::StyledRun own(owner.style, owner.render.view, fixedCamera(owner), look, dt, 100);
  render::StyleHistory history(fed.style, fed.render.view, fixedCamera(fed), dt, 100);
  own.start(owner.system);
  history.start(fed.system);
  Stepper ownStepper(owner.system, owner.simulation.integrator, dt),
      fedStepper(fed.system, fed.simulation.integrator, dt);
  render::Renderer renderer(own.look());
  render::StyledFrameBuffers ownBuffers, fedBuffers;
  for (double t : {0.0, 0.35, 0.8}) {
    CAPTURE(t);
    own.advanceTo(ownStepper, owner.system, t);
    history.advanceTo(fedStepper, fed.system, t);
    // A new StyledRun for each frame, as Renderer::render makes one for its settings.
    render::StyledRun drawn(fed.style, fed.render.view, fixedCamera(fed), look, &history);
    CHECK(drawn.camera(t).center == own.camera(t).center);
    const render::Image expected = render::drawStyledFrame(owner.system, own, renderer, ownBuffers, true);
    CHECK(render::drawStyledFrame(fed.system, drawn, renderer, fedBuffers, true).rgba == expected.rgba);
  }
  CHECK(history.trails()->trails().size() == 2);
  CHECK(history.startTime() == 0.0);

  // A history is its owner's to feed; a followed camera cannot be drawn without one.
  render::StyledRun drawn(fed.style, fed.render.view, fixedCamera(fed), look, &history);
  CHECK_THROWS_AS(drawn.start(fed.system), std::logic_error);
  CHECK_THROWS_AS(drawn.advanceTo(fedStepper, fed.system, 1.0), std::logic_error);
  render::StyledRun without(fed.style, fed.render.view, fixedCamera(fed), look, nullptr);
  CHECK_THROWS_AS(without.camera(0.0), std::logic_error);
}

TEST_CASE("style history: a plain style keeps nothing, and a one-frame output is fitted to its own frame alone") {
  scenario::Scenario s = scenario::loadScenarioText(
      "name: fit\nsimulation: {dt: 0.01, duration: 1}\nrender: {size: [96, 64], view: {fit: all, margin: 0}}\n"
      "particles:\n  - {name: a, pos: [0, 0], vel: [4, 0]}\n  - {name: b, pos: [1, 0], vel: [2, 1]}\n",
      "fit.yaml");
  CHECK_FALSE(render::StyleHistory::needed(s.style, s.render.view));
  const render::RenderOptions look = test::smallRenderOptions(96, 64, 1);
  render::StyledRun run(s.style, s.render.view, fixedCamera(s), look, s.simulation.dt, 100);
  run.start(s.system);  // nothing to keep: no history, no error
  Drawing first, later;
  run.drawFrame(s.system, first, SpringDetail::topology);
  Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
  run.advanceTo(stepper, s.system, 0.5);
  CHECK(s.system.time() == doctest::Approx(0.5));
  run.drawFrame(s.system, later, SpringDetail::topology);
  render::StyledRun fresh(s.style, s.render.view, fixedCamera(s), look, nullptr);
  fresh.fitTo(later);
  run.fitTo(first);
  run.fitTo(later);  // not grown by the first frame's points
  CHECK(run.camera(0.5).center == fresh.camera(0.5).center);
  CHECK(run.camera(0.5).height == fresh.camera(0.5).height);
}
