#include "core/collisions.hpp"

#include <algorithm>

#include "core/endpoint.hpp"
#include "core/rigid_body.hpp"

namespace particles {

namespace {

// Calls visit(endpoint) for every free particle and every body corner (as a body anchor). A fixed
// particle is skipped here, once for force, energy and penetration alike: it cannot respond to
// the penalty force, so it stores none of its energy and its depth is not a contact.
template <typename Visit>
void forEachCollisionPoint(const Model& model, Visit&& visit) {
  for (int i = 0; i < model.layout.numParticles; ++i) {
    if (!model.isFixed(i)) visit(Endpoint::ofParticle(i));
  }
  for (int j = 0; j < model.layout.numBodies; ++j) {
    for (const Vec2& corner : rectangleCorners(model.bodies[size_t(j)].size)) visit(Endpoint::ofBody(j, corner));
  }
}

}  // namespace

void applyCollisions(const Model& model, const StateView& s, const ColliderList& colliders, ForceAccumulator& acc,
                     WorkerPool* pool) {
  if (colliders.empty()) return;
  auto contactForces = [&](const Endpoint& e) {
    const Vec2 p = endpointPosition(s, e);
    for (const auto& collider : colliders) {
      const auto c = collider->contact(p);
      if (!c) continue;
      const PenaltyParams& k = collider->params();
      Vec2 f = c->normal * (k.k * c->depth * c->depth);
      if (k.damping != 0.0) f -= k.damping * endpointVelocity(s, e).dot(c->normal) * c->normal;
      applyForceAt(s, e, f, acc);
    }
  };
  // A particle's contacts touch its own force only; a body's corners all add to the body's.
  forChunks(pool, size_t(model.layout.numParticles), kPointChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (!model.isFixed(int(i))) contactForces(Endpoint::ofParticle(int(i)));
    }
  });
  for (int j = 0; j < model.layout.numBodies; ++j) {
    for (const Vec2& corner : rectangleCorners(model.bodies[size_t(j)].size))
      contactForces(Endpoint::ofBody(j, corner));
  }
}

void addCollisionJacobians(const Model& model, const StateView& s, const ColliderList& colliders, ForceJacobians& out) {
  if (colliders.empty()) return;
  forEachCollisionPoint(model, [&](const Endpoint& e) {
    const Vec2 p = endpointPosition(s, e);
    const int point = e.point(model.layout);
    for (const auto& collider : colliders) {
      const auto c = collider->contact(p);
      if (!c) continue;
      const PenaltyParams& k = collider->params();
      const Eigen::Matrix2d nn = c->normal * c->normal.transpose();
      ForceJacobians::addBlock(out.dfdx, point, point, (-2.0 * k.k * c->depth) * nn);
      if (k.damping != 0.0) ForceJacobians::addBlock(out.dfdv, point, point, -k.damping * nn);
    }
  });
}

double collisionPotential(const Model& model, const StateView& s, const ColliderList& colliders) {
  if (colliders.empty()) return 0.0;
  double u = 0.0;
  forEachCollisionPoint(model, [&](const Endpoint& e) {
    const Vec2 p = endpointPosition(s, e);
    for (const auto& collider : colliders) {
      if (const auto c = collider->contact(p)) u += collider->params().k * c->depth * c->depth * c->depth / 3.0;
    }
  });
  return u;
}

double maxPenetration(const Model& model, const StateView& s, const ColliderList& colliders) {
  if (colliders.empty()) return 0.0;  // `run` asks after every step
  double worst = 0.0;
  forEachCollisionPoint(model, [&](const Endpoint& e) {
    const Vec2 p = endpointPosition(s, e);
    for (const auto& collider : colliders) {
      if (const auto c = collider->contact(p)) worst = std::max(worst, c->depth);
    }
  });
  return worst;
}

}  // namespace particles
