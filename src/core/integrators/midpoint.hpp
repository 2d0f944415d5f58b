#pragma once
// The explicit midpoint method, the report's second (docs/physics.md §3), two evaluations per step,
// global error O(h²):
//   y₁ = y₀ + h f(y₀ + h/2 f(y₀, t₀), t₀ + h/2)
// An Euler half step to the interval's middle, and the full step with the derivative found there.

#include <Eigen/Core>

#include "core/integrators.hpp"

namespace particles {

void integrateMidpoint(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
// Its registry row's state: scratch only, the step over the system's derivEval.
std::unique_ptr<IntegratorState> makeMidpointState();

}  // namespace particles
