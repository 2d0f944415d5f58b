#pragma once
// `particles job OUT INDEX` (docs/sweeps.md): runs job INDEX of the sweep in OUT, as its row of
// OUT/jobs.csv says, in this process. This is what the job lists for GNU parallel and the Slurm
// array scripts hold, and what `particles sweep` starts for each job: a line of fixed words, a
// folder and a number, so no value of a sweep file ever passes through a shell. The row's command
// line is read back into its arguments (splitCommandText) and parsed by the program's own command
// line, never executed by a shell; it may only be the command its stage names (run, render,
// stability or concat).
//
// `--threads N` (what `particles sweep` adds, its share of the cores) is passed on to the command
// when it has that option (concat does not) and its line in jobs.csv does not set it already: a
// sweep file's explicit `threads` wins. It is no part of the job: the record names jobs.csv's line,
// so a job is done whatever threads ran it (the results are the same bits for every count).
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
  int threads = 0;  // --threads: for the command, unless its own line sets them; 0: not given
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;
};

extern const CommandDescriptor<RunJobOptions> kRunJobCommand;

}  // namespace particles::app
