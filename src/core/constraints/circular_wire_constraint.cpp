#include "core/constraints/circular_wire_constraint.hpp"

#include <cmath>

namespace particles {

ConstraintRow CircularWireConstraint::evaluate(const StateView& s) const {
  const Vec2 d = s.pos(particle_) - center_;
  const Vec2 v = s.vel(particle_);
  ConstraintRow row;
  row.C = 0.5 * (d.squaredNorm() - radius_ * radius_);
  row.Cdot = v.dot(d);
  row.count = 1;
  row.particle[0] = particle_;
  row.J[0] = d;
  row.Jdot[0] = v;
  return row;
}

double CircularWireConstraint::violation(const StateView& s) const {
  return std::abs((s.pos(particle_) - center_).norm() - radius_);
}

void CircularWireConstraint::draw(const StateView&, Drawing& out) const { out.addGuideCircle({center_, radius_}); }

}  // namespace particles
