#pragma once
// The integrators (docs/physics.md §3) and their registry. One step advances the flat state y from
// t to t + h; every integrator reaches the system only through derivEval (and, for the implicit
// ones, the force Jacobians). Each is a file pair under integrators/ with its formula at
// the top: the report's three explicit methods over a derivative f(y, t) (explicit_euler,
// midpoint, rk4), and the ones that treat positions and velocities apart (symplectic_euler,
// verlet, and the implicit backward_euler and bdf2 over core/implicit_step.hpp).
//
// A new integrator: its file pair (the step, and makeXxxState for its registry row: what it keeps
// from one step to the next), an enum value below, and one row in the table of integrators.cpp.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include <particles/choices.hpp>

#include "core/worker_pool.hpp"

namespace particles {

class ImplicitStep;
class System;

// The public enum (include/particles/choices.hpp): the library's callers and the core name one type.
using particles::Integrator;

std::string_view integratorName(Integrator integrator);
// "euler", "midpoint", "rk4", "symplectic_euler", "verlet", "backward_euler", "bdf2"
std::optional<Integrator> integratorFromName(std::string_view name);
std::span<const Integrator> allIntegrators();
// Derivative evaluations a step costs once under way: 1, 2, 4, 1, 1 (Verlet reuses the previous
// step's last one), 1 (backward Euler and BDF2, plus the Jacobians and a sparse solve).
int derivEvalsPerStep(Integrator integrator);
// True for the integrators after which the solver projects the state onto the constraints: their
// steps do not follow the multipliers' drift feedback the way the explicit Runge–Kutta ones do.
bool projectsConstraints(Integrator integrator);
// True for backward Euler and BDF2: a linear solve per step, stable at any step on a spring.
bool isImplicit(Integrator integrator);
// One line on what the integrator is, for --help and the docs.
std::string_view integratorSummary(Integrator integrator);

using DerivFn = std::function<void(const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt)>;
// The system's derivEval as a DerivFn (constraint forces included).
DerivFn derivativeOf(System& system);

// Vectors a step fills, kept so that stepping does not allocate; nothing in them is carried from
// one step to the next.
struct IntegratorScratch {
  // The System's threads, for the whole-vector updates (null: serial).
  WorkerPool* pool = nullptr;
  Eigen::VectorXd k1, k2, k3, k4, tmp;
};

// One integrator's own state, made by its registry row and held by the Solver for as long as it
// steps with that integrator: its scratch, and what it carries from one step to the next (Verlet's
// last evaluation, the implicit step's pattern, factors and last Δv, BDF2's previous state). Each
// checks what it carries against the step it is asked for (Verlet: the state and time; BDF2: h,
// t and the state's size; the implicit step: A's pattern) and starts afresh where that no longer
// applies, so a new dt, or a state or time set from outside, needs no call here.
class IntegratorState {
 public:
  virtual ~IntegratorState() = default;
  // One step of the system's state y at time t by h.
  virtual void step(System& system, Eigen::VectorXd& y, double t, double h) = 0;
  // The solver moved y by a projection onto the constraints after the step (a drift-sized
  // correction).
  virtual void stateProjected(const Eigen::VectorXd& y) { (void)y; }
  // The solver undid the step (it blew up) and put the state back.
  virtual void stepUndone() {}
  // Backward Euler's and BDF2's common step (its statistics, for benchmarks and tests); null for
  // the explicit integrators.
  virtual const ImplicitStep* implicitStep() const { return nullptr; }
};

// The state of an integrator that carries nothing between steps: its scratch and its step.
class ScratchOnlyState final : public IntegratorState {
 public:
  using Step = void (*)(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
  explicit ScratchOnlyState(Step step) : step_(step) {}
  void step(System& system, Eigen::VectorXd& y, double t, double h) override;

 private:
  Step step_;
  IntegratorScratch scratch_;
};

// The state of a method over a derivative f(y, t) (explicit Euler, midpoint, RK4): scratch only,
// and the method over the system's derivEval.
using ExplicitMethod = void (*)(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
template <ExplicitMethod method>
std::unique_ptr<IntegratorState> makeExplicitMethodState() {
  return std::make_unique<ScratchOnlyState>([](System& system, Eigen::VectorXd& y, double t, double h,
                                               IntegratorScratch& w) { method(derivativeOf(system), y, t, h, w); });
}

// A fresh state for the named integrator, from its registry row.
std::unique_ptr<IntegratorState> makeIntegratorState(Integrator integrator);

}  // namespace particles
