#pragma once
// Backward (implicit) Euler, linearised as in Baraff & Witkin, "Large Steps in Cloth Simulation"
// (SIGGRAPH 1998, eq. 16–18): one Newton step of v₁ = v₀ + h M⁻¹ f(x₁, v₁), x₁ = x₀ + h v₁,
//   (M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀),   v₁ = v₀ + Δv,   x₁ = x₀ + h v₁
// global error O(h): core/implicit_step.hpp with x̄ = x₀, v̄ = v₀, η = h (the matrix, the
// constraints inside the solve, the direct and CG solves, rigid bodies' explicit rotation). f₀ is
// the force of derivEval at the step's start (collisions included, constraint forces not).
//
// Why: on a linear spring the step's amplification is 1/(1 + h ω) in magnitude for ω h of any
// size (A-stable, L-stable), so stiff springs no longer bound h; the price is numerical damping
// (energy falls by h² ω² E₁ a step on an undamped oscillator, a factor (1 + h² ω²)⁻ⁿ over n
// steps) and one sparse solve per step. BDF2 (bdf2.hpp) damps far less for the same solve.
//
// Constraints are part of the solve (Δv keeps J Δv = −J v₀), and the solver then projects
// (x₁, v₁) onto the constraints after the step (ConstraintSolver), removing the O(h²) drift of
// moving along the tangent. Taken outside the solve instead — the multipliers' forces at the
// step's start, or a projection of v₁ afterwards — the constraints lag the implicit springs: the
// stiff cloth sagged off its rail by a spring's length per second at h = 1/60 s and gained energy
// without bound.

#include <Eigen/Core>

#include "core/implicit_step.hpp"
#include "core/integrators.hpp"

namespace particles {

class System;

struct BackwardEulerOptions {
  double cgTolerance = kCgTolerance;  // the CG path's relative residual
};

// Backward Euler's state: the common implicit step's (its pattern, factors and last Δv).
class BackwardEulerState final : public IntegratorState {
 public:
  explicit BackwardEulerState(const BackwardEulerOptions& options = {}) : options_(options) {}
  void step(System& system, Eigen::VectorXd& y, double t, double h) override;
  const ImplicitStep* implicitStep() const override { return &implicit_; }

 private:
  BackwardEulerOptions options_;
  ImplicitStep implicit_;
};

std::unique_ptr<IntegratorState> makeBackwardEulerState();

}  // namespace particles
