#include "core/colliders/disk_collider.hpp"

#include "core/system.hpp"

namespace particles {

const KindSpec& diskKind() {
  static const KindSpec spec{
      .section = "colliders",
      .type = "disk",
      .summary = "a solid disk",
      .params = withPenaltyParams({{.key = "center", .type = ParamType::vec2, .unit = "m", .required = true},
                                   {.key = "radius", .type = ParamType::number, .unit = "m", .required = true,
                                    .min = Bound{0.0, false}}}),
      .build = [](const KindArgs& args, SystemBuilder& out) {
        const Vec2 center = args.vec2("center");
        const double radius = args.number("radius");
        out.addCollider(std::make_unique<DiskCollider>(center, radius, penaltyFrom(args)));
      },
  };
  return spec;
}

}  // namespace particles
