#pragma once
// Backward (implicit) Euler, linearised as in Baraff & Witkin, "Large Steps in Cloth Simulation"
// (SIGGRAPH 1998, eq. 16–18): one Newton step of v₁ = v₀ + h M⁻¹ f(x₁, v₁), x₁ = x₀ + h v₁,
//   (M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀),   v₁ = v₀ + Δv,   x₁ = x₀ + h v₁
// global error O(h). f₀ is the force of derivEval at the step's start (collisions included,
// constraint forces not: see below); ∂f/∂x and ∂f/∂v come from each force's Jacobians
// (core/force_jacobians.hpp). The matrix is sparse, symmetric positive definite (every block is
// negative semi-definite, the spring's compressive part being clamped), and is solved by
// conjugate gradients with a diagonal (Jacobi) preconditioner, from the previous step's Δv.
// Fixed particles keep Δv = 0 (their rows and columns become the identity).
//
// Why: on a linear spring the step's amplification is 1/(1 + h ω) in magnitude for ω h of any
// size (A-stable, L-stable), so stiff springs no longer bound h; the price is numerical damping
// (energy falls by h² ω² E₁ a step on an undamped oscillator) and one sparse solve per step.
//
// Rigid bodies: their centres' translation is in the implicit solve (springs and corners couple
// through the centre); their rotation is explicit, symplectic Euler on (θ, ω) with the torque at
// the step's start: ω₁ = ω₀ + h τ₀/I, θ₁ = θ₀ + h ω₁.
//
// Constraints are part of the solve: CG runs projected onto J Δv = −J v₀ (J at x₀), so v₁ keeps
// Ċ = 0 and the stiff springs feel the rail holding the cloth within the same step (projected
// CG, the general form of Baraff & Witkin's §5.3 filter). The solver then projects (x₁, v₁) onto
// the constraints after the step (ConstraintSolver), removing the O(h²) drift of moving along the
// tangent. Taken outside the solve instead — the multipliers' forces at the step's start, or a
// projection of v₁ afterwards — the constraints lag the implicit springs: the stiff cloth sagged
// off its rail by a spring's length per second at h = 1/60 s and gained energy without bound.

#include <Eigen/Core>

#include "core/integrators.hpp"

namespace particles {

class System;

struct BackwardEulerOptions {
  double tolerance = 1e-6;  // CG's relative residual
};

void integrateBackwardEuler(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w,
                            const BackwardEulerOptions& options = {});

}  // namespace particles
