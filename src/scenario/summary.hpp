#pragma once
// How a loaded scenario is described to people, and the simulation keys that have shorthands:
// one text for `particles check` and the library's Scenario::summary(), one list of shorthands
// for the command line's --integrator, --dt, --duration, --implicit-solver and the library's
// Scenario::set("dt", …).

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "scenario/scenario.hpp"

namespace particles::scenario {

// "1 particle", "625 particles".
std::string plural(std::size_t n, const char* one, const char* many);

// "625 particles, 0 rigid bodies, 1200 springs, 1 constraint, 0 colliders, 1 mouse script".
std::string contents(const Scenario& s);

// What `particles check` prints for a valid scenario, `shownAs` naming it:
// "scenarios/cloth.yaml: ok: 'cloth' with 625 particles, …; rk4, dt 0.01 s, duration 10 s (1000 steps)".
std::string checkSummary(const Scenario& s, const std::string& shownAs);

// The simulation keys a shorthand names: "dt" stands for "simulation.dt", and so on.
inline constexpr std::array<std::string_view, 4> kSimulationShorthands = {"integrator", "dt", "duration",
                                                                          "implicit_solver"};

}  // namespace particles::scenario
