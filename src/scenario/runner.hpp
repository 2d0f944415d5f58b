#pragma once
// Running a loaded scenario for its duration with its integrator and time step, sampling what
// `particles run --stats` reports (docs/physics.md §12). Shared by the program and the tests, so that the
// numbers a test bounds are the numbers a user sees.

#include <functional>

#include "scenario/scenario.hpp"
#include "core/solver.hpp"

namespace particles::scenario {

// One --stats row: energies (J), the worst constraint violation and penetration (m) right now.
struct Sample {
  double t = 0.0;
  double kinetic = 0.0;
  double potential = 0.0;
  double total = 0.0;
  double constraintError = 0.0;
  double penetration = 0.0;
};
Sample sampleOf(const System& system);

struct RunObserver {
  // At t = 0, at every tick k / fps of the render rate, and at the end.
  std::function<void(const System&)> onTick;
  // After every step (for progress displays).
  std::function<void(long step, long steps)> onStep;
};

struct RunSummary {
  long steps = 0;
  double simulatedTime = 0.0;         // s
  double wallSeconds = 0.0;           // s
  double worstConstraintError = 0.0;  // m, over every step
  double worstPenetration = 0.0;      // m, over every step
  EnergyReport initialEnergy, finalEnergy;
};

// Steps the scenario's system from its current state for simulation.steps() steps. Throws
// SimulationError when it blows up (the system is then left at the last good state).
RunSummary runScenario(Scenario& scenario, const RunObserver& observer = {});

}  // namespace particles::scenario
