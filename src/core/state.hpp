#pragma once
// The flat state vector (docs/physics.md §2) and typed, read-only access to it.
//
// Points are the particles followed by the rigid bodies' centres of mass: point i < numParticles
// is particle i, point numParticles + j is the centre of body j. The integrator sees one vector
//   y = [ x (2P) | v (2P) | θ (B) | ω (B) ],   P = particles + bodies, B = bodies
// and its derivative has the same layout: [ v | F/m | ω | τ/I ] (report eq. 1 and 7).

#include <array>

#include <Eigen/Core>

namespace particles {

using Vec2 = Eigen::Vector2d;

struct StateLayout {
  int numParticles = 0;
  int numBodies = 0;

  int numPoints() const { return numParticles + numBodies; }
  Eigen::Index size() const { return 4 * Eigen::Index(numPoints()) + 2 * Eigen::Index(numBodies); }
  Eigen::Index velocityOffset() const { return 2 * Eigen::Index(numPoints()); }
  Eigen::Index angleOffset() const { return 4 * Eigen::Index(numPoints()); }
  Eigen::Index omegaOffset() const { return angleOffset() + numBodies; }
  int bodyPoint(int body) const { return numParticles + body; }

  // The state as second-order pairs (position block, its velocity block), for the integrators
  // that update them apart: x (2P) with v, θ (B) with ω. The derivative's entry at a velocity
  // block's offset is that block's acceleration.
  struct SecondOrderBlock {
    Eigen::Index position, velocity, length;
  };
  std::array<SecondOrderBlock, 2> secondOrderBlocks() const {
    return {SecondOrderBlock{0, velocityOffset(), 2 * Eigen::Index(numPoints())},
            SecondOrderBlock{angleOffset(), omegaOffset(), numBodies}};
  }
};

class StateView {
 public:
  StateView(const StateLayout& layout, const Eigen::VectorXd& y) : layout_(layout), y_(y) {}

  Vec2 pos(int point) const { return {y_[2 * point], y_[2 * point + 1]}; }
  Vec2 vel(int point) const {
    const Eigen::Index v = layout_.velocityOffset() + 2 * point;
    return {y_[v], y_[v + 1]};
  }
  double angle(int body) const { return y_[layout_.angleOffset() + body]; }
  double omega(int body) const { return y_[layout_.omegaOffset() + body]; }

  const StateLayout& layout() const { return layout_; }
  const Eigen::VectorXd& vector() const { return y_; }

 private:
  const StateLayout& layout_;
  const Eigen::VectorXd& y_;
};

}  // namespace particles
