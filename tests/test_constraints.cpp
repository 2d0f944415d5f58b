// Constraints by numbers: Jacobians against finite differences, drift bounds over long runs,
// and singular systems that must stay finite.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>

#include "core/constraints/circular_wire_constraint.hpp"
#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

namespace {

// The integrators whose constraint drift is held to the same bounds: RK4 (the report's) and the
// three that project after each step.
constexpr Integrator kConstrainedIntegrators[] = {Integrator::rk4, Integrator::symplecticEuler, Integrator::verlet,
                                                  Integrator::backwardEuler};

// A state of three particles with arbitrary (fixed, so reproducible) positions and velocities.
Eigen::VectorXd sampleState(const StateLayout& layout) {
  Eigen::VectorXd y(layout.size());
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = std::sin(1.7 * double(i) + 0.3) * (1.0 + 0.1 * double(i));
  return y;
}

// Checks J = ∂C/∂q and J̇ = d/dt J along q̇ against central differences, and Ċ = J q̇.
void checkJacobians(const Constraint& c, const StateLayout& layout) {
  const double eps = 1e-6;
  const Eigen::VectorXd y = sampleState(layout);
  const ConstraintRow row = c.evaluate(StateView(layout, y));
  const Eigen::Index v = layout.velocityOffset();

  double jqdot = 0.0;
  for (int k = 0; k < row.count; ++k) {
    const int p = row.particle[size_t(k)];
    for (int d = 0; d < 2; ++d) {
      Eigen::VectorXd plus = y, minus = y;
      plus[2 * p + d] += eps;
      minus[2 * p + d] -= eps;
      const double fd = (c.evaluate(StateView(layout, plus)).C - c.evaluate(StateView(layout, minus)).C) / (2 * eps);
      CAPTURE(k);
      CAPTURE(d);
      CHECK(std::abs(row.J[size_t(k)][d] - fd) < 1e-6);
      jqdot += row.J[size_t(k)][d] * y[v + 2 * p + d];
    }
  }
  CHECK(std::abs(row.Cdot - jqdot) < 1e-12);

  // J̇: move positions along q̇ by ±eps and difference J.
  Eigen::VectorXd plus = y, minus = y;
  plus.head(v) += eps * y.segment(v, v);
  minus.head(v) -= eps * y.segment(v, v);
  const ConstraintRow rp = c.evaluate(StateView(layout, plus));
  const ConstraintRow rm = c.evaluate(StateView(layout, minus));
  for (int k = 0; k < row.count; ++k) {
    const Vec2 fd = (rp.J[size_t(k)] - rm.J[size_t(k)]) / (2 * eps);
    CHECK((row.Jdot[size_t(k)] - fd).norm() < 1e-6);
  }
}

}  // namespace

TEST_CASE("constraint Jacobians J and J-dot match finite differences of C") {
  const StateLayout layout{3, 0};
  SUBCASE("circular wire") { checkJacobians(CircularWireConstraint(1, Vec2(0.2, -0.4), 0.8), layout); }
  SUBCASE("rod") { checkJacobians(RodConstraint(0, 2, 1.3), layout); }
  SUBCASE("horizontal line") { checkJacobians(HorizontalLineConstraint(2, 0.5), layout); }
}

