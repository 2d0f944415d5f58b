#include "core/constraints/horizontal_line_constraint.hpp"

#include <cmath>

namespace particles {

ConstraintRow HorizontalLineConstraint::evaluate(const StateView& s) const {
  ConstraintRow row;
  row.C = s.pos(particle_).y() - height_;
  row.Cdot = s.vel(particle_).y();
  row.count = 1;
  row.particle[0] = particle_;
  row.J[0] = Vec2(0.0, 1.0);
  row.Jdot[0] = Vec2::Zero();
  return row;
}

double HorizontalLineConstraint::violation(const StateView& s) const {
  return std::abs(s.pos(particle_).y() - height_);
}

void HorizontalLineConstraint::draw(const StateView&, Drawing& out) const {
  out.addGuideLine({Vec2(0.0, height_), Vec2(1.0, 0.0)});
}

}  // namespace particles
