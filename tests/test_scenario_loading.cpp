// Loading valid scenarios: defaults, references, grids, overrides (docs/physics.md §11, docs/scenarios.md).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/forces/damped_spring_force.hpp"
#include "core/colliders/disk_collider.hpp"
#include "core/forces/drag_force.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/colliders/half_plane_collider.hpp"
#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "scenario/scenario.hpp"

using namespace particles;
using namespace particles::scenario;

namespace {

int particleIndex(const System& s, const std::string& name) {
  const auto& names = s.model().particleNames;
  const auto it = std::find(names.begin(), names.end(), name);
  REQUIRE_MESSAGE(it != names.end(), "no particle " << name);
  return int(it - names.begin());
}

// All springs of the system, in the order the loader added them.
std::vector<SpringSpec> springsOf(const System& s) {
  std::vector<SpringSpec> out;
  for (const auto& f : s.forces()) {
    if (const auto* springs = dynamic_cast<const DampedSpringForce*>(f.get())) {
      for (size_t i = 0; i < springs->size(); ++i) out.push_back(springs->spring(i));
    }
  }
  return out;
}

}  // namespace

TEST_CASE("scenario: a name alone gives the documented defaults") {
  const Scenario s = loadScenarioText("name: empty\n", "x.yaml");
  CHECK(s.name == "empty");
  CHECK(s.description.empty());
  CHECK(s.simulation.integrator == Integrator::rk4);
  CHECK(s.simulation.dt == 0.01);
  CHECK(s.simulation.duration == 10.0);
  CHECK(s.simulation.steps() == 1000);
  CHECK(s.render.width == 1280);
  CHECK(s.render.height == 720);
  CHECK(s.render.fps == 60.0);
  CHECK(s.render.viewCenter == Vec2(0, 0));
  CHECK(s.render.viewHeight == 3.0);
  CHECK(s.system.layout().numPoints() == 0);
}

TEST_CASE("scenario: settings and particles as written") {
  const Scenario s = loadScenarioText(R"(
name: p
description: two particles
simulation: {integrator: midpoint, dt: 0.002, duration: 1.5}
render: {size: [640, 480], fps: 25, view: {center: [1, -2], height: 4}}
particles:
  - {name: anchor, pos: [0, 0], fixed: true, mass: 3}
  - {pos: [1, 2], vel: [3, 4], mass: 0.5}
)",
                                      "x.yaml");
  CHECK(s.description == "two particles");
  CHECK(s.simulation.integrator == Integrator::midpoint);
  CHECK(s.simulation.steps() == 750);
  CHECK(s.render.width == 640);
  CHECK(s.render.fps == 25);
  CHECK(s.render.viewCenter == Vec2(1, -2));
  CHECK(s.render.viewHeight == 4);
  const Model& m = s.system.model();
  CHECK(m.isFixed(0));
  CHECK(m.mass[0] == 3);
  CHECK(m.mass[1] == 0.5);
  CHECK(s.system.view().pos(1) == Vec2(1, 2));
  CHECK(s.system.view().vel(1) == Vec2(3, 4));
  CHECK(pointName(m, 0) == "anchor");
  CHECK(pointName(m, 1) == "#1");
}

TEST_CASE("scenario: grid springs with stiffness varying from top to bottom") {
  const Scenario s = loadScenarioText(R"(
name: g
grids:
  - name: cloth
    origin: [-1, 1]
    size: [4, 3]
    spacing: [0.5, 0.25]
    mass: 0.1
    springs:
      structural: {ks: [25, 1], kd: 0.2}
      shear: {ks: 7}
)",
                                      "x.yaml");
  const System& sys = s.system;
  CHECK(sys.layout().numParticles == 12);
  CHECK(springCount(sys) == size_t(3 * 3 + 2 * 4 + 2 * 2 * 3));
  const int corner = particleIndex(sys, "cloth[2][3]");
  CHECK(sys.view().pos(corner).isApprox(Vec2(0.5, 0.5)));
  double top = 0, bottom = 1e9;
  for (const SpringSpec& sp : springsOf(sys)) {
    if (sp.kd == 0.2) {
      top = std::max(top, sp.ks);
      bottom = std::min(bottom, sp.ks);
    } else {
      CHECK(sp.ks == 7);
    }
  }
  CHECK(top == 25);    // the top row's horizontal springs
  CHECK(bottom == 1);  // the bottom row's
}

