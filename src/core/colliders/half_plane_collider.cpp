#include "core/colliders/half_plane_collider.hpp"

#include "core/system.hpp"

namespace particles {

const KindSpec& halfPlaneKind() {
  static const KindSpec spec{
      .section = "colliders",
      .type = "half_plane",
      .summary = "the allowed side is n·p ≥ offset; everything with n·p < offset is solid",
      .params = withPenaltyParams(
          {{.key = "normal", .type = ParamType::vec2, .required = true, .note = "not [0, 0]; normalised on loading"},
           {.key = "offset", .type = ParamType::number, .unit = "m", .defaultNumber = 0.0}}),
      .build = [](const KindArgs& args, SystemBuilder& out) {
        const Vec2 normal = args.vec2("normal");
        if (!(normal.norm() > 0.0)) args.fail("normal", "the normal must not be [0, 0]");
        const double offset = args.number("offset");
        out.addCollider(std::make_unique<HalfPlaneCollider>(normal, offset, penaltyFrom(args)));
      },
  };
  return spec;
}

}  // namespace particles
