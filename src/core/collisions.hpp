#pragma once
// Penalty collision response for every collider against every free particle and every corner
// of every rigid rectangle (docs/physics.md §2 stage 3, §6, §7). Fixed particles are no contacts: no
// force, no energy, no penetration.

#include <memory>
#include <vector>

#include "core/collider.hpp"
#include "core/force_accumulator.hpp"
#include "core/force_jacobians.hpp"
#include "core/model.hpp"
#include "core/worker_pool.hpp"

namespace particles {

using ColliderList = std::vector<std::unique_ptr<Collider>>;

// The particles' forces are added in chunks of particles on `pool` (each particle's contacts in
// collider order, as a serial loop adds them), the bodies' corners after, on the calling thread.
void applyCollisions(const Model& model, const StateView& s, const ColliderList& colliders, ForceAccumulator& acc,
                     WorkerPool* pool = nullptr);
// The penalty's Jacobians for backward Euler, per contact: ∂f/∂x = −2 k d n nᵀ (d grows as the
// point moves against n) and ∂f/∂v = −c n nᵀ; the turning of a disk's normal with position is
// left out (it is positive, so it would break the SPD matrix, and it vanishes at the surface).
// Corners of bodies couple through the body's centre; their rotation is explicit.
void addCollisionJacobians(const Model& model, const StateView& s, const ColliderList& colliders, ForceJacobians& out);
// Σ k d³/3 over all contacts, joules.
double collisionPotential(const Model& model, const StateView& s, const ColliderList& colliders);
// The largest penetration depth of any free particle or corner, metres (0 when nothing touches).
double maxPenetration(const Model& model, const StateView& s, const ColliderList& colliders);

}  // namespace particles
