#pragma once
// The integrators (docs/physics.md §3) and their registry. One step advances the flat state y from
// t to t + h; every integrator reaches the system only through derivEval (and, for the implicit
// ones, the force Jacobians). Each is a file pair under integrators/ with its formula at
// the top: the report's three explicit methods over a derivative f(y, t) (explicit_euler,
// midpoint, rk4), and the ones that treat positions and velocities apart (symplectic_euler,
// verlet, and the implicit backward_euler and bdf2 over core/implicit_step.hpp).
//
// A new integrator: its file pair, an enum value below, and one row in the table of integrators.cpp.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include "core/implicit_step.hpp"
#include "core/worker_pool.hpp"

namespace particles {

class System;

enum class Integrator { Euler, Midpoint, Rk4, SymplecticEuler, Verlet, BackwardEuler, Bdf2 };

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

// Scratch kept between steps, so stepping does not allocate, and what an integrator carries from
// one step to the next (Verlet's last evaluation, the implicit step's last Δv and factors, BDF2's
// previous state).
struct IntegratorScratch {
  // The System's threads, for the whole-vector updates (set by integrate; null: serial).
  WorkerPool* pool = nullptr;
  Eigen::VectorXd k1, k2, k3, k4, tmp;

  // Verlet: f at (verletY, verletT), valid when verletValid.
  Eigen::VectorXd verletF, verletY;
  double verletT = 0.0;
  bool verletValid = false;
  // The solver moved y by a projection after the step (a drift-sized correction): the cached
  // evaluation stays, so Verlet keeps to one evaluation per step on constrained systems.
  void stateProjected(const Eigen::VectorXd& y) {
    if (verletValid) verletY = y;
  }

  // Backward Euler and BDF2 (core/implicit_step.hpp).
  ImplicitScratch implicit;
  // BDF2: the state a step before the current one (bdfPrevious at bdfPreviousT, a step of
  // bdfPreviousH), valid when bdfValid; and x̄ − x₀, v̄ − v₀.
  Eigen::VectorXd bdfPrevious, bdfStart, bdfXShift, bdfVShift;
  double bdfPreviousT = 0.0, bdfPreviousH = 0.0;
  bool bdfValid = false;
};

// One step of the named integrator on the system's state y at time t.
void integrate(Integrator integrator, System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);

}  // namespace particles
