#include "core/integrators/bdf2.hpp"

#include <algorithm>
#include <cmath>

#include "core/system.hpp"

namespace particles {

bool Bdf2State::continues(const Eigen::VectorXd& y, double t, double h) const {
  // The history holds when this step continues the last one: same h, same state size, and t its
  // end (the Solver computes t afresh each step, so allow rounding).
  return hasPrevious_ && previous_.size() == y.size() && h == previousH_ &&
         std::abs(t - (previousT_ + h)) <= 1e-9 * std::max(1.0, std::abs(t));
}

void Bdf2State::step(System& system, Eigen::VectorXd& y, double t, double h) {
  const StateLayout& layout = system.layout();
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();
  const bool bdf2 = continues(y, t, h);
  start_ = y;
  if (!bdf2) {
    implicit_.step(system, y, t, h, ImplicitTarget{.eta = h});
  } else {
    // Linearised at the extrapolated end y_b = 2 y₀ − y₋₁, at t + h: x̄ − x_b = (x₋₁ − x₀) 2/3,
    // v̄ − v_b likewise (x̄ = (4 x₀ − x₋₁)/3).
    xShift_ = (previous_.head(n) - y.head(n)) * (2.0 / 3.0);
    vShift_ = (previous_.segment(vOff, n) - y.segment(vOff, n)) * (2.0 / 3.0);
    y.head(vOff + n) = 2.0 * y.head(vOff + n) - previous_.head(vOff + n);
    implicit_.step(
        system, y, t + h, h,
        ImplicitTarget{.eta = 2.0 * h / 3.0, .xShift = &xShift_, .vShift = &vShift_, .rotationStart = &start_});
  }
  previous_.swap(start_);
  previousT_ = t;
  previousH_ = h;
  hasPrevious_ = true;
}

std::unique_ptr<IntegratorState> makeBdf2State() {
  return std::make_unique<Bdf2State>();
}

}  // namespace particles
