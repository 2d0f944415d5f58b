#pragma once
// Velocity Verlet, global error O(h²), one new evaluation per step after the first:
//   x₁ = x₀ + h v₀ + h²/2 a₀,   a₁ = a(x₁, v₀ + h a₀, t₀ + h),   v₁ = v₀ + h/2 (a₀ + a₁)
// (and θ, ω alike), with a₀ the previous step's a₁. For forces of position alone this is the
// classic symplectic, time-reversible scheme (bounded energy error, stable for h ω < 2). A force
// of velocity (drag, spring damping) makes the exact scheme implicit in v₁; a₁ is taken at the
// Euler prediction v₀ + h a₀ instead, an O(h²) error in a₁'s argument, so the step stays second
// order. The cached a₀ is used only when y and t are those the last step ended at (a projection
// after the step keeps it, IntegratorScratch::stateProjected); otherwise it is evaluated afresh.

#include <Eigen/Core>

#include "core/integrators.hpp"
#include "core/state.hpp"

namespace particles {

void integrateVerlet(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h,
                     IntegratorScratch& w);

}  // namespace particles
