#include "core/constraints/rod_constraint.hpp"

#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "core/system.hpp"

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

const KindSpec& rodKind() {
  static const KindSpec spec{
      .section = "constraints",
      .type = "rod",
      .summary = "a fixed distance between two particles: C = |p1−p2|² − r²",
      .params = withFeedbackParams(
          {{.key = "a", .type = ParamType::particle, .required = true, .note = "a particle"},
           {.key = "b", .type = ParamType::particle, .required = true, .note = "a particle other than `a`"},
           {.key = "length", .type = ParamType::number, .unit = "m", .defaultText = "the current distance",
            .min = Bound{0.0, false}}}),
      .build = [](const KindArgs& args, SystemBuilder& out) {
        const Endpoint a = args.points("a").front(), b = args.points("b").front();
        if (a.particle == b.particle) args.fail("b", fmt::format("a rod joins {} to itself", args.describe(a)));
        double length = 0.0;
        if (args.has("length")) {
          length = args.number("length");
        } else {
          length = (args.initialPosition(a) - args.initialPosition(b)).norm();
          if (!(length > 0.0)) args.fail("b", "the rod's particles coincide; give a 'length' > 0");
        }
        out.addConstraint(std::make_unique<RodConstraint>(a.particle, b.particle, length, feedbackFrom(args)));
      },
  };
  return spec;
}

}  // namespace particles
