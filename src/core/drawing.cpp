#include "core/drawing.hpp"

#include <algorithm>

namespace particles {

void Drawing::clear() {
  time = 0.0;
  particles.clear();
  particleFixed.clear();
  bodies.clear();
  springs.clear();
  springTopology.reset();
  rods.clear();
  guideCircles.clear();
  guideLines.clear();
  halfPlanes.clear();
  disks.clear();
  cursors.clear();
  particleVelocities.clear();
  particleAccelerations.clear();
  particleMasses.clear();
  bodyMasses.clear();
  bodyVelocities.clear();
  bodyAngularVelocities.clear();
  bodyAccelerations.clear();
}

void Drawing::addGuideCircle(const Circle& c) {
  const bool seen = std::any_of(guideCircles.begin(), guideCircles.end(),
                                [&](const Circle& o) { return o.center == c.center && o.radius == c.radius; });
  if (!seen) guideCircles.push_back(c);
}

void Drawing::addGuideLine(const Line& l) {
  const bool seen = std::any_of(guideLines.begin(), guideLines.end(),
                                [&](const Line& o) { return o.point == l.point && o.direction == l.direction; });
  if (!seen) guideLines.push_back(l);
}

}  // namespace particles
