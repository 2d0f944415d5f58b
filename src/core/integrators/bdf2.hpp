#pragma once
// BDF2, the second-order backward differentiation formula (Choi & Ko, "Stable but Responsive
// Cloth", SIGGRAPH 2002): with y = (x, v) and step h,
//   y₁ − 4/3 y₀ + 1/3 y₋₁ = 2/3 h (v₁, M⁻¹ f(x₁, v₁))
// that is x₁ = x̄ + η v₁, v₁ = v̄ + η M⁻¹ f(x₁, v₁) with x̄ = (4 x₀ − x₋₁)/3, v̄ = (4 v₀ − v₋₁)/3,
// η = 2h/3, taken as one Newton step from (x₀, v₀) by core/implicit_step.hpp:
//   (M − η D − η² K) Δv = M (v̄ − v₀) + η (f₀ + K (x̄ − x₀ + η v₀)),   v₁ = v₀ + Δv
// the same matrix as backward Euler's with η for h, the same solves and constraints.
//
// Why: global error O(h²), and far less numerical damping than backward Euler. On an undamped
// oscillator of frequency ω its amplification per step is 1 − O((hω)⁴) in magnitude (backward
// Euler's 1 − (hω)²/2), so at h = 0.01, ω = 2 it loses 6.8·10⁻⁴ of the energy over 10 s (most of
// it in its backward Euler first step) where backward Euler loses a third. It stays A-stable (any
// step on a stiff spring) and L-stable: at h ω → ∞ its roots, of (1 − 2/3 h λ) ζ² − 4/3 ζ + 1/3 = 0,
// go to 0 like 1/√(2 h ω).
//
// BDF2 needs the state one step back: the first step, one after a change of h, and one after the
// state or time was set from outside (the time is not the last step's end) are backward Euler.
// Rigid bodies rotate explicitly, as in backward Euler (symplectic Euler on θ, ω).

#include <Eigen/Core>

#include "core/implicit_step.hpp"
#include "core/integrators.hpp"

namespace particles {

class System;

// BDF2's state: the common implicit step's, and the state one step back.
class Bdf2State final : public IntegratorState {
 public:
  void step(System& system, Eigen::VectorXd& y, double t, double h) override;
  const ImplicitStep* implicitStep() const override { return &implicit_; }
  // Whether the next step of h from t would use the history (a BDF2 step), not start afresh (a
  // backward Euler step): tests.
  bool continues(const Eigen::VectorXd& y, double t, double h) const;

 private:
  ImplicitStep implicit_;
  // The state a step before the current one (previous_ at previousT_, a step of previousH_),
  // valid when hasPrevious_; the step's start, x̄ − x_b and v̄ − v_b.
  Eigen::VectorXd previous_, start_, xShift_, vShift_;
  double previousT_ = 0.0, previousH_ = 0.0;
  bool hasPrevious_ = false;
};

std::unique_ptr<IntegratorState> makeBdf2State();

}  // namespace particles
