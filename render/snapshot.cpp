#include "render/snapshot.hpp"

#include <algorithm>

#include "core/constraints/circular_wire_constraint.hpp"
#include "core/forces/damped_spring_force.hpp"
#include "core/colliders/disk_collider.hpp"
#include "core/endpoint.hpp"
#include "core/colliders/half_plane_collider.hpp"
#include "core/constraints/horizontal_line_constraint.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "core/constraints/rod_constraint.hpp"
#include "core/system.hpp"

namespace particles::render {

FrameSnapshot snapshotOf(const System& system) {
  const StateView s = system.view();
  const Model& model = system.model();
  const StateLayout& layout = system.layout();
  FrameSnapshot f;
  f.time = system.time();

  f.particles.reserve(size_t(layout.numParticles));
  f.particleFixed.reserve(size_t(layout.numParticles));
  for (int i = 0; i < layout.numParticles; ++i) {
    f.particles.push_back(s.pos(i));
    f.particleFixed.push_back(model.isFixed(i) ? 1 : 0);
  }
  for (int j = 0; j < layout.numBodies; ++j) {
    f.bodies.push_back({s.pos(layout.bodyPoint(j)), s.angle(j), model.bodies[size_t(j)].size});
  }

  for (const auto& force : system.forces()) {
    if (const auto* springs = dynamic_cast<const DampedSpringForce*>(force.get())) {
      f.springs.reserve(f.springs.size() + springs->size());
      for (size_t i = 0; i < springs->size(); ++i) {
        const SpringSpec spec = springs->spring(i);
        f.springs.push_back({endpointPosition(s, spec.a), endpointPosition(s, spec.b), springs->strain(s, i)});
      }
    } else if (const auto* mouse = dynamic_cast<const MouseSpringForce*>(force.get())) {
      if (mouse->activeAt(f.time)) {
        f.mice.push_back({mouse->target(f.time), endpointPosition(s, mouse->script().grab)});
      }
    }
  }

  // The cloth puts one rail constraint on each of its 25 top particles: draw each line once.
  for (const auto& constraint : system.constraints()) {
    if (const auto* rod = dynamic_cast<const RodConstraint*>(constraint.get())) {
      f.rods.push_back({s.pos(rod->a()), s.pos(rod->b())});
    } else if (const auto* wire = dynamic_cast<const CircularWireConstraint*>(constraint.get())) {
      const bool seen = std::any_of(f.wires.begin(), f.wires.end(), [&](const WireCircle& w) {
        return w.center == wire->center() && w.radius == wire->radius();
      });
      if (!seen) f.wires.push_back({wire->center(), wire->radius()});
    } else if (const auto* line = dynamic_cast<const HorizontalLineConstraint*>(constraint.get())) {
      const bool seen =
          std::any_of(f.rails.begin(), f.rails.end(), [&](const Rail& r) { return r.height == line->height(); });
      if (!seen) f.rails.push_back({line->height()});
    }
  }

  for (const auto& collider : system.colliders()) {
    if (const auto* plane = dynamic_cast<const HalfPlaneCollider*>(collider.get())) {
      f.halfPlanes.push_back({plane->normal(), plane->offset()});
    } else if (const auto* disk = dynamic_cast<const DiskCollider*>(collider.get())) {
      f.disks.push_back({disk->center(), disk->radius()});
    }
  }
  return f;
}

}  // namespace particles::render
