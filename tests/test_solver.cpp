// The solver's guarantees: explosions become errors, runs are bit-for-bit reproducible, and the
// builder rejects references to objects that do not exist.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "core/grid.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

TEST_CASE("an absurd dt on a stiff spring gives the explosion error, not NaNs") {
  for (Integrator integrator : allIntegrators()) {
    // Backward Euler and BDF2 are stable at any step on a spring (test_integrators.cpp checks it).
    if (isImplicit(integrator)) continue;
    CAPTURE(integratorName(integrator));
    System sys = harmonicOscillator(1e6, 0.1);  // ω = 1000 rad/s
    Solver solver(integrator);
    const double dt = 0.5;  // ω dt = 500
    bool thrown = false;
    try {
      advance(sys, solver, dt, 1000);
    } catch (const SimulationError& e) {
      thrown = true;
      const std::string what = e.what();
      CAPTURE(what);
      CHECK(e.step() >= 1);
      CHECK(e.step() < 20);  // caught within a few steps of the growth starting
      CHECK(e.dt() == dt);
      CHECK(e.integrator() == integrator);
      CHECK(what.find("step " + std::to_string(e.step())) != std::string::npos);
      CHECK(what.find(std::string(integratorName(integrator))) != std::string::npos);
      CHECK(what.find("dt = 0.5") != std::string::npos);
      CHECK(what.find("smaller time step") != std::string::npos);
    }
    CHECK(thrown);
    // The system is left at its last good state: finite, and time not advanced past it.
    CHECK(sys.state().allFinite());
    CHECK(sys.time() == doctest::Approx(dt * double(solver.steps())));
  }
}

namespace {

// Global order of each integrator, from the formulas atop integrators.hpp and integrators/*.hpp.
// A new integrator is a compile error here (-Wswitch) until its order is stated.
int globalOrder(Integrator integrator) {
  switch (integrator) {
    case Integrator::euler:
    case Integrator::symplecticEuler:
    case Integrator::backwardEuler: return 1;
    case Integrator::midpoint:
    case Integrator::verlet:
    case Integrator::bdf2: return 2;
    case Integrator::rk4: return 4;
  }
  return 0;
}

}  // namespace

TEST_CASE("10 s of free fall follow the exact parabola to each integrator's order, without tripping the guard") {
  // Kinetic energy grows to ~500× the scale, far below the guard's 1e6 factor. The exact answer:
  //   x = v0x t,   y = v0y t − ½ g t²,   vy = v0y − g t.
  // Every integrator's velocity update is exact for a constant acceleration (v₁ = v₀ + h a), so vy
  // is exact up to round-off. For y, a method's local error is its first Taylor term it misses:
  // second and higher order ones miss h³ y‴/6 or beyond, and y‴ = 0: only round-off remains. A
  // first-order one misses ±h² y″/2 = ∓½ g h² per step (explicit Euler moves with v₀, symplectic
  // and backward Euler with v₁), and nothing further since y‴ = 0: over t / h steps exactly
  // |Δy| = ½ g t h = 0.4905 m here. Round-off: 1000 steps of ε·|y| ≈ 2.2e-16 · 490 m ≈ 1e-10 m; 1e-9 allows 10×.
  constexpr double g = 9.81, h = 0.01, v0x = 3.0, v0y = 4.0, roundOff = 1e-9;
  constexpr long steps = 1000;
  for (Integrator integrator : allIntegrators()) {
    CAPTURE(integratorName(integrator));
    SystemBuilder b;
    ParticleSpec p = particleAt(0, 0);
    p.vel = Vec2(v0x, v0y);
    b.addParticle(p);
    b.emplaceForce<GravityForce>(Vec2(0, -g));
    System sys = b.build();
    Solver solver(integrator);
    REQUIRE_NOTHROW(advance(sys, solver, h, steps));
    const double t = sys.time();
    REQUIRE(t == doctest::Approx(10.0).epsilon(1e-12));
    // BDF2 is exact on a quadratic too, but its backward Euler start leaves e₁ = −½ g h², which its
    // recurrence e_{n+1} = 4/3 e_n − 1/3 e_{n−1} carries to e_n = −¾ g h² (1 − 3⁻ⁿ): O(h²), not growing.
    const double expectedYError = integrator == Integrator::bdf2 ? 0.75 * g * h * h
                                  : globalOrder(integrator) == 1 ? 0.5 * g * t * h
                                                                 : 0.0;
    const double yError = sys.view().pos(0).y() - (v0y * t - 0.5 * g * t * t);
    CAPTURE(yError);
    CHECK(std::abs(std::abs(yError) - expectedYError) < roundOff);
    CHECK(std::abs(sys.view().pos(0).x() - v0x * t) < roundOff);
    CHECK(std::abs(sys.view().vel(0).x() - v0x) < roundOff);
    CHECK(std::abs(sys.view().vel(0).y() - (v0y - g * t)) < roundOff);
  }
}

