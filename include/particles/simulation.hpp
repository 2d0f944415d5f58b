#pragma once
/// @file
/// A simulation made from a scenario: steps its system with the scenario's integrator and time step,
/// and reads and changes its state. Stepping gives the same bits as `particles run` for the same
/// scenario, whatever the thread count.
///
/// @code
/// particles::Simulation sim(particles::Scenario::load("scenarios/cloth.yaml"));
/// sim.advance(1.0);                                   // one simulated second
/// particles::Point p = sim.position(sim.particleIndex("cloth[0][0]"));
/// @endcode
///
/// A Simulation is driven by one thread at a time: a call that steps or changes it while another
/// thread's call is under way throws particles::Error (it never races). Reading while another
/// thread steps is not checked; do not.

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <particles/choices.hpp>
#include <particles/export.hpp>

namespace particles {

class Scenario;

/// A point or a vector in the plane: a particle's position (m) or velocity (m/s).
struct Point {
  double x = 0.0;  ///< m, or m/s for a velocity
  double y = 0.0;  ///< m, or m/s for a velocity
};

/// A rigid body's centre of mass, orientation and spin.
struct BodyState {
  double x = 0.0;      ///< the centre of mass, m
  double y = 0.0;      ///< the centre of mass, m
  double angle = 0.0;  ///< rad, counter-clockwise
  double omega = 0.0;  ///< rad/s
};

/// The system's energy now, as `particles run --stats` writes it.
struct Energy {
  double kinetic = 0.0;    ///< J
  double potential = 0.0;  ///< J: gravity, springs, the mouse's spring, the colliders' penalty
  double total = 0.0;      ///< J
};

/// The thread count `particles run` takes without `--threads`: the environment variable
/// PARTICLES_THREADS when set, else the CPUs this process may use (its affinity mask and cgroup
/// quota). Throws ArgumentError for a PARTICLES_THREADS that is not a whole number from 1 to 1024.
PARTICLES_API int defaultThreads();

/// A simulation made from a scenario: its system, stepped with the scenario's integrator and time
/// step, whose state can be read and changed. Moved, never copied; driven by one thread at a time.
class PARTICLES_API Simulation {
 public:
  /// A new system built from the scenario as it is now (later set()s on it do not reach this
  /// simulation), at t = 0, stepping on `threads` threads (1 to 1024; the bits are the same for
  /// every count). Throws ScenarioError for a scenario that cannot be built, ArgumentError for a
  /// bad thread count.
  explicit Simulation(const Scenario& scenario, int threads = 1);
  /// Takes over other's system; other may then only be destroyed or assigned to.
  Simulation(Simulation&& other) noexcept;
  /// Takes over other's system; other may then only be destroyed or assigned to.
  Simulation& operator=(Simulation&& other) noexcept;
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;
  ~Simulation();

  /// n steps of dt (n ≥ 0). Throws SimulationError when a step blows up: the simulation stays at
  /// the last good state.
  void step(long n = 1);
  /// Moves the simulation's clock on by `seconds` (finite, ≥ 0) and steps to the last multiple of
  /// dt at or before it. The clock keeps what a step could not cover: advance(1.0 / fps) once per
  /// frame lands frame k on the step `particles render` draws at t = k / fps, whatever dt is (with
  /// dt = 0.005, 90 calls of 1/30 end at t = 3.0 s, not 2.7). step() and advanceTo() set the clock
  /// to the time they reach.
  void advance(double seconds);
  /// Steps to the last multiple of dt at or before t (finite, not behind time()): the step
  /// `particles render` draws at t, so advanceTo(k / fps) gives its frame k exactly.
  void advanceTo(double t);
  /// Asked before each step of the calls below that take it: false stops the call there.
  using KeepGoing = std::function<bool()>;
  /// @name Stepping that can be stopped
  //@{
  /// step(), advance() and advanceTo(), asking keepGoing() before each step: when it returns false
  /// the call stops there, at a whole step, and returns false (true when every step was taken). For
  /// a caller that must be able to stop a long call: a GUI's cancel button, Python's Ctrl-C. The
  /// steps taken are the same bits as without it. An exception keepGoing throws passes through as
  /// it is.
  bool step(long n, const KeepGoing& keepGoing);
  bool advance(double seconds, const KeepGoing& keepGoing);
  bool advanceTo(double t, const KeepGoing& keepGoing);
  //@}
  double time() const;            ///< s: t₀ + k·dt after k steps, computed afresh (no drift from summing)
  long steps() const;             ///< steps taken since the simulation was made
  double dt() const;              ///< the time step, s
  Integrator integrator() const;  ///< the scenario's integrator

  void setThreads(int threads);  ///< 1 to 1024; the bits stay the same
  int threads() const;           ///< the threads it steps on

  int particleCount() const;  ///< particles in the system
  int bodyCount() const;      ///< rigid bodies in the system

  /// @name The state without a copy
  //@{
  /// The particles' positions and velocities as they are in the state: 2 × particleCount()
  /// doubles, x₀ y₀ x₁ y₁ …. The span stays valid, and follows the state, for as long as the
  /// simulation lives (stepping writes into the same memory); not after it is destroyed or moved
  /// from.
  std::span<const double> positions() const;
  std::span<const double> velocities() const;
  //@}
  Point position(int particle) const;     ///< m; throws ArgumentError for an index out of range
  Point velocity(int particle) const;     ///< m/s; throws ArgumentError for an index out of range
  BodyState body(int body) const;         ///< throws ArgumentError for an index out of range
  std::vector<BodyState> bodies() const;  ///< every rigid body, in the scenario's order

  Energy energy() const;           ///< kinetic, potential and total, J
  double constraintError() const;  ///< m: the largest violation of a constraint now
  double penetration() const;      ///< m: the deepest a point is inside a collider now

  /// The names `particles run --trace` writes: the scenario's names, `cloth[3][4]` for a grid's
  /// particle, `#7` for an unnamed particle.
  std::vector<std::string> particleNames() const;
  /// The bodies' names: the scenario's, `body#2` for an unnamed body.
  std::vector<std::string> bodyNames() const;
  /// The index of a particle's name; throws ArgumentError naming the closest name when there is
  /// none.
  int particleIndex(std::string_view name) const;
  /// The index of a body's name; throws ArgumentError naming the closest name when there is none.
  int bodyIndex(std::string_view name) const;

  /// Moves a particle where the next step starts (constraints are not projected: the next step's
  /// constraint forces pull it back). Finite values only.
  void setPosition(int particle, Point position);
  /// Sets a particle's velocity where the next step starts. Finite values only.
  void setVelocity(int particle, Point velocity);

  /// The scenario's mice (its `mouse` section, in order): springs that pull a grabbed point towards
  /// a target along a scripted path. A scenario without one can be given one with
  /// Scenario::set("mouse", "[{grab: ..., ...}]").
  int mouseCount() const;
  /// Takes a mouse over: from now on it holds its point at `target` (finite), its path and time
  /// window replaced, until releaseMouse() lets go.
  void setMouseTarget(Point target, int mouse = 0);
  /// Lets go of the mouse's point: it pulls no more, and mouseTarget() is nothing.
  void releaseMouse(int mouse = 0);
  /// Where the mouse pulls now; nothing while it holds no point (outside its window, released).
  std::optional<Point> mouseTarget(int mouse = 0) const;

  struct Impl;  ///< the library's own, opaque here

 private:
  std::unique_ptr<Impl> impl_;
  friend class Renderer;  ///< draws the state
};

}  // namespace particles
