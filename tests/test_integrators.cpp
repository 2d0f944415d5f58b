// Integrators by numbers: convergence orders, exactness on free fall, energy behaviour.
#include <doctest/doctest.h>

#include <Eigen/LU>
#include <cmath>
#include <utility>
#include <vector>

#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "core/forces/drag_force.hpp"
#include "core/integrators/backward_euler.hpp"
#include "core/integrators/bdf2.hpp"
#include "core/integrators/explicit_euler.hpp"
#include "core/integrators/midpoint.hpp"
#include "core/integrators/rk4.hpp"
#include "core/integrators/symplectic_euler.hpp"
#include "core/integrators/verlet.hpp"
#include "sanitizer.hpp"
#include "skip.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

namespace {

// Global error of x at t = 2 for the oscillator x(t) = 1 + 0.5 cos(2t) (k = 4, m = 1).
double oscillatorError(Integrator integrator, double h) {
  System sys = harmonicOscillator(4.0, 0.5);
  Solver solver(integrator);
  const long steps = std::lround(2.0 / h);
  advance(sys, solver, h, steps);
  const double exact = 1.0 + 0.5 * std::cos(2.0 * 2.0);
  return std::abs(sys.view().pos(1).x() - exact);
}

// A vertical chain of `links` stiff springs (k = 2500 N/m, 2 g particles, 8 cm apart) whose top
// particle is fixed, or slides on a horizontal rail.
System hangingChain(bool rail, int links = 24) {
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  int previous = b.addParticle(particleAt(0.0, 0.0, 0.002, !rail));
  if (rail) b.addConstraint(std::make_unique<HorizontalLineConstraint>(previous, 0.0));
  for (int i = 1; i <= links; ++i) {
    const int p = b.addParticle(particleAt(0.0, -0.08 * i, 0.002));
    springs.add({Endpoint::ofParticle(previous), Endpoint::ofParticle(p), 0.08, 2500.0, 0.01});
    previous = p;
  }
  b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  return b.build();
}

}  // namespace

TEST_CASE("integrators are chosen by name") {
  CHECK(integratorFromName("euler") == Integrator::euler);
  CHECK(integratorFromName("midpoint") == Integrator::midpoint);
  CHECK(integratorFromName("rk4") == Integrator::rk4);
  CHECK(integratorFromName("symplectic_euler") == Integrator::symplecticEuler);
  CHECK(integratorFromName("verlet") == Integrator::verlet);
  CHECK(integratorFromName("backward_euler") == Integrator::backwardEuler);
  CHECK_FALSE(integratorFromName("RK4").has_value());
  CHECK_FALSE(integratorFromName("leapfrog").has_value());
  // Every enum value has its row in the registry, once.
  CHECK(allIntegrators().size() == 7);
  for (Integrator i : allIntegrators()) {
    CHECK(integratorFromName(integratorName(i)) == i);
    CHECK_FALSE(integratorSummary(i).empty());
  }
  CHECK(derivEvalsPerStep(Integrator::euler) == 1);
  CHECK(derivEvalsPerStep(Integrator::midpoint) == 2);
  CHECK(derivEvalsPerStep(Integrator::rk4) == 4);
  CHECK(derivEvalsPerStep(Integrator::symplecticEuler) == 1);
  CHECK(derivEvalsPerStep(Integrator::verlet) == 1);
  CHECK(derivEvalsPerStep(Integrator::backwardEuler) == 1);
  CHECK_FALSE(projectsConstraints(Integrator::rk4));
  CHECK(projectsConstraints(Integrator::verlet));
}

TEST_CASE("each registry row makes its integrator's own state, which steps as the solver does") {
  for (Integrator integrator : allIntegrators()) {
    CAPTURE(integratorName(integrator));
    const std::unique_ptr<IntegratorState> state = makeIntegratorState(integrator);
    REQUIRE(state != nullptr);
    CHECK((state->implicitStep() != nullptr) == isImplicit(integrator));
    // Three steps of the state on its own give the solver's bits (an oscillator without
    // constraints: the solver adds no projection).
    System bySolver = harmonicOscillator(4.0, 0.5), byState = harmonicOscillator(4.0, 0.5);
    Solver solver(integrator);
    for (int i = 0; i < 3; ++i) {
      solver.doStep(bySolver, 0.01);
      state->step(byState, byState.state(), byState.time(), 0.01);
      byState.setTime(bySolver.time());
    }
    CHECK(byState.state() == bySolver.state());
  }
  // Two states of one integrator share nothing: a step of one leaves the other's history alone.
  const std::unique_ptr<IntegratorState> first = makeIntegratorState(Integrator::bdf2);
  const std::unique_ptr<IntegratorState> second = makeIntegratorState(Integrator::bdf2);
  System a = harmonicOscillator(4.0, 0.5), b = harmonicOscillator(4.0, 0.5);
  first->step(a, a.state(), 0.0, 0.01);
  first->step(a, a.state(), 0.01, 0.01);
  second->step(b, b.state(), 0.0, 0.01);  // a first step: backward Euler's, as first's was
  System c = harmonicOscillator(4.0, 0.5);
  BackwardEulerState backwardEuler;
  backwardEuler.step(c, c.state(), 0.0, 0.01);
  CHECK(b.state() == c.state());
}

