// The registry of kinds: one line per force, constraint or collider kind a scenario file can
// name. Order matters only for listings (`particles schema`, error messages' "expected one of").
// A new kind: its file pair (class, draw, KindSpec with its build function), one line here, its
// tests and its row in docs/scenarios.md (docs/architecture.md, "Adding a kind").
#include "core/colliders/disk_collider.hpp"
#include "core/colliders/half_plane_collider.hpp"
#include "core/constraints/circular_wire_constraint.hpp"
#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "core/forces/damped_spring_force.hpp"
#include "core/forces/drag_force.hpp"
#include "core/forces/gravity_force.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "core/kind.hpp"

namespace particles {

const std::vector<const KindSpec*>& registeredKinds() {
  static const std::vector<const KindSpec*> kinds = {
      &gravityKind(),
      &dragKind(),
      &springKind(),
      &circularWireKind(),
      &rodKind(),
      &horizontalLineKind(),
      &halfPlaneKind(),
      &diskKind(),
      &mouseKind(),
  };
  return kinds;
}

}  // namespace particles
