#pragma once
// `particles stability SCENARIO` (src/core/stability.hpp, docs/stability.md): the largest stable
// time step of each integrator, as a table on stdout, `--csv` and a `--plot` figure.
//
// Exit codes: 0 done; 1 the reference run failed; 2 bad input; 3 an output could not be written.

#include <string>
#include <vector>

#include "app/command.hpp"
#include "core/stability.hpp"

namespace particles::app {

// Without --min-dt, the smallest step tried is the scenario's dt divided by this.
inline constexpr double kMinDtDivisor = 1000;
// The reference run (rk4 at a quarter of the scenario's dt) is halved up to this many times until
// it is stable.
inline constexpr int kReferenceHalvings = 6;

// Defaults from StabilityCriteria and StabilityOptions.
struct StabilityOptionsCli {
  CommonOptions common;
  std::vector<std::string> integrators = integratorNames();  // every integrator the core has
  std::string csv;                                           // --csv, empty: none
  std::string plot;                                          // --plot .svg | .png | .pdf, empty: none
  std::vector<std::string> references;                       // --reference NAME=DT or NAME=LO:HI, for the figure
  std::string referenceName = "reference";
  double energyTolerance = StabilityCriteria{}.energyTolerance;
  double stretchFactor = StabilityOptions{}.stretchFactor;  // × the reference run's largest stretch
  double shakeThreshold = StabilityCriteria{}.shakeThreshold;
  double minDt = 0;  // 0: the scenario's dt / kMinDtDivisor
  double maxDt = StabilityOptions{}.maxDt;
  JobOptions job;
};

extern const CommandDescriptor<StabilityOptionsCli> kStabilityCommand;

}  // namespace particles::app
