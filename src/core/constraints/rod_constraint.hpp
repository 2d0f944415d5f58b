#pragma once
// Rigid rod of length r between particles 1 and 2 (docs/physics.md §5):
//   C = |p1−p2|² − r²,  Ċ = 2(p1−p2)·(v1−v2),
//   J = [2(p1−p2)ᵀ, −2(p1−p2)ᵀ],  J̇ = [2(v1−v2)ᵀ, −2(v1−v2)ᵀ]

#include "core/constraint.hpp"

namespace particles {

class RodConstraint final : public Constraint {
 public:
  RodConstraint(int a, int b, double length, ConstraintFeedback feedback = {})
      : Constraint(feedback), a_(a), b_(b), length_(length) {}
  int a() const { return a_; }
  int b() const { return b_; }
  double length() const { return length_; }

  std::string_view kind() const override { return "rod"; }
  ConstraintRow evaluate(const StateView& s) const override;
  double violation(const StateView& s) const override;
  std::vector<int> particles() const override { return {a_, b_}; }
  void draw(const StateView& s, Drawing& out) const override;

 private:
  int a_, b_;
  double length_;
};

// How scenario files write it (`{type: rod, a, b, length, ks, kd}`).
const KindSpec& rodKind();

}  // namespace particles
