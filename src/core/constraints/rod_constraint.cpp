#include "core/constraints/rod_constraint.hpp"

#include <cmath>

namespace particles {

ConstraintRow RodConstraint::evaluate(const StateView& s) const {
  const Vec2 d = s.pos(a_) - s.pos(b_);
  const Vec2 w = s.vel(a_) - s.vel(b_);
  ConstraintRow row;
  row.C = d.squaredNorm() - length_ * length_;
  row.Cdot = 2.0 * d.dot(w);
  row.count = 2;
  row.particle = {a_, b_};
  row.J = {2.0 * d, -2.0 * d};
  row.Jdot = {2.0 * w, -2.0 * w};
  return row;
}

double RodConstraint::violation(const StateView& s) const {
  return std::abs((s.pos(a_) - s.pos(b_)).norm() - length_);
}

void RodConstraint::draw(const StateView& s, Drawing& out) const { out.rods.push_back({s.pos(a_), s.pos(b_)}); }

}  // namespace particles
