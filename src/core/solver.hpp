#pragma once
// The solver advances a System with one integrator (docs/physics.md §1): doStep(system, dt) calls
// system.derivEval 1, 2 or 4 times, then checks the new state with the explosion guard.

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <particles/errors.hpp>

#include "core/implicit_step.hpp"
#include "core/integrators.hpp"
#include "core/system.hpp"

namespace particles {

// A simulation that blew up: the public particles::SimulationError (include/particles/errors.hpp),
// thrown by doStep. what() names the step, time, integrator and dt and suggests what to change.
SimulationError explosionError(const std::string& reason, long step, double time, Integrator integrator, double dt);

struct ExplosionGuard {
  // Kinetic energy above this multiple of System::energyScale() is runaway. Explosions grow
  // geometrically, so the exact factor barely changes the step at which one is caught, while a
  // sane run stays orders of magnitude below it (a 10 s free fall reaches ~500×).
  double energyFactor = 1e6;
};

class Solver {
 public:
  // The integrator's state is made from its registry row (makeIntegratorState) and lives as long
  // as the solver: a new scenario, or a trial of the stability study, gets a new solver.
  explicit Solver(Integrator integrator, ExplosionGuard guard = {})
      : integrator_(integrator), guard_(guard), state_(makeIntegratorState(integrator)) {}
  Integrator integrator() const { return integrator_; }
  long steps() const { return steps_; }
  // What the last backward Euler or BDF2 step's linear solve did (core/implicit_step.hpp; all
  // zero for the explicit integrators), and the direct path's factorisations so far: benchmarks
  // and tests.
  const ImplicitStepStats& lastImplicitStep() const;
  long factorizations() const;

  // Advances the system's state and time by dt. Throws SimulationError (and leaves the system at
  // the last good state) when the step blows up.
  //
  // The solver is the one owner of simulated time: after k steps of the same dt from t₀ the time
  // is t₀ + k·dt, computed afresh (not summed, which would drift by rounding: 1000 steps of 0.01
  // would not end at 10). A new dt, or a time set from outside, starts a new run of steps there.
  void doStep(System& system, double dt);

 private:
  Integrator integrator_;
  ExplosionGuard guard_;
  std::unique_ptr<IntegratorState> state_;
  Eigen::VectorXd previous_;
  System::StateCheckScratch guardScratch_;
  long steps_ = 0;
  // The current run of equal steps: t = runStart_ + runSteps_ · runDt_.
  double runStart_ = 0.0, runDt_ = 0.0;
  long runSteps_ = 0;
};

// Advances a system with one integrator and time step to given times (the frames of a video, the
// ticks of a --stats file): the time after k steps is t₀ + k·dt, the Solver's.
class Stepper {
 public:
  Stepper(System& system, Integrator integrator, double dt)
      : system_(system), solver_(integrator), dt_(dt), t0_(system.time()) {}
  // One step. Throws SimulationError (the system stays at the last good state).
  void step() { solver_.doStep(system_, dt_); }
  // Steps until the time is the last multiple of dt at or before t (a time within 1e-9 of a step
  // counts as reached).
  void advanceTo(double t);
  // The step count at which advanceTo(t) stops: steps() when t is not ahead.
  long stepsAt(double t) const;
  long steps() const { return solver_.steps(); }
  double elapsed() const { return system_.time() - t0_; }

 private:
  System& system_;
  Solver solver_;
  double dt_, t0_;
};

}  // namespace particles
