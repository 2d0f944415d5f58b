#include "core/integrators/bdf2.hpp"

#include <cmath>

#include "core/system.hpp"

namespace particles {

void integrateBdf2(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  const StateLayout& layout = system.layout();
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();
  // The history holds when this step continues the last one: same h, same state size, and t its
  // end (the Solver computes t afresh each step, so allow rounding).
  const bool continues = w.bdfValid && w.bdfPrevious.size() == y.size() && h == w.bdfPreviousH &&
                         std::abs(t - (w.bdfPreviousT + h)) <= 1e-9 * std::max(1.0, std::abs(t));
  w.bdfStart = y;
  if (!continues) {
    implicitStep(system, y, t, h, ImplicitTarget{.eta = h}, w.implicit);
  } else {
    // Linearised at the extrapolated end y_b = 2 y₀ − y₋₁, at t + h: x̄ − x_b = (x₋₁ − x₀) 2/3,
    // v̄ − v_b likewise (x̄ = (4 x₀ − x₋₁)/3).
    w.bdfXShift = (w.bdfPrevious.head(n) - y.head(n)) * (2.0 / 3.0);
    w.bdfVShift = (w.bdfPrevious.segment(vOff, n) - y.segment(vOff, n)) * (2.0 / 3.0);
    y.head(vOff + n) = 2.0 * y.head(vOff + n) - w.bdfPrevious.head(vOff + n);
    implicitStep(
        system, y, t + h, h,
        ImplicitTarget{
            .eta = 2.0 * h / 3.0, .xShift = &w.bdfXShift, .vShift = &w.bdfVShift, .rotationStart = &w.bdfStart},
        w.implicit);
  }
  w.bdfPrevious.swap(w.bdfStart);
  w.bdfPreviousT = t;
  w.bdfPreviousH = h;
  w.bdfValid = true;
}

}  // namespace particles
