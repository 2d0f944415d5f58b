// particles::Simulation: see include/particles/simulation.hpp.
#include <particles/simulation.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "api/exclusive_use.hpp"
#include "input/printable_text.hpp"
#include "api/guarded_call.hpp"
#include "api/scenario_impl.hpp"
#include "api/simulation_impl.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "core/solver.hpp"
#include "core/worker_pool.hpp"
#include "input/closest_name.hpp"
#include "input/default_threads.hpp"
#include "scenario/runner.hpp"

namespace particles {

namespace {

void checkThreads(std::string_view call, int threads) {
  if (threads < 1 || threads > kMaxThreads) {
    throw ArgumentError(fmt::format("{}: threads must be 1 to {}, got {}", call, kMaxThreads, threads));
  }
}

}  // namespace


namespace {


Simulation::Impl& implOf(const std::unique_ptr<Simulation::Impl>& impl, std::string_view call) {
  if (!impl) throw ArgumentError(fmt::format("Simulation::{}: this Simulation was moved from", call));
  return *impl;
}

void checkIndex(std::string_view call, std::string_view what, int index, int count) {
  if (index < 0 || index >= count) {
    throw ArgumentError(count == 0 ? fmt::format("Simulation::{}: {} {} out of range: the scenario has none", call,
                                                 what, index)
                                   : fmt::format("Simulation::{}: {} {} out of range 0 to {}", call, what, index,
                                                 count - 1));
  }
}

void checkFinite(std::string_view call, Point p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
    throw ArgumentError(fmt::format("Simulation::{}: expected finite values, got ({}, {})", call, p.x, p.y));
  }
}

}  // namespace

int defaultThreads() {
  return api::guardedCall("defaultThreads", [] {
    try {
      return input::defaultThreads(kMaxThreads);
    } catch (const input::BadThreadCount& e) {
      throw ArgumentError(e.what());
    }
  });
}

Simulation::Simulation(const Scenario& scenario, int threads) {
  impl_ = api::guardedCall("Simulation", [&] {
    checkThreads("Simulation", threads);
    if (!scenario.impl_) throw ArgumentError("Simulation: the Scenario was moved from");
    auto impl = std::make_unique<Impl>(scenario.impl_->load());
    impl->system().setThreads(threads);
    return impl;
  });
}
Simulation::Simulation(Simulation&& other) noexcept = default;
Simulation& Simulation::operator=(Simulation&& other) noexcept = default;
Simulation::~Simulation() = default;

void Simulation::step(long n) { step(n, KeepGoing()); }
void Simulation::advance(double seconds) { advance(seconds, KeepGoing()); }
void Simulation::advanceTo(double t) {
  advanceTo(t, KeepGoing());
}

namespace {

// Asks the caller's keepGoing before each step; an exception it throws is kept, to pass through
// the API boundary as it is (guardedCall would make it a particles::Error).
class StopCheck {
 public:
  explicit StopCheck(const Simulation::KeepGoing& keepGoing) : keepGoing_(keepGoing) {}
  bool keepGoing() {
    if (!keepGoing_) return true;
    try {
      return keepGoing_();
    }
    PARTICLES_PASS_FORCED_UNWIND catch (...) {
      thrown_ = std::current_exception();
      return false;
    }
  }
  void rethrowTheCallers() const {
    if (thrown_) std::rethrow_exception(thrown_);
  }

 private:
  const Simulation::KeepGoing& keepGoing_;
  std::exception_ptr thrown_;
};

// Takes steps until `target` steps were taken since the start; false when told to stop first.
bool stepTo(Simulation::Impl& impl, long target, StopCheck& check) {
  while (impl.stepper.steps() < target) {
    if (!check.keepGoing()) return false;
    impl.step();
  }
  return true;
}

}  // namespace

bool Simulation::step(long n, const KeepGoing& keepGoing) {
  StopCheck check(keepGoing);
  const bool done = api::guardedCall("Simulation::step", [&] {
    Impl& impl = implOf(impl_, "step");
    if (n < 0) throw ArgumentError(fmt::format("Simulation::step: expected a number of steps ≥ 0, got {}", n));
    if (n > scenario::kMaxSteps) {
      throw ArgumentError(fmt::format("Simulation::step: {} steps is more than {} at once", n, scenario::kMaxSteps));
    }
    ExclusiveUse use(impl.busy, "Simulation::step");
    const bool all = stepTo(impl, impl.stepper.steps() + n, check);
    impl.clockAtSteps();
    return all;
  });
  check.rethrowTheCallers();
  return done;
}

namespace {

// Steps to the step at `target` s (Stepper::stepsAt: within 1e-9 of a step counts as reached),
// refusing more than kMaxSteps at once; `call` names the API call in messages.
bool stepToTime(Simulation::Impl& impl, std::string_view call, double target, StopCheck& check) {
  const double dt = impl.scenario.simulation.dt;
  if ((target - impl.system().time()) / dt > double(scenario::kMaxSteps)) {
    throw ArgumentError(fmt::format("Simulation::{}: {} s is more than {} steps of dt = {} s ahead", call,
                                    target - impl.system().time(), scenario::kMaxSteps, dt));
  }
  return stepTo(impl, impl.stepper.stepsAt(target), check);
}

}  // namespace