TEST_CASE("BDF2's history: kept while the steps continue, dropped at a new h, a time jump or a new state size") {
  Bdf2State state;
  System sys = harmonicOscillator(4.0, 0.5);
  const double h = 0.01;
  CHECK_FALSE(state.continues(sys.state(), 0.0, h));  // nothing yet: the first step is backward Euler's
  state.step(sys, sys.state(), 0.0, h);
  CHECK(state.continues(sys.state(), h, h));
  CHECK(state.continues(sys.state(), h * (1.0 + 1e-12), h));  // the Solver's t, rounded
  CHECK_FALSE(state.continues(sys.state(), h, h / 2));        // a new h
  CHECK_FALSE(state.continues(sys.state(), 5.0, h));          // a jump in time
  CHECK_FALSE(state.continues(sys.state(), 0.0, h));          // a rewind
  const Eigen::VectorXd longer = Eigen::VectorXd::Zero(sys.state().size() + 4);
  CHECK_FALSE(state.continues(longer, h, h));  // another scene's state
  state.step(sys, sys.state(), h, h);
  CHECK(state.continues(sys.state(), 2 * h, h));
}

TEST_CASE("convergence order on an undamped harmonic oscillator") {
  // Halving h divides the global error by 2^order. Step sizes are chosen per method so that the
  // error is in the asymptotic regime (ωh ≤ 0.1) and well above round-off (RK4's smallest error
  // here is ~1e-9). Tolerance ±15 % on the ratio: room for the error's higher-order terms at these
  // steps.
  struct Case {
    Integrator integrator;
    double h;
    double expectedRatio;
  };
  for (const Case& c :
       {Case{Integrator::euler, 1e-3, 2.0}, Case{Integrator::midpoint, 1e-2, 4.0}, Case{Integrator::rk4, 5e-2, 16.0},
        Case{Integrator::symplecticEuler, 1e-3, 2.0}, Case{Integrator::verlet, 1e-2, 4.0},
        Case{Integrator::backwardEuler, 1e-3, 2.0}, Case{Integrator::bdf2, 1e-2, 4.0}}) {
    CAPTURE(integratorName(c.integrator));
    const double coarse = oscillatorError(c.integrator, c.h);
    const double fine = oscillatorError(c.integrator, c.h / 2);
    const double ratio = coarse / fine;
    CAPTURE(coarse);
    CAPTURE(fine);
    CHECK(ratio == doctest::Approx(c.expectedRatio).epsilon(0.15));
  }
}

TEST_CASE("free fall: midpoint and RK4 are exact for constant acceleration") {
  // y(t) = y0 + v0 t + ½ g t² is quadratic in t: both methods integrate it exactly, so only
  // round-off remains (1e-12 over 200 steps).
  for (Integrator integrator : {Integrator::midpoint, Integrator::rk4}) {
    CAPTURE(integratorName(integrator));
    SystemBuilder b;
    ParticleSpec p = particleAt(0.3, 2.0);
    p.vel = Vec2(0.7, 1.5);
    b.addParticle(p);
    b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
    System sys = b.build();
    Solver solver(integrator);
    const double h = 0.01;
    advance(sys, solver, h, 200);
    const double t = sys.time();
    CHECK(t == doctest::Approx(2.0).epsilon(1e-12));
    CHECK(std::abs(sys.view().pos(0).x() - (0.3 + 0.7 * t)) < 1e-12);
    CHECK(std::abs(sys.view().pos(0).y() - (2.0 + 1.5 * t - 0.5 * 9.81 * t * t)) < 1e-12);
    CHECK(std::abs(sys.view().vel(0).y() - (1.5 - 9.81 * t)) < 1e-12);
  }
}

namespace {

System twoParticleSpring() {
  SystemBuilder b;
  ParticleSpec a = particleAt(-0.6, 0.0);
  a.vel = Vec2(0.0, 0.3);
  ParticleSpec c = particleAt(0.6, 0.0);
  c.vel = Vec2(0.0, -0.3);
  const int ia = b.addParticle(a), ic = b.addParticle(c);
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(ia), Endpoint::ofParticle(ic), 1.0, 10.0, 0.0});
  return b.build();
}

}  // namespace