TEST_CASE("bead on a circular wire under gravity stays on the wire and goes through the bottom") {
  // Released at the height of the centre moving up at v0, the bead swings through the bottom,
  // h = r lower, where energy conservation (the wire's force is normal to the motion and does
  // no work) gives the speed v = √(v0² + 2 g h). Its amplitude is just over 90° (cos θ0 =
  // −v0²/2gr), its period 4 √(r/g) K(sin(θ0/2)) = 2.37 s: it passes the bottom at 0.64 s and every
  // 1.19 s after, eight times in 10 s (the ninth would be at 10.14 s).
  // The drift bound holds for every integrator that keeps constraints (the explicit ones through the
  // multipliers' feedback, the others through the projection after each step); the swing itself
  // is checked on RK4, whose energy error is small enough for the speed at the bottom.
  for (Integrator integrator : kConstrainedIntegrators) {
  CAPTURE(integratorName(integrator));
  const double r = 1.0, g = 9.81, v0 = 0.5, h = 0.01;
  SystemBuilder b;
  ParticleSpec bead = particleAt(r, 0.0);
  bead.vel = Vec2(0.0, v0);
  const int i = b.addParticle(bead);
  b.emplaceForce<GravityForce>(Vec2(0, -g));
  b.addConstraint(std::make_unique<CircularWireConstraint>(i, Vec2(0, 0), r));
  System sys = b.build();
  const double vBottom = std::sqrt(v0 * v0 + 2 * g * r);
  // The speed at the bottom is interpolated linearly between the steps either side of it. Near
  // the bottom v(φ) ≈ v_b − g r φ²/(2 v_b), and a step covers Δφ = v_b h / r, so the
  // interpolation alone is off by up to g r Δφ²/(8 v_b), relative g h²/(8 r) = 1.2e-4. On top of
  // that, 5e-5 for the integration: the speed error of a 1e-4 error in the bottom's kinetic
  // energy, the energy bound the rod pendulum below is held to.
  const double speedTolerance = g * h * h / (8 * r) + 5e-5;
  Solver solver(integrator);
  double worst = 0.0, worstSpeedError = 0.0;
  int passes = 0;
  Vec2 prevPos = sys.view().pos(i);
  double prevSpeed = v0;
  for (int s = 0; s < 1000; ++s) {  // 10 s
    solver.doStep(sys, h);
    worst = std::max(worst, sys.constraintError(sys.state()));
    const Vec2 pos = sys.view().pos(i);
    const double speed = sys.view().vel(i).norm();
    if (pos.y() < 0.0 && (prevPos.x() < 0.0) != (pos.x() < 0.0)) {
      const double w = prevPos.x() / (prevPos.x() - pos.x());  // where x = 0 falls in this step
      const double atBottom = (1.0 - w) * prevSpeed + w * speed;
      worstSpeedError = std::max(worstSpeedError, std::abs(atBottom - vBottom) / vBottom);
      ++passes;
    }
    prevPos = pos;
    prevSpeed = speed;
  }
  CAPTURE(worst);
  CAPTURE(passes);
  CAPTURE(vBottom);
  CAPTURE(worstSpeedError);
  CAPTURE(speedTolerance);
  CHECK(worst < 1e-4 * r);
  if (integrator == Integrator::rk4) {
    CHECK(passes == 8);
    CHECK(worstSpeedError < speedTolerance);
  }
  }
}

TEST_CASE("rod pendulum keeps its length and conserves energy") {
  for (Integrator integrator : kConstrainedIntegrators) {
  CAPTURE(integratorName(integrator));
  const double length = 1.0;
  SystemBuilder b;
  const int pivot = b.addParticle(particleAt(0, 0, 1.0, true));
  const int bob = b.addParticle(particleAt(length * std::sin(1.0), -length * std::cos(1.0)));
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  b.addConstraint(std::make_unique<RodConstraint>(pivot, bob, length));
  System sys = b.build();
  Solver solver(integrator);
  const double e0 = sys.energy().total();
  double worst = 0.0;
  for (int s = 0; s < 1000; ++s) {
    solver.doStep(sys, 0.01);
    worst = std::max(worst, sys.constraintError(sys.state()) / length);
  }
  CAPTURE(worst);
  CHECK(worst < 1e-4);
  // The constraint force does no work: energy stays within 1e-4 of its start (the drift feedback
  // only removes the integrator's small error). Verlet (multiplier forces, then projection) stays
  // as close; symplectic Euler and backward Euler keep the rod by projection alone, which only
  // takes energy out (measured: symplectic Euler −1.1 J of the 5.3 J swing in these 10 s,
  // first order in h), never puts it in.
  const double e1 = sys.energy().total();
  CAPTURE(e1 - e0);
  if (integrator == Integrator::rk4) CHECK(std::abs(e1 - e0) < 1e-4 * std::abs(e0));
  if (integrator == Integrator::verlet) CHECK(std::abs(e1 - e0) < 1e-3 * std::abs(e0));
  if (integrator == Integrator::symplecticEuler) {
    CHECK(e1 < e0);
    CHECK(e0 - e1 < 0.25 * std::abs(e0));
  }
  if (integrator == Integrator::backwardEuler) CHECK(e1 < e0);
  }
}

