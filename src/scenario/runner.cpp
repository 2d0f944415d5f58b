#include "scenario/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace particles::scenario {

Sample sampleOf(const System& system) {
  const EnergyReport e = system.energy();
  return {system.time(),
          e.kinetic,
          e.potential,
          e.total(),
          system.constraintError(system.state()),
          system.penetration(system.state())};
}

RunSummary runScenario(Scenario& scenario, const RunObserver& observer) {
  System& system = scenario.system;
  const SimulationSettings& sim = scenario.simulation;
  const double fps = scenario.render.fps;
  const long steps = sim.steps();
  Stepper stepper(system, sim.integrator, sim.dt);

  RunSummary summary;
  summary.initialEnergy = system.energy();
  summary.worstConstraintError = system.constraintError(system.state());
  summary.worstPenetration = system.penetration(system.state());

  const auto start = std::chrono::steady_clock::now();
  if (observer.onTick) observer.onTick(system);
  long nextTick = 1;
  bool tickedLast = true;
  for (long step = 1; step <= steps; ++step) {
    stepper.step();
    summary.worstConstraintError = std::max(summary.worstConstraintError, system.constraintError(system.state()));
    summary.worstPenetration = std::max(summary.worstPenetration, system.penetration(system.state()));
    // Tick k falls at t0 + k / fps; a tick is due once the step reaches it (to rounding).
    const double elapsed = stepper.elapsed() + 1e-9 * sim.dt;
    tickedLast = false;
    if (double(nextTick) / fps <= elapsed) {
      while (double(nextTick) / fps <= elapsed) ++nextTick;
      if (observer.onTick) observer.onTick(system);
      tickedLast = true;
    }
    if (observer.onStep) observer.onStep(step, steps);
  }
  if (!tickedLast && observer.onTick) observer.onTick(system);
  summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.steps = steps;
  summary.simulatedTime = stepper.elapsed();
  summary.finalEnergy = system.energy();
  return summary;
}

}  // namespace particles::scenario