TEST_CASE("undamped two-particle spring: RK4 conserves energy, explicit Euler gains it") {
  {
    System sys = twoParticleSpring();
    Solver solver(Integrator::rk4);
    const double e0 = sys.energy().total();
    double worst = 0.0;
    for (int i = 0; i < 10000; ++i) {  // h = 0.01, 100 s
      solver.doStep(sys, 0.01);
      worst = std::max(worst, std::abs(sys.energy().total() - e0) / e0);
    }
    CAPTURE(e0);
    CHECK(worst < 1e-5);
  }
  {
    System sys = twoParticleSpring();
    Solver solver(Integrator::euler);
    const double e0 = sys.energy().total();
    advance(sys, solver, 0.01, 1000);  // 10 s
    // Euler's amplification factor |1 + iωh| > 1 makes the energy grow every step.
    CHECK(sys.energy().total() > 1.1 * e0);
  }
}

TEST_CASE("integrators on a plain ODE: y' = -y") {
  const DerivFn f = [](const Eigen::VectorXd& y, double, Eigen::VectorXd& dydt) { dydt = -y; };
  IntegratorScratch w;
  const double h = 0.1;
  // One step of each method reproduces the Taylor series of e^{-h} up to its order.
  Eigen::VectorXd y = Eigen::VectorXd::Ones(1);
  integrateEuler(f, y, 0.0, h, w);
  CHECK(y[0] == doctest::Approx(1 - h).epsilon(1e-15));
  y = Eigen::VectorXd::Ones(1);
  integrateMidpoint(f, y, 0.0, h, w);
  CHECK(y[0] == doctest::Approx(1 - h + h * h / 2).epsilon(1e-15));
  y = Eigen::VectorXd::Ones(1);
  integrateRk4(f, y, 0.0, h, w);
  CHECK(y[0] == doctest::Approx(1 - h + h * h / 2 - h * h * h / 6 + h * h * h * h / 24).epsilon(1e-15));
}

namespace {

// A damped, driven 2-D problem with every velocity-dependent force: two free particles joined by a
// damped spring, one on a damped spring to a fixed anchor, under gravity and drag. Its x is
// compared with RK4 at a step far below the tested ones.
System dampedPair() {
  SystemBuilder b;
  const int anchor = b.addParticle(particleAt(0, 0, 1.0, true));
  ParticleSpec p1 = particleAt(0.9, -0.4, 0.7);
  p1.vel = Vec2(0.3, 0.8);
  const int i1 = b.addParticle(p1);
  const int i2 = b.addParticle(particleAt(1.6, -1.1, 1.3));
  auto& springs = b.emplaceForce<DampedSpringForce>();
  springs.add({Endpoint::ofParticle(anchor), Endpoint::ofParticle(i1), 0.8, 12.0, 0.4});
  springs.add({Endpoint::ofParticle(i1), Endpoint::ofParticle(i2), 0.7, 20.0, 0.3});
  b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  b.emplaceForce<DragForce>(0.15);
  return b.build();
}

Eigen::VectorXd dampedPairAt(Integrator integrator, double h, double duration) {
  System sys = dampedPair();
  Solver solver(integrator);
  advance(sys, solver, h, std::lround(duration / h));
  return sys.state();
}

}  // namespace

TEST_CASE("convergence orders with damping and drag (velocity-dependent forces)") {
  // Verlet evaluates a₁ at a predicted velocity and backward Euler and BDF2 linearise the damping:
  // they keep their orders (2, 1 and 2) when forces depend on v. Errors against RK4 at h = 1e-4.
  const double duration = 1.0;
  const Eigen::VectorXd reference = dampedPairAt(Integrator::rk4, 1e-4, duration);
  struct Case {
    Integrator integrator;
    double h;
    double expectedRatio;
  };
  for (const Case& c : {Case{Integrator::symplecticEuler, 2e-3, 2.0}, Case{Integrator::verlet, 1e-2, 4.0},
                        Case{Integrator::backwardEuler, 2e-3, 2.0}, Case{Integrator::bdf2, 1e-2, 4.0}}) {
    CAPTURE(integratorName(c.integrator));
    const double coarse = (dampedPairAt(c.integrator, c.h, duration) - reference).norm();
    const double fine = (dampedPairAt(c.integrator, c.h / 2, duration) - reference).norm();
    CAPTURE(coarse);
    CAPTURE(fine);
    CHECK(coarse / fine == doctest::Approx(c.expectedRatio).epsilon(0.15));
  }
}

