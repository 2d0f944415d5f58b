#pragma once
// `particles sweep SPEC.yaml` and `particles gather OUTDIR` (docs/sweeps.md): many runs of one
// command over scenarios and parameters, run here (--jobs N), or emitted for GNU parallel or as a
// Slurm job array; and the one table (and figure) of their results.
//
// Exit codes: sweep — 0 every job succeeded (or the lists were emitted), 1 some job failed (the
// others still ran; each failure is listed with its message), 2 a bad sweep file (file:line, before
// any job runs), 3 an output could not be written, 128 + signal when interrupted (rerun to
// resume). gather — 0, 2 (not a sweep's folder), 3.

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace particles::app {

struct SweepOptions {
  std::string spec;     // the sweep file
  std::string out;      // -o: the output folder; empty: ./sweep-<name>
  int jobs = 0;         // --jobs: at once here; 0: one per core
  std::string emit;     // --emit parallel | slurm: write the job lists, run nothing
  std::string program;  // --program: the particles the jobs call; empty: this one
  bool force = false;   // rerun finished jobs
  bool quiet = false;
  std::uintmax_t maxInputMiB = 64;
};

struct GatherOptions {
  std::string outDir;
  std::string output;  // -o: the CSV; empty: OUTDIR/results.csv
  std::string plot;    // --plot: the figure; empty: OUTDIR/results.svg when one parameter varies; "none": no figure
  bool quiet = false;
  std::uintmax_t maxInputMiB = 64;  // --max-input: jobs.csv and each record are read within this
};

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options);
CLI::App* addGatherCommand(CLI::App& app, GatherOptions& options);

int sweepCommand(const SweepOptions& options);
int gatherCommand(const GatherOptions& options);

}  // namespace particles::app