TEST_CASE("a 25-particle row on a horizontal line stays on the line") {
  for (Integrator integrator : kConstrainedIntegrators) {
  CAPTURE(integratorName(integrator));
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  std::vector<int> row;
  for (int c = 0; c < 25; ++c) row.push_back(b.addParticle(particleAt(0.08 * c, 1.0, 0.05)));
  // A hanging particle under every other one so the line carries real load.
  for (int c = 0; c < 25; c += 2) {
    const int hanging = b.addParticle(particleAt(0.08 * c + 0.05, 0.9, 0.05));
    springs.add({Endpoint::ofParticle(row[size_t(c)]), Endpoint::ofParticle(hanging), 0.1, 25.0, 0.2});
  }
  for (int c = 0; c + 1 < 25; ++c) {
    springs.add({Endpoint::ofParticle(row[size_t(c)]), Endpoint::ofParticle(row[size_t(c + 1)]), 0.08, 25.0, 0.2});
  }
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  for (int i : row) b.addConstraint(std::make_unique<HorizontalLineConstraint>(i, 1.0));
  System sys = b.build();
  Solver solver(integrator);
  double worst = 0.0;
  for (int s = 0; s < 1000; ++s) {
    solver.doStep(sys, 0.01);
    worst = std::max(worst, sys.constraintError(sys.state()));
  }
  CAPTURE(worst);
  CHECK(worst < 1e-4);
  }
}

TEST_CASE("singular constraint systems stay finite") {
  SUBCASE("a fixed particle on a line it is not on") {
    SystemBuilder b;
    const int fixed = b.addParticle(particleAt(0, 0.3, 1.0, true));
    const int free = b.addParticle(particleAt(1, 0));
    b.emplaceForce<GravityForce>(Vec2(0, -9.81));
    b.addConstraint(std::make_unique<HorizontalLineConstraint>(fixed, 0.0));
    b.addConstraint(std::make_unique<RodConstraint>(fixed, free, 1.1));
    System sys = b.build();
    Solver solver(Integrator::rk4);
    advance(sys, solver, 0.01, 500);
    CHECK(sys.state().allFinite());
    CHECK(sys.view().pos(fixed) == Vec2(0, 0.3));
    // The other constraint still holds.
    const double rodError = std::abs((sys.view().pos(free) - sys.view().pos(fixed)).norm() - 1.1);
    CHECK(rodError < 1e-4);
  }
  SUBCASE("two identical rods on the same pair") {
    SystemBuilder b;
    const int pivot = b.addParticle(particleAt(0, 0, 1.0, true));
    const int bob = b.addParticle(particleAt(1, 0));
    b.emplaceForce<GravityForce>(Vec2(0, -9.81));
    b.addConstraint(std::make_unique<RodConstraint>(pivot, bob, 1.0));
    b.addConstraint(std::make_unique<RodConstraint>(pivot, bob, 1.0));
    System sys = b.build();
    Solver solver(Integrator::rk4);
    advance(sys, solver, 0.01, 500);
    CHECK(sys.state().allFinite());
    CHECK(sys.constraintError(sys.state()) < 1e-4);
  }
  SUBCASE("two contradicting rods on the same pair") {
    SystemBuilder b;
    const int pivot = b.addParticle(particleAt(0, 0, 1.0, true));
    const int bob = b.addParticle(particleAt(1, 0));
    b.emplaceForce<GravityForce>(Vec2(0, -9.81));
    b.addConstraint(std::make_unique<RodConstraint>(pivot, bob, 1.0));
    b.addConstraint(std::make_unique<RodConstraint>(pivot, bob, 1.2));
    System sys = b.build();
    Solver solver(Integrator::rk4);
    advance(sys, solver, 0.01, 500);
    CHECK(sys.state().allFinite());
    // No length can satisfy both; it settles between them rather than flying off.
    const double len = sys.view().pos(bob).norm();
    CHECK(len > 0.95);
    CHECK(len < 1.25);
  }
}