namespace {

struct EnergyHistory {
  double worst = 0.0;      // largest |E − E₀| / E₀
  double firstMean = 0.0;  // mean of (E − E₀)/E₀ over the first tenth of the run
  double lastMean = 0.0;   // … and over the last tenth
  bool monotoneDecreasing = true;
};

// The undamped oscillator of oscillatorError (ω = 2, period π) over `periods` periods at h.
EnergyHistory oscillatorEnergy(Integrator integrator, double h, double periods) {
  System sys = harmonicOscillator(4.0, 0.5);
  Solver solver(integrator);
  const long steps = std::lround(periods * M_PI / h);
  const double e0 = sys.energy().total();
  EnergyHistory out;
  double previous = e0;
  const long tenth = steps / 10;
  for (long i = 0; i < steps; ++i) {
    solver.doStep(sys, h);
    const double e = sys.energy().total();
    const double rel = (e - e0) / e0;
    out.worst = std::max(out.worst, std::abs(rel));
    if (i < tenth) out.firstMean += rel / double(tenth);
    if (i >= steps - tenth) out.lastMean += rel / double(tenth);
    if (!(e < previous)) out.monotoneDecreasing = false;
    previous = e;
  }
  return out;
}

}  // namespace

TEST_CASE("undamped oscillator over 10^4 periods: symplectic Euler and Verlet keep the energy bounded") {
  // One particle stepped 10^6 times by three integrators: 13 s under ASan + UBSan for no code that
  // the shorter runs here do not reach there.
  if (particles::test::kUnderAddressSanitizer)
    return particles::test::skipTest("energy over 10^4 periods: checked in the plain build, not under ASan");
  // h ω = 0.2. A symplectic map conserves a modified energy within O(h^p) of the true one, so the
  // error oscillates with the period and does not drift: its mean over the last thousand periods
  // equals its mean over the first. On this linear oscillator the conserved quantities are exact
  // quadratics: v² + ω²x² − h ω² x v for symplectic Euler, whose energy error then peaks at
  // (hω/2) / (1 − hω/2) = 1/9, and v² / (1 − (hω)²/4) + ω²x² for Verlet, peaking at
  // ((hω)²/4) / (1 − (hω)²/4) = 0.0101.
  const double h = 0.1, periods = 1e4;
  for (const auto& [integrator, peak] : {std::pair{Integrator::symplecticEuler, 1.0 / 9.0},
                                         std::pair{Integrator::verlet, 0.01 / 0.99}}) {
    CAPTURE(integratorName(integrator));
    const EnergyHistory e = oscillatorEnergy(integrator, h, periods);
    CAPTURE(e.worst);
    CAPTURE(e.firstMean);
    CAPTURE(e.lastMean);
    CHECK(e.worst == doctest::Approx(peak).epsilon(1e-3));
    CHECK(std::abs(e.lastMean - e.firstMean) < 1e-3 * e.worst);
  }
  {
    // For contrast, RK4 at the same step is not symplectic: its energy drifts down, steadily
    // (linearly in time, so the last tenth's mean is about 19 times the first's).
    const EnergyHistory e = oscillatorEnergy(Integrator::rk4, h, periods);
    CAPTURE(e.firstMean);
    CAPTURE(e.lastMean);
    CHECK(e.firstMean < 0.0);
    CHECK(e.lastMean < 10.0 * e.firstMean);
    CHECK(e.lastMean < -1e-3);
  }
}

TEST_CASE("backward Euler: the energy of a passive system falls every step") {
  // On the undamped oscillator E₁ = E₀ / (1 + h² ω²) exactly (the spring is linear, so the one
  // Newton step is the implicit step itself).
  const EnergyHistory e = oscillatorEnergy(Integrator::backwardEuler, 0.01, 100);
  CHECK(e.monotoneDecreasing);
  System sys = harmonicOscillator(4.0, 0.5);
  Solver solver(Integrator::backwardEuler);
  const double e0 = sys.energy().total(), h = 0.05;
  solver.doStep(sys, h);
  CHECK(sys.energy().total() == doctest::Approx(e0 / (1.0 + h * h * 4.0)).epsilon(1e-9));
  // From a moving state: on a linear spring one Newton step is the implicit step, whose closed
  // form is v₁ = (v₀ − h ω² u₀) / (1 + h² ω²), x₁ = x₀ + h v₁ (u: displacement from rest). The
  // h ∂f/∂x v₀ term of the right-hand side is what makes it so: without it v₁ = v₀ − h ω² u₀ /
  // (1 + h² ω²), off by h² ω² v₀ / (1 + h² ω²), an O(h²) error per step that no order test sees.
  System moving = harmonicOscillator(4.0, 0.3);
  moving.state()[moving.layout().velocityOffset() + 2] = 0.7;
  Solver s1(Integrator::backwardEuler);
  s1.doStep(moving, h);
  const double v1 = (0.7 - h * 4.0 * 0.3) / (1.0 + h * h * 4.0);
  CHECK(moving.view().vel(1).x() == doctest::Approx(v1).epsilon(1e-12));
  CHECK(moving.view().pos(1).x() == doctest::Approx(1.3 + h * v1).epsilon(1e-12));
  // A damped, driven system with gravity: energy is not conserved there, but the damped pair's
  // mechanical energy still only falls.
  System pair = dampedPair();
  Solver s2(Integrator::backwardEuler);
  double previous = pair.energy().total();
  bool falls = true;
  for (int i = 0; i < 2000; ++i) {
    s2.doStep(pair, 0.01);
    const double now = pair.energy().total();
    if (!(now <= previous)) falls = false;
    previous = now;
  }
  CHECK(falls);
}

