#pragma once
// What a particles::Simulation holds (include/particles/simulation.hpp): its own loaded scenario
// (the System it steps), the stepper, what its style keeps of the run, and the names of --trace.
// Shared by simulation.cpp and renderer.cpp.

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <particles/errors.hpp>
#include <particles/simulation.hpp>

#include "core/solver.hpp"
#include "render/errors.hpp"
#include "render/style_history.hpp"
#include "scenario/scenario.hpp"

namespace particles {

struct Simulation::Impl {
  scenario::Scenario scenario;
  Stepper stepper;
  std::atomic<bool> busy{false};
  // The trails and the followed camera of the scenario's style, fed every step from the start, so
  // that Renderer::render draws what `particles render --at` draws; none where the style keeps
  // nothing of the run. Their memory is bounded for the scenario's duration: when it would exceed
  // the trails' limit, historyError says why, and rendering (not stepping) fails with it.
  std::unique_ptr<render::StyleHistory> history;
  std::string historyError;
  // advance()'s clock: the time asked for so far, which the steps reach to within a step. A
  // Neumaier sum (the running total and the rounding it lost), so that a million calls of
  // advance(1 / fps) stay within a few ulps of frames / fps, where render takes its frame times.
  double clock = 0.0, clockError = 0.0;
  // The names of --trace, made on first use (a million-particle cloth has a million of them).
  std::optional<std::vector<std::string>> particleNames, bodyNames;

  explicit Impl(scenario::Scenario loaded)
      : scenario(std::move(loaded)),
        stepper(scenario.system, scenario.simulation.integrator, scenario.simulation.dt),
        clock(scenario.system.time()) {
    if (!render::StyleHistory::needed(scenario.style, scenario.render.view)) return;
    try {
      history = std::make_unique<render::StyleHistory>(
          scenario.style, scenario.render.view, render::Camera{scenario.render.viewCenter, scenario.render.viewHeight},
          scenario.simulation.dt, scenario.simulation.steps());
      history->start(system());
    } catch (const render::OutOfMemory& e) {
      historyError = e.what();
    }
  }

  // One step of dt, fed to the style's history.
  void step() {
    stepper.step();
    if (history) history->afterStep(system());
  }

  // The clock set to where the steps are (after step(), advanceTo(), a stop part-way).
  void clockAtSteps() {
    clock = system().time();
    clockError = 0.0;
  }
  // clock + seconds, summed as Neumaier's compensated sum: {total, its lost rounding}.
  std::pair<double, double> clockPlus(double seconds) const {
    const double total = clock + seconds;
    const double lost = std::abs(clock) >= std::abs(seconds) ? (clock - total) + seconds : (seconds - total) + clock;
    return {total, clockError + lost};
  }

  System& system() { return scenario.system; }
  const System& system() const { return scenario.system; }

  const std::vector<std::string>& names(bool bodies) {
    auto& cache = bodies ? bodyNames : particleNames;
    if (!cache) {
      const Model& model = system().model();
      const int first = bodies ? model.layout.numParticles : 0;
      const int count = bodies ? model.layout.numBodies : model.layout.numParticles;
      cache.emplace();
      cache->reserve(size_t(count));
      for (int p = first; p < first + count; ++p) cache->push_back(scenario::pointName(model, p));
    }
    return *cache;
  }
};


}  // namespace particles
