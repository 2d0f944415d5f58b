#pragma once
// Symplectic (semi-implicit) Euler, one evaluation per step, global error O(h):
//   v₁ = v₀ + h a(x₀, v₀, t₀),   x₁ = x₀ + h v₁
// (and ω, θ alike). Using the new velocity for the position makes the map symplectic for forces
// from a potential: on an undamped oscillator the energy error stays bounded and oscillates
// instead of growing as explicit Euler's does; stable for h ω < 2 (docs/physics.md §3).
//
// With constraints, a is taken without the multipliers' forces and the constraints are kept by
// projection: v₁ is projected onto J(x₀) v = 0 before x moves (projectVelocities), and the solver
// projects (x₁, v₁) after the step. Explicit multiplier forces depend on v (the centripetal part)
// and made the step gain energy (a pendulum: +32 % in 10 s at h = 0.01); the projection loses a
// little instead (−1 J of 5.3 in the same run), as a first-order method may.

#include <Eigen/Core>

#include "core/integrators.hpp"
#include "core/state.hpp"

namespace particles {

// Projects y's velocities onto the constraints at y's positions; empty when there are none.
using VelocityProjection = std::function<void(Eigen::VectorXd& y)>;

void integrateSymplecticEuler(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h,
                              IntegratorScratch& w, const VelocityProjection& projectVelocities = {});
// Its registry row's state: scratch only, the step over the system's derivEval without the
// constraint forces, and its velocity projection when the system has constraints.
std::unique_ptr<IntegratorState> makeSymplecticEulerState();

}  // namespace particles