namespace {

// BDF2 on the undamped oscillator u'' = −ω² u (u = x − 1), in closed form: with y = (u, v) and
// L = [0 1; −ω² 0], y₁ = (I − h L)⁻¹ y₀ (the backward Euler start), then
// y_{n+1} = (I − 2h/3 L)⁻¹ (4 y_n − y_{n−1}) / 3. The spring is linear, so the one Newton step is
// the implicit step itself and the integrator must reproduce this to rounding.
std::vector<Eigen::Vector2d> bdf2Oscillator(double omega, double u0, double h, long steps) {
  Eigen::Matrix2d l;
  l << 0.0, 1.0, -omega * omega, 0.0;
  const Eigen::Matrix2d start = (Eigen::Matrix2d::Identity() - h * l).inverse();
  const Eigen::Matrix2d step = (Eigen::Matrix2d::Identity() - (2.0 * h / 3.0) * l).inverse();
  std::vector<Eigen::Vector2d> y{Eigen::Vector2d(u0, 0.0)};
  y.push_back(start * y[0]);
  for (long n = 1; n < steps; ++n) y.push_back(step * (4.0 * y[size_t(n)] - y[size_t(n) - 1]) / 3.0);
  return y;
}

}  // namespace

TEST_CASE("BDF2 on an undamped oscillator: its closed form, second order, and 100× less damping than backward Euler") {
  // ω = 2 (k = 4, m = 1), amplitude 0.5, h = 0.01 over 10 s: the case docs/physics.md measures.
  const double omega = 2.0, h = 0.01, amplitude = 0.5;
  const long steps = 1000;
  System sys = harmonicOscillator(4.0, amplitude);
  Solver solver(Integrator::bdf2);
  const std::vector<Eigen::Vector2d> exact = bdf2Oscillator(omega, amplitude, h, steps);
  double worst = 0.0;
  for (long n = 1; n <= steps; ++n) {
    solver.doStep(sys, h);
    const Eigen::Vector2d y(sys.view().pos(1).x() - 1.0, sys.view().vel(1).x());
    worst = std::max(worst, (y - exact[size_t(n)]).norm());
  }
  CHECK(worst < 1e-12);
  // Energy: backward Euler's falls by (1 + h² ω²)⁻ⁿ; BDF2's is its closed form's.
  auto energyOf = [&](const Eigen::Vector2d& y) { return 0.5 * y[1] * y[1] + 0.5 * omega * omega * y[0] * y[0]; };
  const double e0 = energyOf(exact[0]);
  const double bdf2Loss = (e0 - sys.energy().total()) / e0;
  const double backwardEulerLoss = 1.0 - std::pow(1.0 + h * h * omega * omega, -double(steps));
  System be = harmonicOscillator(4.0, amplitude);
  Solver beSolver(Integrator::backwardEuler);
  advance(be, beSolver, h, steps);
  CHECK((e0 - be.energy().total()) / e0 == doctest::Approx(backwardEulerLoss).epsilon(1e-9));
  CAPTURE(bdf2Loss);
  CAPTURE(backwardEulerLoss);
  CHECK(bdf2Loss > 0.0);                        // it damps (BDF2 is dissipative), but
  CHECK(bdf2Loss * 100.0 < backwardEulerLoss);  // at least 100× less (6.8e-4 against 0.33: 490×)
  CHECK(std::abs(energyOf(exact[size_t(steps)]) - sys.energy().total()) < 1e-12);
  // Second order: the error at t = 2 falls by 4 when h halves (the convergence test above, here
  // against the exact cos as well, at two pairs of steps).
  for (double coarseH : {0.02, 0.01}) {
    const double coarse = oscillatorError(Integrator::bdf2, coarseH),
                 fine = oscillatorError(Integrator::bdf2, coarseH / 2);
    CAPTURE(coarseH);
    CHECK(coarse / fine == doctest::Approx(4.0).epsilon(0.1));
  }
}

