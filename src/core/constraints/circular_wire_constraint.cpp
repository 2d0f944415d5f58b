#include "core/constraints/circular_wire_constraint.hpp"

#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "core/system.hpp"

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

const KindSpec& circularWireKind() {
  static const KindSpec spec{
      .section = "constraints",
      .type = "circular_wire",
      .summary = "a bead on a circle: C = ½((p−c)·(p−c) − r²)",
      .params = withFeedbackParams(
          {{.key = "particle", .type = ParamType::particles, .note = "particles", .insteadOf = "particles"},
           {.key = "particles", .type = ParamType::particles, .note = "particles", .insteadOf = "particle"},
           {.key = "center", .type = ParamType::vec2, .unit = "m", .required = true},
           {.key = "radius", .type = ParamType::number, .unit = "m",
            .defaultText = "each particle's current distance to the centre", .min = Bound{0.0, false}}}),
      .build = [](const KindArgs& args, SystemBuilder& out) {
        const Vec2 center = args.vec2("center");
        for (const Endpoint& p : args.points(args.has("particle") ? "particle" : "particles")) {
          double radius = 0.0;
          if (args.has("radius")) {
            radius = args.number("radius");
          } else {
            radius = (args.initialPosition(p) - center).norm();
            if (!(radius > 0.0)) {
              args.fail("", fmt::format("{} sits at the wire's centre; give a 'radius' > 0", args.describe(p)));
            }
          }
          out.addConstraint(std::make_unique<CircularWireConstraint>(p.particle, center, radius, feedbackFrom(args)));
        }
      },
  };
  return spec;
}

}  // namespace particles
