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
// Constraints are kept by projection, as for symplectic Euler: v₁ is projected onto J(x₀) v = 0
// before x moves, and the solver projects (x₁, v₁) after the step (ConstraintSolver). The
// multipliers' forces taken explicitly would add energy (their centripetal part depends on v),
// against the method's point; the projection only removes it.

#include <Eigen/Core>

#include "core/integrators.hpp"

namespace particles {

class System;

struct BackwardEulerOptions {
  double tolerance = 1e-10;  // CG's relative residual
};

void integrateBackwardEuler(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w,
                            const BackwardEulerOptions& options = {});

}  // namespace particles
