#pragma once
// A particle sliding on the horizontal line y = h (the cloth's rail) (docs/physics.md §5):
//   C = p_y − h,  Ċ = v_y,  J = [0, 1],  J̇ = 0

#include "core/constraint.hpp"

namespace particles {

class HorizontalLineConstraint final : public Constraint {
 public:
  HorizontalLineConstraint(int particle, double height, ConstraintFeedback feedback = {})
      : Constraint(feedback), particle_(particle), height_(height) {}
  int particle() const { return particle_; }
  double height() const { return height_; }

  std::string_view kind() const override { return "horizontal_line"; }
  ConstraintRow evaluate(const StateView& s) const override;
  double violation(const StateView& s) const override;
  std::vector<int> particles() const override { return {particle_}; }
  void draw(const StateView& s, Drawing& out) const override;

 private:
  int particle_;
  double height_;
};

// How scenario files write it (`{type: horizontal_line, particle(s), y, ks, kd}`: one constraint per particle).
const KindSpec& horizontalLineKind();

}  // namespace particles
