#pragma once
// The classic 4th-order Runge–Kutta method, the report's third (docs/physics.md §3), four
// evaluations per step, global error O(h⁴):
//   k1 = h f(y₀, t₀),              k2 = h f(y₀ + k1/2, t₀ + h/2),
//   k3 = h f(y₀ + k2/2, t₀ + h/2), k4 = h f(y₀ + k3, t₀ + h),
//   y₁ = y₀ + k1/6 + k2/3 + k3/3 + k4/6
// The code keeps the k's as derivatives (kᵢ/h) and applies h once, when they are combined:
//   y₁ = y₀ + (h/6) (k1 + 2 k2 + 2 k3 + k4).

#include <Eigen/Core>

#include "core/integrators.hpp"

namespace particles {

void integrateRk4(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
// Its registry row's state: scratch only, the step over the system's derivEval.
std::unique_ptr<IntegratorState> makeRk4State();

}  // namespace particles