TEST_CASE("scenario: references to grid rows, body anchors and element-wise spring lists") {
  const Scenario s = loadScenarioText(R"(
name: r
particles:
  - {name: hook, pos: [0, 2], fixed: true}
grids:
  - {name: g, origin: [0, 1], size: [3, 2], spacing: [1, 1]}
rigid_bodies:
  - {name: plate, pos: [5, 0], size: [2, 1], angle: 0}
  - {name: wheel, pos: [8, 0], size: [1, 1]}
forces:
  - {type: spring, a: hook, b: "g[0][*]", ks: 10}                                   # one to many
  - {type: spring, a: "g[-1][*]", b: ["g[0][2]", "g[0][1]", "g[0][0]"], ks: 10}    # element-wise
  - {type: spring, a: "plate@[1, 0.5]", b: wheel, ks: 10}
  - {type: spring, a: "plate @ [ -1, 0 ]", b: "g[1][2]", ks: 10, rest: 0.25}
constraints:
  - {type: horizontal_line, particles: "g[0][*]"}
  - {type: rod, a: "g[1][0]", b: "#0"}
)",
                                      "x.yaml");
  const System& sys = s.system;
  const auto springs = springsOf(sys);
  REQUIRE(springs.size() == 8);
  const int hook = particleIndex(sys, "hook");
  for (int i = 0; i < 3; ++i) {
    CHECK(springs[size_t(i)].a.particle == hook);
    CHECK(springs[size_t(i)].b.particle == particleIndex(sys, "g[0][" + std::to_string(i) + "]"));
  }
  CHECK(springs[3].a.particle == particleIndex(sys, "g[1][0]"));
  CHECK(springs[3].b.particle == particleIndex(sys, "g[0][2]"));
  CHECK(springs[5].b.particle == particleIndex(sys, "g[0][0]"));
  // rest defaults to the current distance: plate corner (6, 0.5) to wheel centre (8, 0)
  CHECK(springs[6].a.body == 0);
  CHECK(springs[6].a.anchor == Vec2(1, 0.5));
  CHECK(springs[6].b.body == 1);
  CHECK(springs[6].b.anchor == Vec2(0, 0));
  CHECK(springs[6].rest == doctest::Approx(std::sqrt(4.0 + 0.25)));
  CHECK(springs[7].a.anchor == Vec2(-1, 0));
  CHECK(springs[7].rest == 0.25);

  REQUIRE(sys.constraints().size() == 4);
  const auto* line = dynamic_cast<const HorizontalLineConstraint*>(sys.constraints()[0].get());
  REQUIRE(line);
  CHECK(line->height() == 1.0);  // y defaults to the particle's current height
  const auto* rod = dynamic_cast<const RodConstraint*>(sys.constraints()[3].get());
  REQUIRE(rod);
  CHECK(rod->b() == 0);
  CHECK(rod->length() == doctest::Approx(2.0));  // g[1][0] at (0, 0) to #0, the hook at (0, 2)
  CHECK(rod->feedback().ks == ConstraintFeedback{}.ks);
  CHECK(pointName(sys.model(), sys.layout().bodyPoint(1)) == "wheel");
}

