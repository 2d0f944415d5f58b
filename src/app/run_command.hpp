#pragma once
// `particles run SCENARIO [--stats S.csv] [--trace T.csv]` (docs/physics.md §12): simulates a
// scenario headless for its duration and prints a summary; the CSVs have one row per 1/fps tick.
//
// Exit codes: 0 done; 1 the simulation failed (exploded: the CSVs are not written); 2 bad input;
// 3 an output could not be written.

#include <string>
#include <vector>

#include "app/command.hpp"

namespace particles::app {

struct RunOptions {
  CommonOptions common;
  std::string stats;                   // --stats CSV, empty: none
  std::string trace;                   // --trace CSV, empty: none
  std::vector<std::string> traceOnly;  // --trace-only names
  JobOptions job;
};

extern const CommandDescriptor<RunOptions> kRunCommand;

}  // namespace particles::app