namespace {

// The report's cloth at 10 × 10, its top row (reportCloth puts it at y = 1) sliding on a rail as in
// scenarios/cloth.yaml, and a rod from each top particle to the one below it.
constexpr double kRailHeight = 1.0;

System clothWithRail() {
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  const GridIndices g = addGrid(b, springs, reportCloth(10, 0.1));
  for (int c = 0; c < 10; ++c) {
    b.addConstraint(std::make_unique<HorizontalLineConstraint>(g.at(0, c), kRailHeight));
    b.addConstraint(std::make_unique<RodConstraint>(g.at(0, c), g.at(1, c), 0.1));
  }
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  return b.build();
}

}  // namespace

TEST_CASE("two identical runs are bit-for-bit identical") {
  for (Integrator integrator : allIntegrators()) {
    CAPTURE(integratorName(integrator));
    System a = clothWithRail(), b = clothWithRail();
    Solver sa(integrator), sb(integrator);
    // The rail holds the top row up: nothing else does (no particle is fixed), so without it the
    // cloth falls ½ g t² = 20 m in these 2 s. 1e-4 m is the drift bound of the constraint tests
    // (test_constraints.cpp). Explicit Euler's drift grows with its energy error: its bound is looser.
    double worstRail = 0.0;
    for (int s = 0; s < 400; ++s) {
      sa.doStep(a, 0.005);
      // Particles 0 … 9 are the top row: the grid is the first thing the builder was given.
      for (int c = 0; c < 10; ++c) worstRail = std::max(worstRail, std::abs(a.view().pos(c).y() - kRailHeight));
    }
    advance(b, sb, 0.005, 400);
    CAPTURE(worstRail);
    CHECK(worstRail < (integrator == Integrator::euler ? 1e-2 : 1e-4));
    REQUIRE(a.state().size() == b.state().size());
    CHECK(std::memcmp(a.state().data(), b.state().data(), sizeof(double) * size_t(a.state().size())) == 0);
    CHECK(a.time() == b.time());
    // …and the run did something.
    CHECK((a.state() - clothWithRail().state()).norm() > 0.1);
  }
}

TEST_CASE("the builder rejects bad masses, sizes and references") {
  {
    SystemBuilder b;
    b.addParticle(particleAt(0, 0, 0.0));
    CHECK_THROWS_AS(b.build(), std::invalid_argument);
  }
  {
    SystemBuilder b;
    RigidBodySpec body;
    body.size = Vec2(0, 1);
    b.addRigidBody(body);
    CHECK_THROWS_AS(b.build(), std::invalid_argument);
  }
  {
    SystemBuilder b;
    b.addParticle(particleAt(0, 0));
    b.addConstraint(std::make_unique<RodConstraint>(0, 3, 1.0));
    CHECK_THROWS_WITH_AS(b.build(), "rod constraint: particle 3 does not exist", std::invalid_argument);
  }
  {
    SystemBuilder b;
    b.addParticle(particleAt(0, 0));
    b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(0), Endpoint::ofBody(0), 1, 1, 0});
    CHECK_THROWS_WITH_AS(b.build(), "spring: body 0 does not exist", std::invalid_argument);
  }
}

