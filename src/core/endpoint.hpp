#pragma once
// A place a force acts at: a particle, or an anchor on a rigid body given in body coordinates.
// Kinematics and force application follow docs/physics.md §7:
//   p′ = R(θ) r + p,   v′ = v + ω (−r′_y, r′_x),   τ += r′_x f_y − r′_y f_x,   r′ = R(θ) r

#include "core/force_accumulator.hpp"
#include "core/state.hpp"

namespace particles {

struct Endpoint {
  int particle = -1;            // particle index, or -1 when this is a body anchor
  int body = -1;                // body index, or -1 when this is a particle
  Vec2 anchor = Vec2::Zero();   // body coordinates, metres (zero: the centre of mass)

  static Endpoint ofParticle(int index) { return {index, -1, Vec2::Zero()}; }
  static Endpoint ofBody(int index, const Vec2& anchor = Vec2::Zero()) { return {-1, index, anchor}; }

  bool isParticle() const { return body < 0; }
  int point(const StateLayout& layout) const { return isParticle() ? particle : layout.bodyPoint(body); }
};

// Throws std::invalid_argument naming `what` when the endpoint is not in the layout.
void checkEndpoint(const StateLayout& layout, const Endpoint& e, const char* what);

// r′ = R(θ) r: the anchor's offset from the centre, in world axes.
Vec2 worldOffset(const StateView& s, const Endpoint& e);
Vec2 endpointPosition(const StateView& s, const Endpoint& e);
Vec2 endpointVelocity(const StateView& s, const Endpoint& e);
// Adds f at the endpoint: to the point's force and, for a body anchor, τ = r′_x f_y − r′_y f_x.
void applyForceAt(const StateView& s, const Endpoint& e, const Vec2& f, ForceAccumulator& acc);

}  // namespace particles
