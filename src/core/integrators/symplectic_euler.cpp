#include "core/integrators/symplectic_euler.hpp"

#include <functional>

namespace particles {

void integrateSymplecticEuler(const DerivFn& f, const StateLayout& layout, Eigen::VectorXd& y, double t, double h,
                              IntegratorScratch& w, const VelocityProjection& projectVelocities) {
  f(y, t, w.k1);
  const auto blocks = layout.secondOrderBlocks();
  for (const auto& b : blocks) y.segment(b.velocity, b.length) += h * w.k1.segment(b.velocity, b.length);
  if (projectVelocities) projectVelocities(y);
  for (const auto& b : blocks) y.segment(b.position, b.length) += h * y.segment(b.velocity, b.length);
}

}  // namespace particles