bool Simulation::advance(double seconds, const KeepGoing& keepGoing) {
  StopCheck check(keepGoing);
  const bool done = api::guardedCall("Simulation::advance", [&] {
    Impl& impl = implOf(impl_, "advance");
    if (!std::isfinite(seconds) || seconds < 0.0) {
      throw ArgumentError(fmt::format("Simulation::advance: expected finite seconds ≥ 0, got {}", seconds));
    }
    ExclusiveUse use(impl.busy, "Simulation::advance");
    const auto [clock, clockError] = impl.clockPlus(seconds);
    const bool all = stepToTime(impl, "advance", clock + clockError, check);
    if (all) {
      impl.clock = clock;
      impl.clockError = clockError;
    } else {
      impl.clockAtSteps();
    }
    return all;
  });
  check.rethrowTheCallers();
  return done;
}

bool Simulation::advanceTo(double t, const KeepGoing& keepGoing) {
  StopCheck check(keepGoing);
  const bool done = api::guardedCall("Simulation::advanceTo", [&] {
    Impl& impl = implOf(impl_, "advanceTo");
    const double now = impl.system().time(), dt = impl.scenario.simulation.dt;
    // Behind by less than Stepper's tolerance is the step already reached (k / fps computed another way).
    if (!std::isfinite(t) || (t - now) / dt < -1e-9) {
      throw ArgumentError(
          fmt::format("Simulation::advanceTo: expected a finite time not before t = {} s, got {}", now, t));
    }
    ExclusiveUse use(impl.busy, "Simulation::advanceTo");
    const bool all = stepToTime(impl, "advanceTo", t, check);
    impl.clockAtSteps();
    if (all && t > impl.clock) impl.clock = t;
    return all;
  });
  check.rethrowTheCallers();
  return done;
}

double Simulation::time() const { return implOf(impl_, "time").system().time(); }
long Simulation::steps() const { return implOf(impl_, "steps").stepper.steps(); }
double Simulation::dt() const { return implOf(impl_, "dt").scenario.simulation.dt; }
Integrator Simulation::integrator() const {
  return implOf(impl_, "integrator").scenario.simulation.integrator;
}

void Simulation::setThreads(int threads) {
  api::guardedCall("Simulation::setThreads", [&] {
    Impl& impl = implOf(impl_, "setThreads");
    checkThreads("Simulation::setThreads", threads);
    ExclusiveUse use(impl.busy, "Simulation::setThreads");
    impl.system().setThreads(threads);
  });
}
int Simulation::threads() const { return implOf(impl_, "threads").system().threads(); }

int Simulation::particleCount() const { return implOf(impl_, "particleCount").system().layout().numParticles; }
int Simulation::bodyCount() const { return implOf(impl_, "bodyCount").system().layout().numBodies; }

std::span<const double> Simulation::positions() const {
  const Impl& impl = implOf(impl_, "positions");
  return {impl.system().state().data(), 2 * size_t(impl.system().layout().numParticles)};
}

std::span<const double> Simulation::velocities() const {
  const Impl& impl = implOf(impl_, "velocities");
  const StateLayout& layout = impl.system().layout();
  return {impl.system().state().data() + layout.velocityOffset(), 2 * size_t(layout.numParticles)};
}

Point Simulation::position(int particle) const {
  const Impl& impl = implOf(impl_, "position");
  checkIndex("position", "particle", particle, impl.system().layout().numParticles);
  const Vec2 x = impl.system().view().pos(particle);
  return {x.x(), x.y()};
}

Point Simulation::velocity(int particle) const {
  const Impl& impl = implOf(impl_, "velocity");
  checkIndex("velocity", "particle", particle, impl.system().layout().numParticles);
  const Vec2 v = impl.system().view().vel(particle);
  return {v.x(), v.y()};
}

BodyState Simulation::body(int body) const {
  const Impl& impl = implOf(impl_, "body");
  const StateLayout& layout = impl.system().layout();
  checkIndex("body", "body", body, layout.numBodies);
  const StateView view = impl.system().view();
  const Vec2 x = view.pos(layout.bodyPoint(body));
  return {x.x(), x.y(), view.angle(body), view.omega(body)};
}

std::vector<BodyState> Simulation::bodies() const {
  return api::guardedCall("Simulation::bodies", [&] {
    std::vector<BodyState> out;
    out.reserve(size_t(bodyCount()));
    for (int j = 0; j < bodyCount(); ++j) out.push_back(body(j));
    return out;
  });
}

