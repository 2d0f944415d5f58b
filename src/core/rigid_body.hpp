#pragma once
// Rigid rectangles (docs/physics.md §7): uniform density, centre of mass at the centre, orientation θ
// counter-clockwise. Their kinematics at anchors live in endpoint.hpp.

#include <array>

#include "core/state.hpp"

namespace particles {

// I = m (w² + h²) / 12 for a w × h rectangle about its centre. (The report prints m w h / 12,
// which is not a moment of inertia; tests check this one against an area integral.)
inline double rectangleInertia(double mass, const Vec2& size) {
  return mass * (size.x() * size.x() + size.y() * size.y()) / 12.0;
}

// Corners in body coordinates, counter-clockwise from (−w/2, −h/2).
inline std::array<Vec2, 4> rectangleCorners(const Vec2& size) {
  const Vec2 h = 0.5 * size;
  return {Vec2(-h.x(), -h.y()), Vec2(h.x(), -h.y()), Vec2(h.x(), h.y()), Vec2(-h.x(), h.y())};
}

}  // namespace particles
