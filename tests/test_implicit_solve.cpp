// The implicit integrators' linear solve (core/implicit_step.hpp): the direct path (reduced
// coordinates, a sparse LDLᵀ reused across steps, the Schur complement for other rows) against the
// projected CG, its choice, and its limits.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "core/integrators/backward_euler.hpp"
#include "scenario/scenario.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

namespace {

// A chain of 24 stiff springs (k = 2500 N/m, 2 g particles) whose top slides on a horizontal rail,
// hung at an angle so that it swings and the rail pushes.
System swingingChainOnRail() {
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  int previous = b.addParticle(particleAt(0.0, 0.0, 0.002));
  b.addConstraint(std::make_unique<HorizontalLineConstraint>(previous, 0.0));
  for (int i = 1; i <= 24; ++i) {
    const int p = b.addParticle(particleAt(0.06 * i, -0.05 * i, 0.002));
    springs.add({Endpoint::ofParticle(previous), Endpoint::ofParticle(p), 0.075, 2500.0, 0.01});
    previous = p;
  }
  b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  return b.build();
}

scenario::Scenario loadProjectScenario(const std::string& name, const std::vector<scenario::Override>& overrides = {}) {
  return scenario::loadScenarioFile(std::string(PARTICLES_SOURCE_DIR) + "/scenarios/" + name, overrides);
}

struct OneStep {
  Eigen::VectorXd y, dv;
  ImplicitStepStats stats;
};

// One backward Euler step from the system's state with the given solve, from fresh scratch (so
// the direct path factors A itself); CG to 1e-14.
OneStep stepWith(System& system, ImplicitSolver solver) {
  OneStep out{system.state(), {}, {}};
  BackwardEulerState w({.cgTolerance = 1e-14});
  const ImplicitSolver before = system.implicitSolver();
  system.setImplicitSolver(solver);
  w.step(system, out.y, system.time(), 1.0 / 60.0);
  system.setImplicitSolver(before);
  out.dv = w.implicitStep()->lastSystem().dv;
  out.stats = w.implicitStep()->stats();
  return out;
}

}  // namespace

TEST_CASE("the direct solve's reduced coordinates against the projected CG: a chain swinging on a rail") {
  System chain = swingingChainOnRail();
  Solver solver(Integrator::backwardEuler);
  for (int i = 0; i < 30; ++i) solver.doStep(chain, 1.0 / 60.0);  // swinging, the rail pushing
  // A vertical velocity at the rail (as after a kick): its coordinate's known Δv = −0.3 m/s must
  // reach the free rows through A's column, as the projection's J Δv = −J v₀ does.
  const Eigen::Index vy = chain.layout().velocityOffset() + 1;
  chain.state()[vy] = 0.3;
  const OneStep cg = stepWith(chain, ImplicitSolver::cg);
  const OneStep direct = stepWith(chain, ImplicitSolver::direct);
  CHECK(cg.stats.solver == ImplicitSolver::cg);
  CHECK(direct.stats.solver == ImplicitSolver::direct);
  CHECK(direct.stats.eliminated == 1);  // the rail's y
  CHECK(direct.stats.schurRows == 0);
  CHECK(direct.stats.factorized);
  CAPTURE(cg.dv.norm());
  CHECK(cg.dv.norm() > 1e-3);
  CHECK((direct.dv - cg.dv).norm() < 1e-9 * cg.dv.norm());
  CHECK((direct.y - cg.y).norm() < 1e-9 * cg.y.norm());
  // The rail holds in both: the top's vertical velocity ends the step at 0 (Ċ = 0).
  CHECK(std::abs(cg.y[vy]) < 1e-12);
  CHECK(direct.y[vy] == 0.0);
}

TEST_CASE("the direct solve against the projected CG on the stiff cloth, its rail eliminated") {
  scenario::Scenario s = loadProjectScenario("cloth_stiff.yaml");
  Stepper(s.system, Integrator::backwardEuler, 1.0 / 60.0).advanceTo(2.0);  // the mouse pulling
  // The rail's particles moving off it, each differently: the known Δv of the eliminated rows.
  for (int column = 0; column < 25; ++column)
    s.system.state()[s.system.layout().velocityOffset() + 2 * column + 1] = 0.01 * (column - 12);
  const OneStep cg = stepWith(s.system, ImplicitSolver::cg);
  const OneStep direct = stepWith(s.system, ImplicitSolver::direct);
  CHECK(direct.stats.eliminated == 25);  // the top row's y on the rail
  CHECK(direct.stats.schurRows == 0);
  CAPTURE(cg.stats.iterations);
  CHECK((direct.dv - cg.dv).norm() < 1e-9 * cg.dv.norm());
  CHECK((direct.y - cg.y).norm() < 1e-9 * cg.y.norm());
}