namespace {

// An n × n net of rods 0.1 m long hanging from its fixed top row, gravity pulling it sideways
// too (so it is not in equilibrium): loops everywhere.
System rodNet(int n, const ConstraintSolverOptions& options = {}) {
  SystemBuilder b;
  b.setConstraintSolverOptions(options);
  auto id = [n](int r, int c) { return r * n + c; };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) b.addParticle(particleAt(0.1 * c, -0.1 * r, 0.1, r == 0));
  }
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (c + 1 < n && r > 0) b.addConstraint(std::make_unique<RodConstraint>(id(r, c), id(r, c + 1), 0.1));
      if (r + 1 < n) b.addConstraint(std::make_unique<RodConstraint>(id(r, c), id(r + 1, c), 0.1));
    }
  }
  b.emplaceForce<GravityForce>(Vec2(3.0, -9.81));
  return b.build();
}

// A straight chain of `rods` rods 0.01 m long from a fixed particle, lying horizontally.
System rodChain(int rods, const ConstraintSolverOptions& options = {}) {
  SystemBuilder b;
  b.setConstraintSolverOptions(options);
  int prev = b.addParticle(particleAt(0, 0, 1.0, true));
  for (int i = 1; i <= rods; ++i) {
    const int next = b.addParticle(particleAt(0.01 * i, 0.0, 0.01));
    b.addConstraint(std::make_unique<RodConstraint>(prev, next, 0.01));
    prev = next;
  }
  b.emplaceForce<GravityForce>(Vec2(0, -9.81));
  return b.build();
}

}  // namespace

TEST_CASE("constraint solver warm start cuts CG iterations") {
  // A net with loops: CG iterates (Jacobi preconditioned); the second evaluation starts from the
  // first λ.
  System sys = rodNet(12);
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);
  const int cold = sys.lastConstraintSolve().iterations;
  sys.derivEval(sys.state(), 0.0, dydt);
  const int warm = sys.lastConstraintSolve().iterations;
  CAPTURE(cold);
  CAPTURE(warm);
  CHECK(sys.lastConstraintSolve().preconditioner == Preconditioner::jacobi);
  CHECK(cold > 3);
  CHECK(warm < cold);
  CHECK(sys.lastConstraintSolve().relativeResidual < 1e-9);
}

TEST_CASE("a long chain of rods is solved in one preconditioned CG step") {
  // A chain's J W Jᵀ is tridiagonal, so its incomplete Cholesky factor is exact: one CG step
  // (Eigen counts it as 0 iterations). Diagonal (Jacobi) preconditioning needs one per rod.
  System sys = rodChain(1000);
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);
  CHECK(sys.lastConstraintSolve().rows == 1000);
  CHECK(sys.lastConstraintSolve().preconditioner == Preconditioner::incompleteCholesky);
  CHECK(sys.lastConstraintSolve().iterations <= 1);
  CHECK(sys.lastConstraintSolve().relativeResidual < 1e-9);

  ConstraintSolverOptions jacobi;
  jacobi.preconditioner = Preconditioner::jacobi;
  System plain = rodChain(1000, jacobi);
  Eigen::VectorXd dydtJacobi;
  plain.derivEval(plain.state(), 0.0, dydtJacobi);
  CHECK(plain.lastConstraintSolve().iterations > 900);
  CHECK((dydtJacobi - dydt).norm() <= 1e-7 * dydt.norm());
}

