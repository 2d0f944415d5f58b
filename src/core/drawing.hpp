#pragma once
// What a system shows of itself at one instant: plain geometry in world units, filled in by the
// system (particles, bodies) and by each force, constraint and collider kind (its draw method), so
// that the renderer needs no knowledge of the kinds. The renderer chooses colours and widths by
// the list a shape is in, and draws the lists in a fixed order, back to front:
//   obstacles (half-planes, disks) → guides (circles, lines) → springs → rods → bodies →
//   particles → cursors.
// A new kind draws itself by adding to these lists; a new list is a change to the renderer.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/state.hpp"

namespace particles {

// The largest frame side in pixels a drawing is rendered at: OSMesa's largest buffer
// (OSMESA_MAX_WIDTH/HEIGHT) in Mesa 22, which EGL's framebuffer there takes too (16384 × 16 and
// 16 × 16384 drawn). Here, below both, so that the renderer (render::RenderOptions, images read
// back) and the scenario loader (render.size, a golden manifest's size) hold to one bound.
inline constexpr int kMaxImageSide = 16384;
// The most frames a second of simulated time is drawn in: a scenario's render.fps, render's --fps.
inline constexpr int kMaxFps = 1000;

// What a style colours by or draws arrows of (style/quantity.hpp), beyond the geometry: filled by
// System::draw only when asked (DrawDetail), since a plain frame needs none of it and the
// accelerations cost one evaluation of the forces.
struct DrawDetail {
  bool velocities = false;     // Drawing::particleVelocities, bodyVelocities, bodyAngularVelocities
  bool accelerations = false;  // Drawing::particleAccelerations, bodyAccelerations (System::addAccelerations)
  bool masses = false;         // Drawing::particleMasses, bodyMasses
  bool any() const { return velocities || accelerations || masses; }
};

// How System::draw gives the springs: each with its ends' positions and strain (Drawing::springs),
// or, where every spring joins two particles, by index (Drawing::springTopology), for a renderer
// that keeps them on the GPU (render/resident_program.hpp).
enum class SpringDetail { positions, topology };

struct Drawing {
  struct Spring {   // a spring, coloured by strain (or, with a style, by tension or energy)
    Vec2 a, b;      // world positions of the ends (anchors on bodies included)
    double strain;  // |l| / rest − 1: negative compressed, 0 at rest, positive stretched
    double rest = 0.0;       // rest length, m
    double stiffness = 0.0;  // ks, N/m
  };
  struct Segment {  // a rigid link (rods)
    Vec2 a, b;
  };
  struct Circle {  // a circular guide, outline only (wires)
    Vec2 center;
    double radius;
  };
  struct Line {       // a straight guide across the whole view (rails)
    Vec2 point;       // any point on it
    Vec2 direction;   // unit
  };
  struct HalfPlane {  // a solid obstacle filling normal·p < offset
    Vec2 normal;      // unit, towards the free side
    double offset;
  };
  struct Disk {  // a solid round obstacle
    Vec2 center;
    double radius;
  };
  struct Box {  // a rigid rectangle
    Vec2 center;
    double angle;  // rad, counter-clockwise
    Vec2 size;     // full width and height
  };
  // The springs by their ends, for a renderer that keeps a scene's topology on the GPU and sends
  // only positions each frame (render/resident_program.hpp): the springs `springs` would hold,
  // in the same order. System::draw gives it (SpringDetail::topology) when every spring joins two
  // particles; it is then the same object from frame to frame, since a system's springs never
  // change, and `springs` stays empty.
  struct SpringTopology {
    std::vector<std::uint32_t> ends;  // two particle indices per spring: a, b
    std::vector<double> rest;         // rest lengths; strain |l| / rest − 1, 0 where rest is 0
    std::vector<double> stiffness;    // ks, N/m, per spring
  };
  struct Cursor {  // a scripted mouse while it holds its point
    Vec2 target;   // where the cursor is
    Vec2 grabbed;  // the point it pulls
  };

  double time = 0.0;                // s
  std::vector<Vec2> particles;      // positions, in particle order
  std::vector<char> particleFixed;  // 1 for a fixed particle, same length as particles
  std::vector<Box> bodies;
  std::vector<Spring> springs;
  std::shared_ptr<const SpringTopology> springTopology;  // null unless asked for and possible
  std::vector<Segment> rods;
  std::vector<Circle> guideCircles;
  std::vector<Line> guideLines;
  std::vector<HalfPlane> halfPlanes;
  std::vector<Disk> disks;
  std::vector<Cursor> cursors;
  // Filled only as DrawDetail asks, else empty; one entry per particle or body.
  std::vector<Vec2> particleVelocities;     // m/s
  std::vector<Vec2> particleAccelerations;  // m/s²: every force and constraint force over the mass
  std::vector<double> particleMasses;       // kg
  std::vector<double> bodyMasses;           // kg
  std::vector<Vec2> bodyVelocities;         // of the centre of mass, m/s
  std::vector<double> bodyAngularVelocities;  // rad/s, counter-clockwise
  std::vector<Vec2> bodyAccelerations;      // of the centre of mass, m/s²

  // Empties every list, keeping its storage.
  void clear();
  // How many springs come by index (springTopology's), 0 without a topology.
  size_t springsByIndex() const { return springTopology ? springTopology->rest.size() : 0; }

  // Guides are drawn once however many constraints share them (the cloth puts one rail
  // constraint on each of its top particles): these skip an exact duplicate.
  void addGuideCircle(const Circle& c);
  void addGuideLine(const Line& l);
};

}  // namespace particles