TEST_CASE("BDF2 starts with backward Euler, and again after a change of step or a time set from outside") {
  System a = harmonicOscillator(4.0, 0.5), b = harmonicOscillator(4.0, 0.5);
  Solver bdf(Integrator::bdf2), be(Integrator::backwardEuler);
  bdf.doStep(a, 0.01);
  be.doStep(b, 0.01);
  CHECK(a.state() == b.state());  // the first step is backward Euler's
  bdf.doStep(a, 0.01);
  be.doStep(b, 0.01);
  CHECK(a.state() != b.state());  // the second is BDF2's own
  // A new h: backward Euler again, from where it is.
  b.state() = a.state();
  b.setTime(a.time());
  bdf.doStep(a, 0.005);
  be.doStep(b, 0.005);
  CHECK(a.state() == b.state());
  // The time set from outside (a rewind): the history no longer applies.
  bdf.doStep(a, 0.005);
  a.setTime(0.0);
  b.state() = a.state();
  b.setTime(0.0);
  bdf.doStep(a, 0.005);
  be.doStep(b, 0.005);
  CHECK(a.state() == b.state());
}

TEST_CASE("backward Euler and BDF2 are stable on a stiff undamped oscillator at h ω = 100") {
  // ω = 100 rad/s, h = 1 s: every explicit method here explodes within a few steps (test_solver.cpp).
  // Backward Euler's amplitude shrinks by 1/√(1 + h²ω²) ≈ 1/100 a step. BDF2 is A-stable and
  // L-stable: its roots solve (1 − 2/3 h λ) ζ² − 4/3 ζ + 1/3 = 0, λ = ±i ω, whose product
  // 1 / (3 − 2 h λ) has magnitude 1/200 here: the amplitude shrinks about 14× a step.
  for (const auto& [integrator, bound] :
       {std::pair{Integrator::backwardEuler, 0.5 / 50.0}, std::pair{Integrator::bdf2, 0.5}}) {
    CAPTURE(integratorName(integrator));
    System sys = harmonicOscillator(1e4, 0.5);
    Solver solver(integrator);
    double worst = 0.0;
    for (int i = 0; i < 1000; ++i) {
      solver.doStep(sys, 1.0);
      worst = std::max(worst, std::abs(sys.view().pos(1).x() - 1.0));
    }
    CHECK(sys.state().allFinite());
    CHECK(worst < bound);
    CHECK(std::abs(sys.view().pos(1).x() - 1.0) < 1e-12);
  }
  for (Integrator explicitOne : {Integrator::euler, Integrator::rk4, Integrator::symplecticEuler, Integrator::verlet}) {
    System other = harmonicOscillator(1e4, 0.5);
    Solver s2(explicitOne);
    CHECK_THROWS_AS(advance(other, s2, 1.0, 100), SimulationError);
  }
}

TEST_CASE("backward Euler on a rail: a chain hung from a rail moves as one hung from a fixed point") {
  // Hung straight, nothing pushes the rail particle sideways, so both chains are the same problem;
  // at one step per 60 fps frame (h ω ≈ 19 for the stiffest mode) the constrained solve must find
  // the same Δv as the one with the top removed from the unknowns. (A projected CG that lost
  // J Δv = −J v₀ to rounding let this chain fall freely: potential energy 5.3 J instead of −0.47.)
  System onRail = hangingChain(true), fixed = hangingChain(false);
  Solver railSolver(Integrator::backwardEuler), fixedSolver(Integrator::backwardEuler);
  const double h = 1.0 / 60.0;
  for (int step = 0; step < 600; ++step) {
    railSolver.doStep(onRail, h);
    fixedSolver.doStep(fixed, h);
  }
  double worst = 0.0;
  for (int i = 0; i < onRail.layout().numPoints(); ++i) worst = std::max(worst, (onRail.view().pos(i) - fixed.view().pos(i)).norm());
  CHECK(worst < 1e-9);
  CHECK(std::abs(onRail.view().pos(0).y()) < 1e-12);
  CHECK(onRail.energy().total() == doctest::Approx(fixed.energy().total()).epsilon(1e-9));
  // At rest under gravity: the bottom link stretched by m g / k, the top by 24 m g / k.
  CHECK(onRail.view().pos(24).y() == doctest::Approx(-24 * 0.08 - 0.002 * 9.81 / 2500.0 * (24 * 25 / 2)).epsilon(1e-6));
}

