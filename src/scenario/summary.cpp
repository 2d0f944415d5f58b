#include "scenario/summary.hpp"

#include <fmt/format.h>

#include "core/integrators.hpp"
#include "core/system.hpp"

namespace particles::scenario {

std::string plural(std::size_t n, const char* one, const char* many) { return fmt::format("{} {}", n, n == 1 ? one : many); }

std::string contents(const Scenario& s) {
  const System& sys = s.system;
  return fmt::format("{}, {}, {}, {}, {}, {}", plural(std::size_t(sys.layout().numParticles), "particle", "particles"),
                     plural(std::size_t(sys.layout().numBodies), "rigid body", "rigid bodies"),
                     plural(springCount(sys), "spring", "springs"),
                     plural(sys.constraints().size(), "constraint", "constraints"),
                     plural(sys.colliders().size(), "collider", "colliders"),
                     plural(mouseScriptCount(sys), "mouse script", "mouse scripts"));
}

std::string checkSummary(const Scenario& s, const std::string& shownAs) {
  const SimulationSettings& sim = s.simulation;
  return fmt::format("{}: ok: '{}' with {}; {}, dt {} s, duration {} s ({})", shownAs, s.name, contents(s),
                     integratorName(sim.integrator), sim.dt, sim.duration, plural(std::size_t(sim.steps()), "step", "steps"));
}

}  // namespace particles::scenario
