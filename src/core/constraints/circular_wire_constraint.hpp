#pragma once
// Bead on a circular wire, centre c, radius r (docs/physics.md §5):
//   C = ½((p−c)·(p−c) − r²),  Ċ = v·(p−c),  J = (p−c)ᵀ,  J̇ = vᵀ

#include "core/constraint.hpp"

namespace particles {

class CircularWireConstraint final : public Constraint {
 public:
  CircularWireConstraint(int particle, const Vec2& center, double radius, ConstraintFeedback feedback = {})
      : Constraint(feedback), particle_(particle), center_(center), radius_(radius) {}
  int particle() const { return particle_; }
  const Vec2& center() const { return center_; }
  double radius() const { return radius_; }

  std::string_view kind() const override { return "circular_wire"; }
  ConstraintRow evaluate(const StateView& s) const override;
  double violation(const StateView& s) const override;
  std::vector<int> particles() const override { return {particle_}; }
  void draw(const StateView& s, Drawing& out) const override;

 private:
  int particle_;
  Vec2 center_;
  double radius_;
};

// How scenario files write it (`{type: circular_wire, particle(s), center, radius, ks, kd}`: one constraint per particle).
const KindSpec& circularWireKind();

}  // namespace particles