TEST_CASE("backward Euler's constrained Δv solves the KKT system of the step, by CG and by the direct solve") {
  // [A Jᵀ; J 0] [Δv; λ] = [b; −J v₀] by a dense LU, against the projected CG and against the
  // direct path (the rail's y eliminated, the rod through the Schur complement): a chain on a rail
  // with a rod in it, swinging, so that J has rows in every direction.
  SystemBuilder b;
  auto& springs = b.emplaceForce<DampedSpringForce>();
  const int top = b.addParticle(particleAt(0.0, 0.0, 0.01));
  const int mid = b.addParticle(particleAt(0.3, -0.2, 0.02));
  const int low = b.addParticle(particleAt(0.5, -0.6, 0.03));
  const int tip = b.addParticle(particleAt(0.9, -0.7, 0.01));
  b.addConstraint(std::make_unique<HorizontalLineConstraint>(top, 0.0));
  b.addConstraint(std::make_unique<RodConstraint>(mid, low, std::hypot(0.2, 0.4)));
  springs.add({Endpoint::ofParticle(top), Endpoint::ofParticle(mid), 0.3, 800.0, 0.5});
  springs.add({Endpoint::ofParticle(low), Endpoint::ofParticle(tip), 0.35, 300.0, 0.2});
  springs.add({Endpoint::ofParticle(top), Endpoint::ofParticle(tip), 1.0, 50.0, 0.0});
  b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  b.emplaceForce<DragForce>(0.01);
  System sys = b.build();
  Solver solver(Integrator::rk4);
  advance(sys, solver, 1e-3, 137);  // moving, with every velocity nonzero
  const Eigen::VectorXd y0 = sys.state();

  Eigen::VectorXd yCg = y0;
  BackwardEulerState cg({.cgTolerance = 1e-14});
  sys.setImplicitSolver(ImplicitSolver::cg);
  cg.step(sys, yCg, sys.time(), 0.05);
  CHECK(cg.implicitStep()->stats().solver == ImplicitSolver::cg);

  const ImplicitStep::LinearSystem w = cg.implicitStep()->lastSystem();
  const Eigen::Index n = w.rhs.size(), m = Eigen::Index(w.constraintRows.size());
  REQUIRE(m == 2);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(m, n);
  for (Eigen::Index r = 0; r < m; ++r) {
    const ConstraintRow& row = w.constraintRows[size_t(r)];
    for (int k = 0; k < row.count; ++k) j.block(r, 2 * row.particle[size_t(k)], 1, 2) = row.J[size_t(k)].transpose();
  }
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + m, n + m);
  kkt.topLeftCorner(n, n) = Eigen::MatrixXd(w.matrix);
  kkt.topRightCorner(n, m) = j.transpose();
  kkt.bottomLeftCorner(m, n) = j;
  Eigen::VectorXd rhs(n + m);
  rhs << w.rhs, -j * y0.segment(sys.layout().velocityOffset(), n);
  const Eigen::VectorXd dense = kkt.partialPivLu().solve(rhs);
  CHECK((w.dv - dense.head(n)).norm() < 1e-9 * dense.head(n).norm());
  CHECK(dense.tail(m).norm() > 1e-6);  // the constraints did push

  Eigen::VectorXd yDirect = y0;
  BackwardEulerState direct;
  sys.setImplicitSolver(ImplicitSolver::direct);
  direct.step(sys, yDirect, sys.time(), 0.05);
  const ImplicitStepStats& stats = direct.implicitStep()->stats();
  CHECK(stats.solver == ImplicitSolver::direct);
  CHECK(stats.eliminated == 1);  // the rail's y
  CHECK(stats.schurRows == 1);   // the rod
  CHECK(stats.factorized);
  CHECK((direct.implicitStep()->lastSystem().dv - dense.head(n)).norm() < 1e-9 * dense.head(n).norm());
  CHECK((yDirect - yCg).norm() < 1e-9 * yCg.norm());
}

TEST_CASE("backward Euler keeps fixed particles in place and treats body rotation explicitly") {
  SystemBuilder b;
  const int anchor = b.addParticle(particleAt(0.2, 0.3, 1.0, true));
  const int bob = b.addParticle(particleAt(1.0, 0.0));
  RigidBodySpec body;
  body.pos = Vec2(0.0, 5.0);
  body.omega = 2.0;
  body.size = Vec2(0.5, 0.2);
  b.addRigidBody(body);
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(bob), Endpoint::ofParticle(anchor), 0.5, 1e3, 1.0});
  b.emplaceForce<GravityForce>(Vec2(0.0, -9.81));
  System sys = b.build();
  Solver solver(Integrator::backwardEuler);
  advance(sys, solver, 0.1, 50);
  CHECK(sys.view().pos(anchor) == Vec2(0.2, 0.3));
  CHECK(sys.view().vel(anchor) == Vec2(0.0, 0.0));
  // No torque: ω stays and θ = ω t; the centre falls as backward Euler's free fall,
  // y_n = y₀ − g h² n(n+1)/2 (each step's velocity is the end-of-step one).
  CHECK(sys.view().omega(0) == 2.0);
  CHECK(sys.view().angle(0) == doctest::Approx(2.0 * 5.0).epsilon(1e-12));
  CHECK(sys.view().pos(sys.layout().bodyPoint(0)).y() == doctest::Approx(5.0 - 9.81 * 0.01 * 50 * 51 / 2).epsilon(1e-12));
}