Energy Simulation::energy() const {
  return api::guardedCall("Simulation::energy", [&] {
    const EnergyReport e = implOf(impl_, "energy").system().energy();
    return Energy{e.kinetic, e.potential, e.total()};
  });
}

double Simulation::constraintError() const {
  return api::guardedCall("Simulation::constraintError", [&] {
    const System& system = implOf(impl_, "constraintError").system();
    return system.constraintError(system.state());
  });
}

double Simulation::penetration() const {
  return api::guardedCall("Simulation::penetration", [&] {
    const System& system = implOf(impl_, "penetration").system();
    return system.penetration(system.state());
  });
}

std::vector<std::string> Simulation::particleNames() const {
  return api::guardedCall("Simulation::particleNames", [&] { return implOf(impl_, "particleNames").names(false); });
}

std::vector<std::string> Simulation::bodyNames() const {
  return api::guardedCall("Simulation::bodyNames", [&] { return implOf(impl_, "bodyNames").names(true); });
}

namespace {

int indexOf(Simulation::Impl& impl, std::string_view call, std::string_view what, bool bodies,
            std::string_view name) {
  const std::vector<std::string>& names = impl.names(bodies);
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return int(it - names.begin());
  const std::string closest = input::closestName(name, names);
  throw ArgumentError(
      fmt::format("Simulation::{}: no {} is named {}{} (names are spelled as in `particles run "
                  "--trace`: bob, cloth[3][4], #7, body#2)",
                  call, what, input::quotedValue(name),
                  closest.empty() ? "" : fmt::format("; did you mean {}?", input::quotedValue(closest))));
}

}  // namespace

int Simulation::particleIndex(std::string_view name) const {
  return api::guardedCall("Simulation::particleIndex",
                          [&] { return indexOf(implOf(impl_, "particleIndex"), "particleIndex", "particle", false, name); });
}

int Simulation::bodyIndex(std::string_view name) const {
  return api::guardedCall("Simulation::bodyIndex",
                          [&] { return indexOf(implOf(impl_, "bodyIndex"), "bodyIndex", "body", true, name); });
}

namespace {

MouseSpringForce& mouseOf(Simulation::Impl& impl, std::string_view call, int mouse) {
  const std::vector<MouseSpringForce*> mice = impl.system().mice();
  checkIndex(call, "mouse", mouse, int(mice.size()));
  return *mice[size_t(mouse)];
}

}  // namespace

int Simulation::mouseCount() const { return int(implOf(impl_, "mouseCount").system().mice().size()); }

void Simulation::setMouseTarget(Point target, int mouse) {
  api::guardedCall("Simulation::setMouseTarget", [&] {
    Impl& impl = implOf(impl_, "setMouseTarget");
    checkFinite("setMouseTarget", target);
    ExclusiveUse use(impl.busy, "Simulation::setMouseTarget");
    mouseOf(impl, "setMouseTarget", mouse).holdAt(Vec2(target.x, target.y), impl.system().time());
  });
}

void Simulation::releaseMouse(int mouse) {
  api::guardedCall("Simulation::releaseMouse", [&] {
    Impl& impl = implOf(impl_, "releaseMouse");
    ExclusiveUse use(impl.busy, "Simulation::releaseMouse");
    mouseOf(impl, "releaseMouse", mouse).release(impl.system().time());
  });
}

std::optional<Point> Simulation::mouseTarget(int mouse) const {
  return api::guardedCall("Simulation::mouseTarget", [&]() -> std::optional<Point> {
    Impl& impl = implOf(impl_, "mouseTarget");
    const MouseSpringForce& m = mouseOf(impl, "mouseTarget", mouse);
    const double t = impl.system().time();
    if (!m.activeAt(t)) return std::nullopt;
    const Vec2 at = m.target(t);
    return Point{at.x(), at.y()};
  });
}

void Simulation::setPosition(int particle, Point position) {
  api::guardedCall("Simulation::setPosition", [&] {
    Impl& impl = implOf(impl_, "setPosition");
    checkIndex("setPosition", "particle", particle, impl.system().layout().numParticles);
    checkFinite("setPosition", position);
    ExclusiveUse use(impl.busy, "Simulation::setPosition");
    Eigen::VectorXd& y = impl.system().state();
    y[2 * particle] = position.x;
    y[2 * particle + 1] = position.y;
  });
}

void Simulation::setVelocity(int particle, Point velocity) {
  api::guardedCall("Simulation::setVelocity", [&] {
    Impl& impl = implOf(impl_, "setVelocity");
    const StateLayout& layout = impl.system().layout();
    checkIndex("setVelocity", "particle", particle, layout.numParticles);
    checkFinite("setVelocity", velocity);
    ExclusiveUse use(impl.busy, "Simulation::setVelocity");
    Eigen::VectorXd& y = impl.system().state();
    y[layout.velocityOffset() + 2 * particle] = velocity.x;
    y[layout.velocityOffset() + 2 * particle + 1] = velocity.y;
  });
}

}  // namespace particles
