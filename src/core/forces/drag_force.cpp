#include "core/forces/drag_force.hpp"

namespace particles {

void DragForce::apply(const Model& model, const StateView& s, double, ForceAccumulator& acc) const {
  const Eigen::Index n = 2 * Eigen::Index(model.layout.numPoints());
  acc.force.head(n) -= kd_ * s.vector().segment(model.layout.velocityOffset(), n);
  if (angularKd_ != 0.0) {
    acc.torque -= angularKd_ * s.vector().segment(model.layout.omegaOffset(), model.layout.numBodies);
  }
}

}  // namespace particles
