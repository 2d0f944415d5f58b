#include "core/endpoint.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace particles {

void checkEndpoint(const StateLayout& layout, const Endpoint& e, const char* what) {
  const bool ok = e.isParticle() ? (e.particle >= 0 && e.particle < layout.numParticles)
                                 : (e.body < layout.numBodies);
  if (!ok) {
    throw std::invalid_argument(std::string(what) + ": " + (e.isParticle() ? "particle " : "body ") +
                                std::to_string(e.isParticle() ? e.particle : e.body) + " does not exist");
  }
}

Vec2 worldOffset(const StateView& s, const Endpoint& e) {
  if (e.isParticle()) return Vec2::Zero();
  const double c = std::cos(s.angle(e.body));
  const double sn = std::sin(s.angle(e.body));
  return {c * e.anchor.x() - sn * e.anchor.y(), sn * e.anchor.x() + c * e.anchor.y()};
}

Vec2 endpointPosition(const StateView& s, const Endpoint& e) {
  const int p = e.point(s.layout());
  return s.pos(p) + worldOffset(s, e);
}

Vec2 endpointVelocity(const StateView& s, const Endpoint& e) {
  const int p = e.point(s.layout());
  if (e.isParticle()) return s.vel(p);
  const Vec2 r = worldOffset(s, e);
  return s.vel(p) + s.omega(e.body) * Vec2(-r.y(), r.x());
}

void applyForceAt(const StateView& s, const Endpoint& e, const Vec2& f, ForceAccumulator& acc) {
  acc.addForce(e.point(s.layout()), f);
  if (e.isParticle()) return;
  const Vec2 r = worldOffset(s, e);
  acc.torque[e.body] += r.x() * f.y() - r.y() * f.x();
}

}  // namespace particles