TEST_CASE("fixed particles never move") {
  SystemBuilder b;
  ParticleSpec p = particleAt(1, 2, 1.0, true);
  p.vel = Vec2(5, 5);  // ignored for a fixed particle
  b.addParticle(p);
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  System sys = b.build();
  Solver solver(Integrator::euler);
  advance(sys, solver, 0.1, 10);
  CHECK(sys.view().pos(0) == Vec2(1, 2));
  CHECK(sys.view().vel(0) == Vec2(0, 0));
}

TEST_CASE("the solver owns time: t = t0 + k·dt, not a rounding sum, and a new dt starts a new run") {
  SystemBuilder b;
  b.addParticle(particleAt(0, 0));
  System sys = b.build();
  sys.setTime(0.25);
  Solver solver(Integrator::euler);
  double summed = 0.25;
  for (int k = 1; k <= 1000; ++k) {
    solver.doStep(sys, 0.01);
    summed += 0.01;
    REQUIRE(sys.time() == 0.25 + double(k) * 0.01);
  }
  CHECK(sys.time() == 10.25);
  CHECK(summed != 10.25);  // what adding dt up would have given: the reason for k·dt
  solver.doStep(sys, 0.1);  // another dt: a new run from 10.25
  CHECK(sys.time() == 10.25 + 0.1);
  sys.setTime(1.0);  // moved from outside: the next run starts there
  solver.doStep(sys, 0.1);
  CHECK(sys.time() == 1.0 + 0.1);
  CHECK(solver.steps() == 1002);

  // The Stepper reaches frame times through the same solver.
  sys.setTime(0.0);
  Stepper stepper(sys, Integrator::rk4, 0.01);
  stepper.advanceTo(1.0 / 3.0);
  CHECK(stepper.steps() == 33);
  CHECK(sys.time() == 33 * 0.01);
  stepper.advanceTo(0.7);  // 0.7 / 0.01 is 69.99999…: within 1e-9 of step 70, so reached
  CHECK(stepper.steps() == 70);
}

TEST_CASE("the guard's one pass: kinetic energy to the bit, and any non-finite entry found") {
  // System::checkState, which the explosion guard runs after every step: 10,000 particles (3
  // chunks of its pass), one of them fixed and moving (its energy does not count), on 1 and 3
  // threads.
  for (int threads : {1, 3}) {
    CAPTURE(threads);
    SystemBuilder b;
    for (int i = 0; i < 10'000; ++i) {
      ParticleSpec p = particleAt(0.01 * (i % 100), 0.01 * (i / 100), 0.001 * (1 + i % 7), i == 42);
      p.vel = Vec2(std::sin(0.37 * i), std::cos(0.11 * i));
      b.addParticle(p);
    }
    System sys = b.build();
    sys.setThreads(threads);
    System::StateCheckScratch scratch;
    const System::StateCheck check = sys.checkState(sys.state(), scratch);
    CHECK(check.finite);
    const double expected = sys.kineticEnergy(sys.state());
    CHECK(std::memcmp(&check.kinetic, &expected, sizeof(double)) == 0);
    CHECK(check.kinetic > 1.0);
    const Eigen::Index velocity = sys.layout().velocityOffset();
    for (Eigen::Index at : {Eigen::Index(0), Eigen::Index(9'999 * 2 + 1), velocity + 8'193 * 2, sys.state().size() - 1}) {
      for (double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
        CAPTURE(at);
        Eigen::VectorXd y = sys.state();
        y[at] = bad;
        CHECK_FALSE(sys.checkState(y, scratch).finite);
      }
    }
  }
}
