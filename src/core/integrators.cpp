#include "core/integrators.hpp"

#include <array>

#include "core/integrators/backward_euler.hpp"
#include "core/integrators/bdf2.hpp"
#include "core/integrators/explicit_euler.hpp"
#include "core/integrators/midpoint.hpp"
#include "core/integrators/rk4.hpp"
#include "core/integrators/symplectic_euler.hpp"
#include "core/integrators/verlet.hpp"
#include "core/name_table.hpp"
#include "core/system.hpp"

namespace particles {

namespace {

struct IntegratorEntry {
  Integrator id;
  std::string_view name;
  int evalsPerStep;
  bool projects;
  bool implicit;  // solves for the step's end (stable at any step on a spring)
  std::string_view summary;
  std::unique_ptr<IntegratorState> (*makeState)();
};

// The registry: one row per integrator, in the order studies and help list them.
constexpr std::array<IntegratorEntry, 7> kIntegrators{{
    {Integrator::euler, "euler", 1, false, false, "explicit Euler, first order", makeEulerState},
    {Integrator::midpoint, "midpoint", 2, false, false, "explicit midpoint, second order", makeMidpointState},
    {Integrator::rk4, "rk4", 4, false, false, "classic 4th-order Runge–Kutta", makeRk4State},
    {Integrator::symplecticEuler, "symplectic_euler", 1, true, false, "semi-implicit Euler (v, then x), first order",
     makeSymplecticEulerState},
    {Integrator::verlet, "verlet", 1, true, false, "velocity Verlet, second order", makeVerletState},
    {Integrator::backwardEuler, "backward_euler", 1, true, true,
     "implicit Euler, one Newton step (Baraff & Witkin 1998), first order", makeBackwardEulerState},
    {Integrator::bdf2, "bdf2", 1, true, true,
     "second-order backward differentiation (BDF2), one Newton step (Choi & Ko 2002), second order", makeBdf2State},
}};

// The rows' names as a name table (core/name_table.hpp), so each name is spelled once, in its row.
struct IntegratorNames {
  NameTableRow<Integrator> rows[kIntegrators.size()];
};
constexpr IntegratorNames kIntegratorNames = [] {
  IntegratorNames names{};
  for (size_t i = 0; i < kIntegrators.size(); ++i) names.rows[i] = {kIntegrators[i].id, kIntegrators[i].name};
  return names;
}();

constexpr std::array<Integrator, kIntegrators.size()> kAll = [] {
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

std::string_view integratorName(Integrator integrator) {
  return nameOf(kIntegratorNames.rows, integrator, "unknown");
}
std::optional<Integrator> integratorFromName(std::string_view name) {
  return valueNamed(kIntegratorNames.rows, name);
}
std::span<const Integrator> allIntegrators() { return kAll; }
int derivEvalsPerStep(Integrator integrator) { return entry(integrator).evalsPerStep; }
bool projectsConstraints(Integrator integrator) { return entry(integrator).projects; }
bool isImplicit(Integrator integrator) {
  return entry(integrator).implicit;
}
std::string_view integratorSummary(Integrator integrator) { return entry(integrator).summary; }

DerivFn derivativeOf(System& system) {
  return [&system](const Eigen::VectorXd& y, double t, Eigen::VectorXd& dydt) { system.derivEval(y, t, dydt); };
}

void ScratchOnlyState::step(System& system, Eigen::VectorXd& y, double t, double h) {
  scratch_.pool = system.pool();
  step_(system, y, t, h, scratch_);
}

std::unique_ptr<IntegratorState> makeIntegratorState(Integrator integrator) {
  return entry(integrator).makeState();
}

}  // namespace particles
