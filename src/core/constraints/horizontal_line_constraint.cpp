#include "core/constraints/horizontal_line_constraint.hpp"

#include <cmath>
#include <memory>

#include "core/system.hpp"

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

const KindSpec& horizontalLineKind() {
  static const KindSpec spec{
      .section = "constraints",
      .type = "horizontal_line",
      .summary = "particles sliding on y = h (the cloth's rail): C = p_y − h",
      .params = withFeedbackParams(
          {{.key = "particle", .type = ParamType::particles, .note = "particles", .insteadOf = "particles"},
           {.key = "particles", .type = ParamType::particles, .note = "particles", .insteadOf = "particle"},
           {.key = "y", .type = ParamType::number, .unit = "m", .defaultText = "each particle's current y"}}),
      .build = [](const KindArgs& args, SystemBuilder& out) {
        const bool hasY = args.has("y");
        const double y = hasY ? args.number("y") : 0.0;
        for (const Endpoint& p : args.points(args.has("particle") ? "particle" : "particles")) {
          const double height = hasY ? y : args.initialPosition(p).y();
          out.addConstraint(std::make_unique<HorizontalLineConstraint>(p.particle, height, feedbackFrom(args)));
        }
      },
  };
  return spec;
}

}  // namespace particles