TEST_CASE("scenario: forces, constraint feedback, colliders and mouse as written") {
  const Scenario s = loadScenarioText(R"(
name: f
particles:
  - {name: a, pos: [0, 0]}
  - {name: b, pos: [0, 1]}
forces:
  - {type: gravity}
  - {type: gravity, g: [1, 0]}
  - {type: drag, kd: 0.1, angular: 0.01}
constraints:
  - {type: circular_wire, particle: a, center: [1, 0], ks: 50, kd: 5}
  - {type: rod, a: a, b: b, length: 2}
colliders:
  - {type: half_plane, normal: [0, 2], offset: -1, k: 500, damping: 3}
  - {type: disk, center: [3, 0], radius: 0.5}
mouse:
  - {grab: b, from: 0.5, to: 2, path: [[0, 0], [1, 1]], ks: 20}
)",
                                      "x.yaml");
  const System& sys = s.system;
  REQUIRE(sys.forces().size() == 4);
  CHECK(dynamic_cast<const GravityForce&>(*sys.forces()[0]).g() == Vec2(0, -9.81));
  CHECK(dynamic_cast<const GravityForce&>(*sys.forces()[1]).g() == Vec2(1, 0));
  CHECK(dynamic_cast<const DragForce&>(*sys.forces()[2]).kd() == 0.1);
  const auto& mouse = dynamic_cast<const MouseSpringForce&>(*sys.forces()[3]);
  CHECK(mouse.script().from == 0.5);
  CHECK(mouse.script().to == 2);
  CHECK(mouse.script().ks == 20);
  CHECK(mouse.script().path.size() == 2);
  CHECK(mouse.script().grab.particle == 1);
  CHECK(mouseScriptCount(sys) == 1);

  CHECK(sys.constraints()[0]->feedback().ks == 50);
  CHECK(sys.constraints()[0]->feedback().kd == 5);
  CHECK(sys.constraints()[1]->feedback().kd == ConstraintFeedback{}.kd);
  CHECK(dynamic_cast<const RodConstraint&>(*sys.constraints()[1]).length() == 2);

  const auto& ground = dynamic_cast<const HalfPlaneCollider&>(*sys.colliders()[0]);
  CHECK(ground.normal() == Vec2(0, 1));
  CHECK(ground.offset() == -1);
  CHECK(ground.params().k == 500);
  CHECK(ground.params().damping == 3);
  const auto& disk = dynamic_cast<const DiskCollider&>(*sys.colliders()[1]);
  CHECK(disk.params().k == PenaltyParams{}.k);
  CHECK(disk.params().damping == 0);
}

TEST_CASE("scenario: --set overrides any value before validation, creating keys as needed") {
  const std::string yaml =
      "name: o\nparticles:\n  - {name: a, pos: [0, 0], mass: 1}\nforces:\n  - {type: drag, kd: 1}\n";
  const std::vector<Override> overrides{
      parseOverride("simulation.dt=0.005"),    parseOverride("render.fps=30"),
      parseOverride("particles[0].mass=2.5"),  parseOverride("forces.0.kd=0.25"),
      parseOverride("render.size=[320, 200]"), {"simulation.integrator", "euler", "--integrator euler"}};
  const Scenario s = loadScenarioText(yaml, "x.yaml", overrides);
  CHECK(s.simulation.dt == 0.005);
  CHECK(s.simulation.integrator == Integrator::euler);
  CHECK(s.render.fps == 30);
  CHECK(s.render.width == 320);
  CHECK(s.system.model().mass[0] == 2.5);
  CHECK(dynamic_cast<const DragForce&>(*s.system.forces()[0]).kd() == 0.25);
}

TEST_CASE("scenario: YAML anchors and aliases share settings") {
  const Scenario s = loadScenarioText(R"(
name: a
grids:
  - {name: a, size: [2, 2], springs: &soft {structural: {ks: 3}}}
  - {name: b, origin: [5, 0], size: [2, 2], springs: *soft}
)",
                                      "x.yaml");
  CHECK(springCount(s.system) == 8);
}

TEST_CASE("scenario: steps cover the duration") {
  SimulationSettings sim;
  sim.dt = 0.15;
  sim.duration = 60;
  CHECK(sim.steps() == 400);
  sim.dt = 0.3;
  sim.duration = 1;
  CHECK(sim.steps() == 4);
}