TEST_CASE("both preconditioners give the same constraint forces on a net with loops") {
  // The net has loops, so the automatic choice is Jacobi; forcing incomplete Cholesky must
  // give the same accelerations (it is only slower there, bench/README.md).
  ConstraintSolverOptions options;
  options.preconditioner = Preconditioner::incompleteCholesky;
  System withIc = rodNet(10, options), automatic = rodNet(10);
  Eigen::VectorXd ic, jacobi;
  withIc.derivEval(withIc.state(), 0.0, ic);
  automatic.derivEval(automatic.state(), 0.0, jacobi);
  CHECK(withIc.lastConstraintSolve().preconditioner == Preconditioner::incompleteCholesky);
  CHECK(automatic.lastConstraintSolve().preconditioner == Preconditioner::jacobi);
  CHECK(withIc.lastConstraintSolve().relativeResidual < 1e-9);
  CHECK(automatic.lastConstraintSolve().relativeResidual < 1e-9);
  CHECK(ic.norm() > 1.0);  // swinging sideways: accelerations of order g
  CHECK((jacobi - ic).norm() <= 1e-7 * ic.norm());
}

TEST_CASE("the automatic preconditioner: incomplete Cholesky for loop-free structures, else Jacobi") {
  auto chosen = [](const std::vector<std::pair<int, int>>& rods, const std::vector<int>& beads) {
    // Particle 0 is fixed, 1 … 4 move; beads ride circular wires.
    SystemBuilder b;
    for (int i = 0; i < 5; ++i) b.addParticle(particleAt(0.3 * i, 0.2 * (i % 2), 0.1, i == 0));
    for (auto [p, q] : rods) {
      const double length = (Vec2(0.3 * p, 0.2 * (p % 2)) - Vec2(0.3 * q, 0.2 * (q % 2))).norm();
      b.addConstraint(std::make_unique<RodConstraint>(p, q, length));
    }
    for (int p : beads) {
      const Vec2 at(0.3 * p, 0.2 * (p % 2));
      b.addConstraint(std::make_unique<CircularWireConstraint>(p, at + Vec2(0, 0.5), 0.5));
    }
    b.emplaceForce<GravityForce>(Vec2(1.0, -9.81));
    System sys = b.build();
    Eigen::VectorXd dydt;
    sys.derivEval(sys.state(), 0.0, dydt);
    CHECK(sys.lastConstraintSolve().relativeResidual < 1e-9);
    return sys.lastConstraintSolve().preconditioner;
  };
  const auto ic = Preconditioner::incompleteCholesky, jacobi = Preconditioner::jacobi;
  CHECK(chosen({{0, 1}, {1, 2}, {2, 3}, {3, 4}}, {}) == ic);          // a chain
  CHECK(chosen({{1, 2}, {1, 3}, {1, 4}}, {2, 3, 4}) == ic);           // a star, beads on its tips
  CHECK(chosen({{0, 1}, {0, 2}, {1, 2}}, {}) == ic);                  // a triangle closed by the fixed point
  CHECK(chosen({{1, 2}, {2, 3}, {3, 1}}, {}) == jacobi);              // a triangle of moving particles
  CHECK(chosen({{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 1}}, {}) == jacobi);  // a chain ending in a loop
  CHECK(chosen({{0, 1}, {0, 2}}, {1, 2, 3}) == jacobi);  // no row joins two moving particles: diagonal
}

