#include "render/style_history.hpp"

#include <algorithm>

#include "render/errors.hpp"

namespace particles::render {

namespace {

bool hasTrail(const style::Style& style) {
  return std::any_of(style.select.begin(), style.select.end(), [](const style::Selection& s) { return s.trail; });
}

}  // namespace

bool StyleHistory::needed(const style::Style& style, const style::ViewStyle& view) {
  return hasTrail(style) || view.mode == style::ViewStyle::Mode::follow;
}

// The camera's aspect matters only to the fit mode, which a history does not keep (StyledRun fits).
StyleHistory::StyleHistory(const style::Style& style, const style::ViewStyle& view, const Camera& fixed, double dt,
                           long steps)
    : style_(style), camera_(view, {fixed.center, fixed.height}, 1.0), dt_(dt) {
  try {
    if (hasTrail(style_)) trails_.emplace(style_, dt, steps);
  } catch (const style::TrailLimitError& e) {
    throw OutOfMemory(e.what());
  }
}

void StyleHistory::start(const System& system) {
  startTime_ = system.time();
  camera_.start(system);
  if (trails_) trails_->start(system);
}

void StyleHistory::afterStep(const System& system) {
  camera_.afterStep(system, dt_);
  if (trails_) trails_->afterStep(system);
}

void StyleHistory::advanceTo(Stepper& stepper, System& system, double t) {
  if (!(t > system.time())) return;
  const long target = stepper.stepsAt(t);
  while (stepper.steps() < target) {
    stepper.step();
    afterStep(system);
  }
}

}  // namespace particles::render
