#pragma once
// The paths of the points a style gives a trail (style/style.hpp's Selection::trail): each
// selected particle's or body centre's position after every time step, so that a trail is as
// smooth as the simulation, kept for the trail's `seconds` (or the whole run). Like the camera
// (style/camera_path.hpp), it depends only on the run's states: a split render steps through the
// same states from the start and draws the whole render's trails.
//
// Memory is bounded before the run starts: the samples a run can hold at once (points × steps in
// the longest window) must stay within kMaxTrailSamples, else the constructor throws
// TrailLimitError naming the limit.

#include <cstddef>
#include <deque>
#include <stdexcept>
#include <vector>

#include "core/system.hpp"
#include "style/style.hpp"

namespace particles::style {

// Samples (a time and a position, 24 bytes) all trails may hold at once: 16 million, 384 MB.
inline constexpr long long kMaxTrailSamples = 16'000'000;

class TrailLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class TrailHistory {
 public:
  struct Sample {
    double t;
    Vec2 p;
  };
  // One trail: a point (particle or body) and its style.
  struct Trail {
    int particle = -1, body = -1;
    const TrailStyle* style = nullptr;
    size_t selection = 0;  // its index in Style::select, for the colour it takes
    std::deque<Sample> samples;
  };

  // The trails of `style`'s selections, for a run of `steps` steps of `dt` from its start.
  TrailHistory(const Style& style, double dt, long steps);
  bool empty() const { return trails_.empty(); }
  // The run's first state, then the state after every step.
  void start(const System& system) { record(system); }
  void afterStep(const System& system) { record(system); }
  const std::vector<Trail>& trails() const { return trails_; }

 private:
  void record(const System& system);
  std::vector<Trail> trails_;
};

}  // namespace particles::style
