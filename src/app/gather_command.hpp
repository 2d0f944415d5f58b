#pragma once
// `particles gather OUTDIR` (docs/sweeps.md): the one table of a sweep's results, a row per job of
// its jobs.csv with its parameters, its outcome from its record and the headline numbers the job
// reported; and, when one parameter varies, a figure of those numbers against it. `sweep` gathers
// when its jobs are done.
//
// Exit codes: 0 written; 2 not a sweep's folder (or a table or record that cannot be read as one,
// or an output naming one of them); 3 an output could not be written.

#include <cstdint>
#include <string>

#include "app/command.hpp"
#include "input/text_file.hpp"

namespace particles::app {

struct GatherOptions {
  std::string outDir;
  std::string output;  // -o: the CSV; empty: OUTDIR/results.csv
  std::string plot;    // --plot: the figure; empty: OUTDIR/results.svg when one parameter varies; "none": no figure
  bool quiet = false;
  std::uintmax_t maxInputMiB =
      input::kDefaultMaxInputMiB;  // --max-input: jobs.csv and each record are read within this
};

int gatherCommand(const GatherOptions& options);

extern const CommandDescriptor<GatherOptions> kGatherCommand;

}  // namespace particles::app
