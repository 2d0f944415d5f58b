#pragma once
// A sweep file turned into jobs (docs/sweeps.md): every job one plain `particles …` command line
// (kept in jobs.csv, run by `particles job OUT INDEX`, never by a shell) with its outputs and record
// in its own folder under the output folder. Everything that can be
// checked is checked here, before any job runs: each scenario loads with each parameter value
// (parsed and loaded once, each value read where it changes the file: scenario/override_check.hpp),
// a job's values together where they change one part of it, the command accepts the options, a
// split render has frames for every segment.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"
#include "scenario/sweep_spec.hpp"

namespace particles::app {

struct SweepJob {
  size_t index = 0;
  std::string stage;                 // run | render | stability | segment | concat
  std::string scenario;              // as the sweep file names it
  std::vector<std::string> values;   // one per parameter column, as written in the sweep file
  std::string segment;               // "k/K" for a segment of a split render, else empty
  std::filesystem::path dir;         // the job's folder, relative to the output folder
  std::vector<std::string> args;     // after the program: command, scenario, options, outputs, --record
  std::vector<size_t> after;         // concat: the segment jobs it joins
  std::filesystem::path record;      // absolute
  std::vector<std::string> outputs;  // absolute
  size_t scenarioIndex = 0;          // in spec.scenarios
  std::vector<scenario::Override> overrides;  // what its command line changes in the scenario; none for concat
};

struct SweepPlan {
  scenario::SweepSpec spec;
  std::filesystem::path outDir;      // absolute
  std::string program;               // the particles the jobs call, absolute
  std::vector<std::string> columns;  // parameter names, in the sweep file's order
  std::vector<SweepJob> jobs;        // the first `firstStageCount` run first; concat jobs after them
  size_t firstStageCount = 0;

  // `program args…` as one shell line.
  std::string commandLine(const SweepJob& job) const;
};

// Expands and checks the sweep, with progress on stderr when `showProgress` and it is a terminal.
// Throws scenario::ScenarioError in the sweep file.
SweepPlan planSweep(const scenario::SweepSpec& spec, const std::filesystem::path& outDir, const std::string& program,
                    std::uintmax_t maxInputMiB, bool showProgress = false);

// Creates the output folder with each job's folder and writes jobs.csv: index, stage, scenario,
// the parameters, segment, dir, command. Throws output::OutputError.
void writeJobTable(const SweepPlan& plan);

}  // namespace particles::app
