#pragma once
// Where the camera looks at each frame of a run (style/view.hpp's modes):
//   fixed   the scenario's render.view centre and height;
//   fit     the box that holds the chosen points at every frame of the output, found by a pass over
//           those frames before the first is drawn (observe), grown by the margin and to the frame's
//           aspect;
//   follow  a point, through a critically damped spring of time constant τ = smoothing:
//             c̈ = ω² (p − c) − 2 ω ċ,   ω = 1 / τ,
//           advanced after every time step by its exact solution with p held over the step
//             e = c − p,  e(h) = (e + (ċ + ω e) h) e^{−ω h},  ċ(h) = (ċ − ω (ċ + ω e) h) e^{−ω h},
//           which is stable for any step and has no overshoot; τ = 0 locks the camera on the point.
//           It starts on the point, at rest, at the run's first state;
//   keys    keyframes of the centre and height; between two keys the centre moves and the height
//           zooms (geometrically) along smoothstep(s) = 3s² − 2s³, at rest at each key.
// Every mode depends only on the run's states, never on which frames are drawn: a split render
// (--frames A:B) steps from the start through the same states and gets the whole render's camera.

#include "core/drawing.hpp"
#include "core/system.hpp"
#include "style/view.hpp"

namespace particles::style {

struct CameraPlacement {
  Vec2 center = Vec2::Zero();
  double height = 3.0;  // world units shown vertically
};

class CameraPath {
 public:
  // `fixed` is the scenario's centre and height; aspect is the frame's width over its height.
  CameraPath(const ViewStyle& view, const CameraPlacement& fixed, double aspect);

  // fit: the frames to hold, each once, before start().
  bool needsPass() const { return view_.mode == ViewStyle::Mode::fit; }
  void observe(const Drawing& frame);
  void endPass();

  // follow: the run's first state, then the state after every step.
  void start(const System& system);
  void afterStep(const System& system, double dt);

  // The camera at the frame of time t (the state the run has reached).
  CameraPlacement at(double t) const;

 private:
  Vec2 followedPoint(const System& system) const;

  ViewStyle view_;
  CameraPlacement fixed_;
  double aspect_;
  // fit: the box seen so far
  Vec2 boxLo_, boxHi_;
  bool boxEmpty_ = true;
  CameraPlacement fitted_;
  // follow: the camera's centre and its velocity
  Vec2 center_ = Vec2::Zero(), velocity_ = Vec2::Zero();
};

}  // namespace particles::style
