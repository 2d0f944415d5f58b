#pragma once
// Explicit (forward) Euler, the report's first method (docs/physics.md §3), one evaluation per step,
// global error O(h):
//   y₁ = y₀ + h f(y₀, t₀)
// Its amplification factor on an undamped oscillator, |1 + iωh| > 1, makes the energy grow every
// step at any h: the baseline the stability study compares the others against.

#include <Eigen/Core>

#include "core/integrators.hpp"

namespace particles {

void integrateEuler(const DerivFn& f, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);
// Its registry row's state: scratch only, the step over the system's derivEval.
std::unique_ptr<IntegratorState> makeEulerState();

}  // namespace particles
