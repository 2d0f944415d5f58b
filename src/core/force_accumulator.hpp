#pragma once
// Force and torque accumulators filled by one derivEval (docs/physics.md §2, stages 1–4).

#include <Eigen/Core>

#include "core/state.hpp"

namespace particles {

struct ForceAccumulator {
  Eigen::VectorXd force;   // 2 per point, newtons
  Eigen::VectorXd torque;  // 1 per body, newton-metres

  void resize(const StateLayout& layout) {
    force.setZero(2 * layout.numPoints());
    torque.setZero(layout.numBodies);
  }
  void clear() {
    force.setZero();
    torque.setZero();
  }
  void addForce(int point, const Vec2& f) {
    force[2 * point] += f.x();
    force[2 * point + 1] += f.y();
  }
  Vec2 forceOn(int point) const { return {force[2 * point], force[2 * point + 1]}; }
};

}  // namespace particles
