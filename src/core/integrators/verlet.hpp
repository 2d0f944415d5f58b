#pragma once
// Velocity Verlet, global error O(h²), one new evaluation per step after the first:
//   x₁ = x₀ + h v₀ + h²/2 a₀,   a₁ = a(x₁, v₀ + h a₀, t₀ + h),   v₁ = v₀ + h/2 (a₀ + a₁)
// (and θ, ω alike), with a₀ the previous step's a₁. For forces of position alone this is the
// classic symplectic, time-reversible scheme (bounded energy error, stable for h ω < 2). A force
// of velocity (drag, spring damping) makes the exact scheme implicit in v₁; a₁ is taken at the
// Euler prediction v₀ + h a₀ instead, an O(h²) error in a₁'s argument, so the step stays second
// order. The cached a₀ is used only when y and t are those the last step ended at (a projection
// after the step keeps it, VerletState::stateProjected); otherwise it is evaluated afresh.

#include <Eigen/Core>

#include "core/integrators.hpp"
#include "core/state.hpp"

namespace particles {

// Verlet's state: a₀, the derivative at the state and time its last step ended at.
class VerletState final : public IntegratorState {
 public:
  void step(System& system, Eigen::VectorXd& y, double t, double h) override;
  // The same step over any derivative f (on the calling thread).
  void stepWith(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h);
  // The projection moved y by a drift-sized correction: a₀ is kept for the moved state, so that
  // Verlet keeps to one evaluation per step on constrained systems.
  void stateProjected(const Eigen::VectorXd& y) override;
  void stepUndone() override { cached_ = false; }

 private:
  IntegratorScratch scratch_;
  Eigen::VectorXd lastF_, lastY_;  // a₀ = f(lastY_, lastT_), valid when cached_
  double lastT_ = 0.0;
  bool cached_ = false;
};

std::unique_ptr<IntegratorState> makeVerletState();

}  // namespace particles
