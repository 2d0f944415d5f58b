#include "core/integrators.hpp"

#include <array>

#include "core/integrators/backward_euler.hpp"
#include "core/integrators/bdf2.hpp"
#include "core/integrators/explicit_euler.hpp"
#include "core/integrators/midpoint.hpp"
#include "core/integrators/rk4.hpp"
#include "core/integrators/symplectic_euler.hpp"
#include "core/integrators/verlet.hpp"
#include "core/system.hpp"

namespace particles {

namespace {

using StepFn = void (*)(System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w);

DerivFn derivOf(System& system) {
  return [&system](const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt) { system.derivEval(y, t, dydt); };
}

struct IntegratorEntry {
  Integrator id;
  std::string_view name;
  int evalsPerStep;
  bool projects;
  bool implicit;  // solves for the step's end (stable at any step on a spring)
  std::string_view summary;
  StepFn step;
};

// The registry: one row per integrator, in the order studies and help list them.
const std::array<IntegratorEntry, 7> kIntegrators{{
    {Integrator::Euler, "euler", 1, false, false, "explicit Euler, first order",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
       integrateEuler(derivOf(s), y, t, h, w);
     }},
    {Integrator::Midpoint, "midpoint", 2, false, false, "explicit midpoint, second order",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
       integrateMidpoint(derivOf(s), y, t, h, w);
     }},
    {Integrator::Rk4, "rk4", 4, false, false, "classic 4th-order Runge–Kutta",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
       integrateRk4(derivOf(s), y, t, h, w);
     }},
    {Integrator::SymplecticEuler, "symplectic_euler", 1, true, false, "semi-implicit Euler (v, then x), first order",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
       const DerivFn withoutConstraintForces = [&s](const Eigen::VectorXd& at, double time, Eigen::VectorXd& dydt) {
         s.derivEval(at, time, dydt, System::ConstraintForces::skip);
       };
       VelocityProjection project;
       if (!s.constraints().empty()) project = [&s](Eigen::VectorXd& at) { s.projectVelocitiesOntoConstraints(at); };
       integrateSymplecticEuler(withoutConstraintForces, s.layout(), y, t, h, w, project);
     }},
    {Integrator::Verlet, "verlet", 1, true, false, "velocity Verlet, second order",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
       integrateVerlet(derivOf(s), s.layout(), y, t, h, w);
     }},
    {Integrator::BackwardEuler, "backward_euler", 1, true, true,
     "implicit Euler, one Newton step (Baraff & Witkin 1998), first order",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
       integrateBackwardEuler(s, y, t, h, w);
     }},
    {Integrator::Bdf2, "bdf2", 1, true, true,
     "second-order backward differentiation (BDF2), one Newton step (Choi & Ko 2002), second order",
     [](System& s, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) { integrateBdf2(s, y, t, h, w); }},
}};

const std::array<Integrator, kIntegrators.size()> kAll = [] {
  std::array<Integrator, kIntegrators.size()> all{};
  for (size_t i = 0; i < all.size(); ++i) all[i] = kIntegrators[i].id;
  return all;
}();

const IntegratorEntry& entry(Integrator integrator) {
  for (const IntegratorEntry& e : kIntegrators) {
    if (e.id == integrator) return e;
  }
  return kIntegrators[0];  // unreachable: every enum value has a row (tested)
}

}  // namespace

std::string_view integratorName(Integrator integrator) { return entry(integrator).name; }

std::optional<Integrator> integratorFromName(std::string_view name) {
  for (const IntegratorEntry& e : kIntegrators) {
    if (e.name == name) return e.id;
  }
  return std::nullopt;
}

std::span<const Integrator> allIntegrators() { return kAll; }
int derivEvalsPerStep(Integrator integrator) { return entry(integrator).evalsPerStep; }
bool projectsConstraints(Integrator integrator) { return entry(integrator).projects; }
bool isImplicit(Integrator integrator) {
  return entry(integrator).implicit;
}
std::string_view integratorSummary(Integrator integrator) { return entry(integrator).summary; }

void integrate(Integrator integrator, System& system, Eigen::VectorXd& y, double t, double h, IntegratorScratch& w) {
  w.pool = system.pool();
  entry(integrator).step(system, y, t, h, w);
}

}  // namespace particles