TEST_CASE("Verlet evaluates once per step after the first, and afresh when the state was moved") {
  int evals = 0;
  const DerivFn f = [&evals](const Eigen::VectorXd& y, double, Eigen::VectorXd& dydt) {
    ++evals;
    dydt.resize(y.size());
    dydt.head(2) = y.tail(2);       // dx/dt = v
    dydt.tail(2) = -4.0 * y.head(2);  // dv/dt = −4 x
  };
  const StateLayout layout{1, 0};
  VerletState w;
  Eigen::VectorXd y(4);
  y << 1.0, 0.0, 0.0, 1.0;
  w.stepWith(f, layout, y, 0.0, 0.1);
  CHECK(evals == 2);
  for (int i = 1; i <= 10; ++i) w.stepWith(f, layout, y, 0.1 * i, 0.1);
  CHECK(evals == 12);
  y[0] += 1e-3;  // moved from outside: the cached a₀ no longer belongs to y
  w.stepWith(f, layout, y, 1.1, 0.1);
  CHECK(evals == 14);
  w.stepWith(f, layout, y, 5.0, 0.1);  // a jump in time
  CHECK(evals == 16);
  w.stepWith(f, layout, y, 5.1, 0.1);
  CHECK(evals == 17);
  y[1] += 1e-9;  // a projection after the step moved y a little, and said so: a₀ is kept
  w.stateProjected(y);
  w.stepWith(f, layout, y, 5.2, 0.1);
  CHECK(evals == 18);
  w.stepUndone();  // the solver put back the state before the step: a₀ is forgotten
  w.stepWith(f, layout, y, 5.3, 0.1);
  CHECK(evals == 20);
  // One step by hand: x₁ = x₀ + h v₀ + h²/2 a₀, v₁ = v₀ + h/2 (a₀ + a(x₁)).
  VerletState fresh;
  Eigen::VectorXd z(4);
  z << 1.0, 0.0, 0.0, 1.0;
  fresh.stepWith(f, layout, z, 0.0, 0.1);
  const double x1 = 1.0 - 0.5 * 0.01 * 4.0;
  CHECK(z[0] == doctest::Approx(x1).epsilon(1e-15));
  CHECK(z[1] == doctest::Approx(0.1).epsilon(1e-15));
  CHECK(z[2] == doctest::Approx(0.05 * (-4.0 - 4.0 * x1)).epsilon(1e-15));
  CHECK(z[3] == doctest::Approx(1.0 + 0.05 * (0.0 - 4.0 * 0.1)).epsilon(1e-15));
}

TEST_CASE("symplectic Euler: velocity first, then position with the new velocity") {
  const DerivFn f = [](const Eigen::VectorXd& y, double, Eigen::VectorXd& dydt) {
    dydt.resize(y.size());
    dydt.head(2) = y.tail(2);
    dydt.tail(2) = -4.0 * y.head(2);
  };
  IntegratorScratch w;
  Eigen::VectorXd y(4);
  y << 1.0, 0.0, 0.0, 1.0;
  integrateSymplecticEuler(f, StateLayout{1, 0}, y, 0.0, 0.1, w);
  CHECK(y[2] == doctest::Approx(-0.4).epsilon(1e-15));
  CHECK(y[0] == doctest::Approx(1.0 - 0.04).epsilon(1e-15));
  CHECK(y[3] == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(y[1] == doctest::Approx(0.1).epsilon(1e-15));
}

TEST_CASE("rigid bodies under the new integrators: free spin and free fall") {
  for (Integrator integrator : {Integrator::symplecticEuler, Integrator::verlet, Integrator::backwardEuler}) {
    CAPTURE(integratorName(integrator));
    SystemBuilder b;
    RigidBodySpec body;
    body.pos = Vec2(0.0, 0.0);
    body.vel = Vec2(1.0, 0.0);
    body.omega = 3.0;
    b.addRigidBody(body);
    System sys = b.build();
    Solver solver(integrator);
    advance(sys, solver, 0.01, 100);
    CHECK(sys.view().angle(0) == doctest::Approx(3.0).epsilon(1e-12));
    CHECK(sys.view().pos(0).x() == doctest::Approx(1.0).epsilon(1e-12));
  }
}
