#include "core/solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/worker_pool.hpp"

namespace particles {

namespace {

std::string explosionMessage(const std::string& reason, long step, double time, Integrator integrator, double dt) {
  std::string advice = fmt::format("try a smaller time step (e.g. --dt {:.3g})", dt / 4.0);
  if (integrator != Integrator::rk4 && !isImplicit(integrator)) {
    advice += " or a higher-order integrator (--integrator rk4)";
  }
  // Stiff springs bound every explicit method's step; the implicit ones are stable at any h.
  if (!isImplicit(integrator)) advice += "; for stiff springs, --integrator bdf2 or backward_euler";
  return fmt::format("simulation exploded at step {} (t = {:.6g} s) with integrator {} and dt = {:.6g} s: {}; {}",
                     step, time, integratorName(integrator), dt, reason, advice);
}

}  // namespace

SimulationError explosionError(const std::string& reason, long step, double time, Integrator integrator, double dt) {
  return SimulationError(explosionMessage(reason, step, time, integrator, dt), reason, step, time, integrator, dt);
}

const ImplicitStepStats& Solver::lastImplicitStep() const {
  static const ImplicitStepStats kNone;
  const ImplicitStep* implicit = state_->implicitStep();
  return implicit ? implicit->stats() : kNone;
}

long Solver::factorizations() const {
  const ImplicitStep* implicit = state_->implicitStep();
  return implicit ? implicit->factorizations() : 0;
}

void Solver::doStep(System& system, double dt) {
  // The guard's copy and checks are whole-state passes like the integrators' own updates, so they
  // run on the same threads (their share of the thinnest step, symplectic Euler's: bench/README.md,
  // "The core past two threads").
  WorkerPool* pool = system.pool();
  const Eigen::VectorXd& y = system.state();
  previous_.resize(y.size());
  forSegments(pool, y.size(), [&](long i, long n) { previous_.segment(i, n) = y.segment(i, n); });
  const double t0 = system.time();
  if (runSteps_ == 0 || dt != runDt_ || t0 != runStart_ + double(runSteps_) * runDt_) {
    runStart_ = t0;
    runDt_ = dt;
    runSteps_ = 0;
  }
  state_->step(system, system.state(), t0, dt);
  if (projectsConstraints(integrator_) && !system.constraints().empty()) {
    system.projectOntoConstraints(system.state());
    state_->stateProjected(system.state());
  }
  const long step = steps_ + 1;
  const double t1 = runStart_ + double(runSteps_ + 1) * dt;

  std::string reason;
  const System::StateCheck check = system.checkState(system.state(), guardScratch_);
  if (!check.finite) {
    reason = "the state became non-finite (NaN or infinity)";
  } else {
    const double limit = guard_.energyFactor * system.energyScale();
    if (check.kinetic > limit) {
      reason = fmt::format("kinetic energy {:.3g} J exceeds {:.0e} times the system's energy scale ({:.3g} J)",
                           check.kinetic, guard_.energyFactor, system.energyScale());
    }
  }
  if (!reason.empty()) {
    system.state() = previous_;
    state_->stepUndone();
    throw explosionError(reason, step, t1, integrator_, dt);
  }
  system.setTime(t1);
  steps_ = step;
  ++runSteps_;
}

long Stepper::stepsAt(double t) const { return std::max(steps(), long(std::floor((t - t0_) / dt_ + 1e-9))); }

void Stepper::advanceTo(double t) {
  const long target = stepsAt(t);
  while (steps() < target) step();
}

}  // namespace particles
