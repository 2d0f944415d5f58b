#include "app/csv_recorder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>

#include "input/printable_text.hpp"
#include "app/exit_codes.hpp"
#include "scenario/runner.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

double CsvRecorder::nominalTime(double t, double fps) {
  if (!std::isfinite(t)) return t;
  // A tick, to the rounding a run of steps accumulates (the runner's own tolerance, 1e-9 of a tick).
  const double ticks = t * fps;
  if (fps > 0 && std::abs(ticks) < 9e15 && std::abs(ticks - std::round(ticks)) <= 1e-9) return std::round(ticks) / fps;
  // Twelve digits, read back; a subnormal time, which the text may not read back as, stays as it is.
  const std::string text = fmt::format("{:.12g}", t);
  double rounded = t;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), rounded);
  return ec == std::errc() && end == text.data() + text.size() ? rounded : t;
}

std::unique_ptr<CsvRecorder> CsvRecorder::open(const System& system, double fps, const std::string& statsPath,
                                               const std::string& tracePath,
                                               const std::vector<std::string>& traceOnly) {
  std::unique_ptr<CsvRecorder> owner(new CsvRecorder());
  CsvRecorder& r = *owner;
  r.fps_ = fps;
  const Model& model = system.model();
  std::vector<std::string> all;
  for (int p = 0; p < model.layout.numPoints(); ++p) all.push_back(scenario::pointName(model, p));
  if (traceOnly.empty()) {
    for (int p = 0; p < model.layout.numPoints(); ++p) r.points_.push_back(p);
  }
  for (const std::string& name : traceOnly) {
    const auto it = std::find(all.begin(), all.end(), name);
    if (it == all.end()) {
      throw InputError(
          fmt::format("--trace-only: nothing in the scenario is named {} (names are spelled as in the trace: bob, "
                      "cloth[3][4], link0, #7)",
                      input::quotedValue(name)));
    }
    r.points_.push_back(int(it - all.begin()));
  }
  for (int p : r.points_) r.names_.push_back(all[size_t(p)]);

  if (!statsPath.empty()) {
    r.stats_.emplace(statsPath);
    r.stats_->write("t,kinetic,potential,total,constraint_error,penetration\n");
  }
  if (!tracePath.empty()) {
    r.trace_.emplace(tracePath);
    r.trace_->write("t,name,x,y,vx,vy,angle,omega\n");
  }
  return owner;
}

void CsvRecorder::record(const System& system) {
  fmt::memory_buffer buffer;
  if (stats_) {
    const scenario::Sample x = scenario::sampleOf(system);
    fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{}\n", nominalTime(x.t, fps_), x.kinetic, x.potential,
                   x.total, x.constraintError, x.penetration);
    stats_->write({buffer.data(), buffer.size()});
  }
  if (trace_) {
    const double t = nominalTime(system.time(), fps_);
    const StateView v = system.view();
    const int numParticles = system.layout().numParticles;
    buffer.clear();
    for (size_t k = 0; k < points_.size(); ++k) {
      const int p = points_[k];
      const Vec2 x = v.pos(p), u = v.vel(p);
      const double angle = p < numParticles ? 0.0 : v.angle(p - numParticles);
      const double omega = p < numParticles ? 0.0 : v.omega(p - numParticles);
      fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{},{},{}\n", t, names_[k], x.x(), x.y(), u.x(), u.y(),
                     angle, omega);
    }
    trace_->write({buffer.data(), buffer.size()});
  }
}

void CsvRecorder::commit() {
  if (stats_) stats_->commit();
  if (trace_) trace_->commit();
}

}  // namespace particles::app
