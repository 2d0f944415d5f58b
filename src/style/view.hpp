#pragma once
// How the camera moves over a run (docs/scenarios.md, render.view): fixed (the scenario's centre
// and height, as without these keys), fit (holds the named points, or all, over the whole run),
// follow (a point, smoothed by a critically damped spring) or keys (keyframes of the centre and
// height, eased between). Plain data, filled by the scenario loader with the names resolved; the
// camera's path over a run is style/camera_path.hpp's.

#include <string>
#include <vector>

#include "core/state.hpp"

namespace particles::style {

struct CameraKey {
  double t = 0.0;  // s, increasing from key to key
  Vec2 center = Vec2::Zero();
  double height = 3.0;  // world units shown vertically, > 0
};

struct ViewStyle {
  enum class Mode { fixed, fit, follow, keys };
  Mode mode = Mode::fixed;
  // fit: every point of the system (fitAll), or the named ones; a margin of this share of the
  // frame's height is kept around them.
  bool fitAll = false;
  std::vector<std::string> fitNames;  // as written, for messages
  std::vector<int> fitParticles, fitBodies;
  double margin = 0.1;
  // follow: one particle or body (the other index −1), and the smoothing time constant, s (0: locked).
  std::string followName;
  int followParticle = -1, followBody = -1;
  double smoothing = 0.1;
  // keys
  std::vector<CameraKey> keys;
};

}  // namespace particles::style
