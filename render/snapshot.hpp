#pragma once
// What the renderer draws, copied out of a System at one instant (DESIGN §1: "Frame snapshot").
// Plain data in world units: the renderer never sees the System, so a frame can be drawn on
// another thread, stored, or built by hand in a test.
//
// snapshotOf() recognises the force, constraint and collider kinds of the core by type; a kind it
// does not know is simply not drawn.

#include <vector>

#include "core/state.hpp"

namespace particles {
class System;
}

namespace particles::render {

struct SpringSegment {
  Vec2 a, b;      // world positions of the two ends (anchors on bodies included)
  double strain;  // |l| / rest − 1: negative compressed, 0 at rest, positive stretched
};

struct RodSegment {
  Vec2 a, b;
};

struct WireCircle {  // circular-wire constraint (drawn once per distinct circle)
  Vec2 center;
  double radius;
};

struct Rail {  // horizontal-line constraint y = height (drawn once per distinct height)
  double height;
};

struct BodyBox {  // rigid rectangle
  Vec2 center;
  double angle;  // rad, counter-clockwise
  Vec2 size;     // full width and height
};

struct HalfPlaneShape {  // solid where normal·p < offset (HalfPlaneCollider's convention)
  Vec2 normal;           // unit
  double offset;
};

struct DiskShape {
  Vec2 center;
  double radius;
};

struct MouseCursor {  // a scripted mouse while it holds its point
  Vec2 target;        // m(t), where the cursor is
  Vec2 grabbed;       // the point it pulls
};

struct FrameSnapshot {
  double time = 0.0;                // s
  std::vector<Vec2> particles;      // positions, in particle order
  std::vector<char> particleFixed;  // 1 for a fixed particle, same length as particles
  std::vector<BodyBox> bodies;
  std::vector<SpringSegment> springs;
  std::vector<RodSegment> rods;
  std::vector<WireCircle> wires;
  std::vector<Rail> rails;
  std::vector<HalfPlaneShape> halfPlanes;
  std::vector<DiskShape> disks;
  std::vector<MouseCursor> mice;  // only the mice active at `time`
};

// The system's current state and time as a snapshot.
FrameSnapshot snapshotOf(const System& system);

}  // namespace particles::render
