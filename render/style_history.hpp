#pragma once
// What a style keeps of a run's states (render/styled_run.hpp): the followed camera and the trails,
// fed the run's first state and then the state after every time step. They depend only on the
// states, never on the frames' size, theme or times, so one history serves every frame drawn of the
// run: `particles render` and a golden check keep one in their StyledRun, and the library's
// Simulation keeps one of its own from its start (src/api/simulation_impl.hpp), which each
// Renderer::render draws from with its own settings.

#include "core/solver.hpp"
#include "core/system.hpp"
#include "render/render_options.hpp"
#include "style/camera_path.hpp"
#include "style/style.hpp"
#include "style/trail_history.hpp"
#include "style/view.hpp"

#include <optional>

namespace particles::render {

class StyleHistory {
 public:
  // Whether `style` and `view` keep anything of the run (a trail, a followed camera); without, a
  // run needs no history and its stepping does no more than without a style.
  static bool needed(const style::Style& style, const style::ViewStyle& view);

  // `fixed` is the scenario's view; `dt` and `steps` the run's, which bound the trails' memory:
  // OutOfMemory (render/errors.hpp) names the selection whose trails would exceed
  // style::kMaxTrailSamples.
  StyleHistory(const style::Style& style, const style::ViewStyle& view, const Camera& fixed, double dt, long steps);
  // The trails point into the history's own copy of the style.
  StyleHistory(const StyleHistory&) = delete;
  StyleHistory& operator=(const StyleHistory&) = delete;

  // The run's first state, then the state after every step.
  void start(const System& system);
  void afterStep(const System& system);
  // Steps `stepper` to time t, feeding every step (nothing when t is not after the system's time).
  void advanceTo(Stepper& stepper, System& system, double t);

  // The followed camera's path (the other modes keep nothing of the run).
  const style::CameraPath& camera() const { return camera_; }
  // The trails, or null when the style has none.
  const style::TrailHistory* trails() const { return trails_ ? &*trails_ : nullptr; }
  // The time of the run's first state: a whole-run trail fades from there.
  double startTime() const { return startTime_; }

 private:
  style::Style style_;
  style::CameraPath camera_;
  std::optional<style::TrailHistory> trails_;
  double dt_;
  double startTime_ = 0.0;
};

}  // namespace particles::render
