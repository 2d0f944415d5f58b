#pragma once
// `particles job OUT INDEX` (docs/sweeps.md): runs job INDEX of the sweep in OUT, as its row of
// OUT/jobs.csv says, in this process. This is what the job lists for GNU parallel and the Slurm
// array scripts hold, and what `particles sweep` starts for each job: a line of fixed words, a
// folder and a number, so no value of a sweep file ever passes through a shell. The row's command
// line is read back into its arguments (splitCommandText) and parsed by the program's own command
// line, never executed by a shell; it may only be the command its stage names (run, render,
// stability or concat).
//
// Exit codes: the job's own (0, 1, 2, 3); 2 also for an index past the end, a folder without a
// valid jobs.csv, or a row whose command is not its stage's.

#include <cstdint>
#include <string>

#include "app/command.hpp"
#include "input/text_file.hpp"

namespace particles::app {

struct RunJobOptions {
  std::string outDir;
  std::string index;  // checked as a whole number here, for a message naming it
  bool force = false;
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;
};

extern const CommandDescriptor<RunJobOptions> kRunJobCommand;

}  // namespace particles::app
