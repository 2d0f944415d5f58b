#pragma once
// `particles stability SCENARIO` (src/core/stability.hpp, docs/stability.md): the largest stable
// time step of each integrator, as a table on stdout, `--csv` and a `--plot` figure.
//
// Exit codes: 0 done; 1 the reference run failed; 2 bad input; 3 an output could not be written.

#include <string>
#include <vector>

#include "app/command.hpp"

namespace particles::app {

// Defaults as in StabilityCriteria / StabilityOptions (src/core/stability.hpp).
struct StabilityOptionsCli {
  CommonOptions common;
  std::vector<std::string> integrators = integratorNames();  // every integrator the core has
  std::string csv;                                           // --csv, empty: none
  std::string plot;                                          // --plot .svg | .png | .pdf, empty: none
  std::vector<std::string> references;                       // --reference NAME=DT or NAME=LO:HI, for the figure
  std::string referenceName = "reference";
  double energyTolerance = 0.1;
  double stretchFactor = 1.5;  // × the reference run's largest stretch
  double shakeThreshold = 0.1;
  double minDt = 0;  // 0: the scenario's dt / 1000
  double maxDt = 10.0;
  int threads = 0;
  JobOptions job;
};

extern const CommandDescriptor<StabilityOptionsCli> kStabilityCommand;

}  // namespace particles::app