TEST_CASE("the direct solve reuses its factors while they serve, and stays with the exact solve") {
  // 2 s of the stiff cloth, the mouse starting at 1.5 s: the factors are refactored on some steps
  // only, the pattern's change when the mouse grabs is followed, and the state stays within the
  // stopping tolerance's reach of a run whose every step is solved to 1e-14 by CG.
  scenario::Scenario reused = loadProjectScenario("cloth_stiff.yaml");
  scenario::Scenario exact = loadProjectScenario("cloth_stiff.yaml");
  reused.system.setImplicitSolver(ImplicitSolver::direct);
  Solver solver(Integrator::backwardEuler);
  BackwardEulerState w({.cgTolerance = 1e-14});
  exact.system.setImplicitSolver(ImplicitSolver::cg);
  const long steps = 120;
  long refactored = 0, iterations = 0;
  for (long i = 0; i < steps; ++i) {
    solver.doStep(reused.system, 1.0 / 60.0);
    refactored += solver.lastImplicitStep().factorized ? 1 : 0;
    iterations += solver.lastImplicitStep().iterations;
    Eigen::VectorXd y = exact.system.state();
    w.step(exact.system, y, exact.system.time(), 1.0 / 60.0);
    exact.system.state() = y;
    exact.system.projectOntoConstraints(exact.system.state());
    exact.system.setTime(double(i + 1) / 60.0);
  }
  CAPTURE(refactored);
  CAPTURE(iterations);
  CHECK(solver.factorizations() == refactored);
  CHECK(refactored >= 2);         // the first step, and the mouse's new pattern at 1.5 s
  CHECK(refactored < steps / 2);  // reused on most steps
  CHECK(iterations < 4 * steps);
  const double scale = exact.system.state().norm();
  CHECK((reused.system.state() - exact.system.state()).norm() < 1e-6 * scale);
}

TEST_CASE("auto keeps CG where it is cheap and moves to the direct solve where CG's iterations cost more") {
  // The demo cloth with springs 10× softer: CG needs 10 iterations a step at most, below the 14 the
  // direct solve costs at 1,225 free coordinates, over the whole 10 s (the mouse's drag included).
  CHECK(autoDirectIterations(1225) == doctest::Approx(13.915).epsilon(1e-4));
  CHECK(autoDirectIterations(20000) == doctest::Approx(32.164).epsilon(1e-4));
  scenario::Scenario soft =
      loadProjectScenario("cloth.yaml", {scenario::parseOverride("grids.0.springs.structural.ks=[2.5, 0.1]")});
  Solver a(Integrator::backwardEuler);
  int most = 0;
  for (int step = 0; step < 600; ++step) {
    a.doStep(soft.system, 1.0 / 60.0);
    CHECK(a.lastImplicitStep().solver == ImplicitSolver::cg);
    most = std::max(most, a.lastImplicitStep().iterations);
  }
  CAPTURE(most);
  CHECK(a.factorizations() == 0);
  // The stiff cloth: it starts flat and at rest, where CG needs about 24 iterations; as it swings
  // CG needs far more (165 a step over the 10 s), and once kAutoWindow CG steps averaged over
  // 13.9 the run moves to the direct solve, for good.
  scenario::Scenario stiff = loadProjectScenario("cloth_stiff.yaml");
  Solver b(Integrator::bdf2);
  int firstDirect = -1;
  std::vector<int> iterations;
  for (int step = 0; step < 120; ++step) {
    b.doStep(stiff.system, 1.0 / 60.0);
    const bool direct = b.lastImplicitStep().solver == ImplicitSolver::direct;
    if (direct && firstDirect < 0) firstDirect = step;
    if (!direct) {
      CHECK(firstDirect < 0);  // never back to CG
      iterations.push_back(b.lastImplicitStep().iterations);
    }
  }
  CAPTURE(firstDirect);
  REQUIRE(firstDirect >= kAutoWindow);
  REQUIRE(int(iterations.size()) == firstDirect);
  double lastWindow = 0.0;
  for (int k = firstDirect - kAutoWindow; k < firstDirect; ++k)
    lastWindow += iterations[size_t(k)] / double(kAutoWindow);
  CHECK(lastWindow > autoDirectIterations(1225));
  // Forced either way, whatever the iterations.
  stiff.system.setImplicitSolver(ImplicitSolver::cg);
  b.doStep(stiff.system, 1.0 / 60.0);
  CHECK(b.lastImplicitStep().solver == ImplicitSolver::cg);
  soft.system.setImplicitSolver(ImplicitSolver::direct);
  a.doStep(soft.system, 1.0 / 60.0);
  CHECK(a.lastImplicitStep().solver == ImplicitSolver::direct);
}

TEST_CASE("the direct solve refuses more general rows than its Schur complement takes, and auto stays with CG") {
  // A net of rods: more rows than kMaxSchurRows that are not rails. auto keeps CG whatever its
  // iterations; direct says why it cannot, naming the setting.
  SystemBuilder b;
  const int side = 10;
  std::vector<int> ids;
  for (int i = 0; i < side * side; ++i)
    ids.push_back(b.addParticle(particleAt(0.1 * (i % side), -0.1 * (i / side), 0.01)));
  int rods = 0;
  for (int i = 0; i < side * side; ++i) {
    if (i % side + 1 < side) {
      b.addConstraint(std::make_unique<RodConstraint>(ids[size_t(i)], ids[size_t(i + 1)], 0.1));
      ++rods;
    }
  }
  b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  System net = b.build();
  REQUIRE(rods > kMaxSchurRows);
  Solver solver(Integrator::backwardEuler);
  solver.doStep(net, 0.01);
  CHECK(solver.lastImplicitStep().solver == ImplicitSolver::cg);
  net.setImplicitSolver(ImplicitSolver::direct);
  try {
    solver.doStep(net, 0.01);
    FAIL("expected the direct solve to refuse");
  } catch (const ImplicitSolverError& e) {
    const std::string what = e.what();
    CHECK(what.find("implicit_solver: direct") != std::string::npos);
    CHECK(what.find(fmt::format("{} constraint rows", rods)) != std::string::npos);
    CHECK(what.find("use implicit_solver: cg or auto") != std::string::npos);
  }
}