TEST_CASE("rows that share no moving particle are solved exactly, one division per row") {
  // Beads on wires, each on a particle of its own, a rod between two particles no other row
  // touches, a rail, and two rods from one fixed particle: J W Jᵀ is diagonal, so the solve divides (ConstraintSolver's diagonal
  // path). The constraint forces must give every row the acceleration its feedback asks for,
  // C̈ = −ks C − kd Ċ (docs/physics.md §3), to rounding and the 1e-10 regularisation.
  SystemBuilder b;
  b.addParticle(particleAt(0, 0, 1.0, true));  // fixed: a row on it and a moving particle stays diagonal
  for (int i = 1; i <= 3; ++i) {
    const int p = b.addParticle(particleAt(0.3 * i, 0.1 * i, 0.5 + 0.1 * i));
    b.addConstraint(std::make_unique<CircularWireConstraint>(p, Vec2(0.3 * i, 0.6), 0.45 + 0.02 * i));
  }
  const int q = b.addParticle(particleAt(1.5, 0.2, 0.3)), r = b.addParticle(particleAt(1.9, 0.5, 0.7));
  b.addConstraint(std::make_unique<RodConstraint>(q, r, 0.48));
  const int s = b.addParticle(particleAt(2.4, 1.0, 0.2));
  b.addConstraint(std::make_unique<HorizontalLineConstraint>(s, 1.01));
  const int t = b.addParticle(particleAt(-0.5, 0.0, 0.4));
  b.addConstraint(std::make_unique<RodConstraint>(0, t, 0.51));
  const int v = b.addParticle(particleAt(-0.2, -0.6, 0.4));
  b.addConstraint(std::make_unique<RodConstraint>(0, v, 0.63));
  b.emplaceForce<GravityForce>(Vec2(0.7, -9.81));
  System sys = b.build();
  // Moving, and off the constraints, so that C, Ċ and J̇ all count (all but the fixed particle 0).
  const Eigen::Index velocity = sys.layout().velocityOffset();
  for (Eigen::Index i = 2; i < sys.state().size(); ++i) {
    if (i != velocity && i != velocity + 1) sys.state()[i] += 0.05 * std::sin(3.1 * double(i));
  }
  Eigen::VectorXd dydt;
  sys.derivEval(sys.state(), 0.0, dydt);
  CHECK(sys.lastConstraintSolve().rows == 7);
  CHECK(sys.lastConstraintSolve().iterations == 1);
  CHECK(sys.lastConstraintSolve().preconditioner == Preconditioner::jacobi);

  const StateLayout& layout = sys.layout();
  const StateView view(layout, sys.state());
  for (const auto& c : sys.constraints()) {
    const ConstraintRow row = c->evaluate(view);
    double cddot = 0.0;
    for (int k = 0; k < row.count; ++k) {
      const int p = row.particle[size_t(k)];
      const Vec2 a(dydt[layout.velocityOffset() + 2 * p], dydt[layout.velocityOffset() + 2 * p + 1]);
      cddot += row.J[size_t(k)].dot(a) + row.Jdot[size_t(k)].dot(view.vel(p));
    }
    const double wanted = -c->feedback().ks * row.C - c->feedback().kd * row.Cdot;
    CAPTURE(row.C);
    CHECK(std::abs(cddot - wanted) <= 1e-8 * (1.0 + std::abs(wanted)));
  }

  // One more row on a moving particle couples two rows: the CG path, to its tolerance.
  SystemBuilder coupled;
  const int u = coupled.addParticle(particleAt(0.3, 0.1, 0.6)), w = coupled.addParticle(particleAt(0.7, 0.1, 0.6));
  coupled.addConstraint(std::make_unique<CircularWireConstraint>(u, Vec2(0.3, 0.6), 0.5));
  coupled.addConstraint(std::make_unique<RodConstraint>(u, w, 0.4));
  coupled.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  System two = coupled.build();
  two.derivEval(two.state(), 0.0, dydt);
  CHECK(two.lastConstraintSolve().relativeResidual < 1e-9);
  CHECK(two.lastConstraintSolve().preconditioner == Preconditioner::incompleteCholesky);
}
