#pragma once
// What does not change while stepping (MuJoCo's "model" as opposed to its "data"): the state
// layout, masses, rigid-body shapes and the names users refer to objects by.

#include <string>
#include <vector>

#include "core/state.hpp"

namespace particles {

struct RigidBody {
  Vec2 size;       // full width and height of the rectangle, metres
  double inertia;  // about the centre of mass, I = m (w² + h²) / 12 (docs/physics.md §7)
};

struct Model {
  StateLayout layout;
  Eigen::VectorXd mass;     // per point, kg
  Eigen::VectorXd invMass;  // per point; 0 for a fixed particle (W in docs/physics.md §5)
  Eigen::VectorXd invInertia;  // per body
  std::vector<RigidBody> bodies;
  std::vector<std::string> particleNames;  // may be empty strings for unnamed particles
  std::vector<std::string> bodyNames;

  bool isFixed(int particle) const { return invMass[particle] == 0.0; }
};

}  // namespace particles
