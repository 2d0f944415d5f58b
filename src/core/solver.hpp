#pragma once
// The solver advances a System with one integrator (DESIGN §1): doStep(system, dt) calls
// system.derivEval 1, 2 or 4 times, then checks the new state with the explosion guard.

#include <stdexcept>
#include <string>

#include "core/integrators.hpp"
#include "core/system.hpp"

namespace particles {

// A simulation that blew up: a non-finite state or runaway kinetic energy. what() names the step,
// time, integrator and dt and suggests what to change.
class SimulationError : public std::runtime_error {
 public:
  SimulationError(const std::string& reason, long step, double time, Integrator integrator, double dt);
  const std::string& reason() const { return reason_; }
  long step() const { return step_; }
  double time() const { return time_; }
  Integrator integrator() const { return integrator_; }
  double dt() const { return dt_; }

 private:
  std::string reason_;
  long step_;
  double time_;
  Integrator integrator_;
  double dt_;
};

struct ExplosionGuard {
  // Kinetic energy above this multiple of System::energyScale() is runaway. Explosions grow
  // geometrically, so the exact factor barely changes the step at which one is caught, while a
  // sane run stays orders of magnitude below it (a 10 s free fall reaches ~500×).
  double energyFactor = 1e6;
};

class Solver {
 public:
  explicit Solver(Integrator integrator, ExplosionGuard guard = {}) : integrator_(integrator), guard_(guard) {}
  Integrator integrator() const { return integrator_; }
  long steps() const { return steps_; }

  // Advances the system's state and time by dt. Throws SimulationError (and leaves the system at
  // the last good state) when the step blows up.
  void doStep(System& system, double dt);

 private:
  Integrator integrator_;
  ExplosionGuard guard_;
  IntegratorScratch scratch_;
  Eigen::VectorXd previous_;
  long steps_ = 0;
};

}  // namespace particles
