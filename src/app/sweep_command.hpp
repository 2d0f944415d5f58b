#pragma once
// `particles sweep SPEC.yaml` (docs/sweeps.md): many runs of one command over scenarios and
// parameters, run here (--jobs N), or emitted for GNU parallel or as a Slurm job array; then their
// results gathered (gather_command.hpp).
//
// Exit codes: 0 every job succeeded (or the lists were emitted), 1 some job failed (the others
// still ran; each failure is listed with its message), 2 a bad sweep file (file:line, before any
// job runs), 3 an output could not be written, 128 + signal when interrupted by SIGINT or SIGTERM
// (rerun to resume).

#include <cstdint>
#include <string>

#include "app/command.hpp"
#include "input/text_file.hpp"

namespace particles::app {

struct SweepOptions {
  std::string spec;     // the sweep file
  std::string out;      // -o: the output folder; empty: ./sweep-<name>
  int jobs = 0;         // --jobs: at once here; 0: one per core
  std::string emit;     // --emit parallel | slurm: write the job lists, run nothing
  std::string program;  // --program: the particles the jobs call; empty: this one
  bool force = false;   // rerun finished jobs
  bool quiet = false;
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;
};

extern const CommandDescriptor<SweepOptions> kSweepCommand;

}  // namespace particles::app
