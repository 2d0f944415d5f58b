#pragma once
// The command line (docs/physics.md §12): every subcommand, its options and where they are parsed
// into, built once per parse. main() parses argv with it; `sweep` parses each job's command line
// with a fresh one before any job runs, so a bad option in a sweep file is found up front.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/compare_command.hpp"
#include "app/concat_command.hpp"
#include "app/job_command.hpp"
#include "app/job_record.hpp"
#include "app/sweep_command.hpp"
#include "output/distinct_files.hpp"

namespace particles::app {

// The files a command writes and reads, as its command line names them (empty: an option not
// given). Checked against each other before the command runs (output/distinct_files.hpp).
struct CommandFiles {
  std::vector<output::NamedFile> outputs, inputs;
};

struct Cli {
  Cli();
  Cli(const Cli&) = delete;
  Cli& operator=(const Cli&) = delete;

  // Runs the parsed subcommand (with its job record, when it has --record) and returns the exit
  // code; errors are printed and mapped by runReportingErrors. `args` is argv without argv[0].
  int dispatch(const std::vector<std::string>& args);
  // The parsed command's files, --record aside. gather has none here: its inputs are the records
  // its job table lists, which it checks once it has read the table.
  CommandFiles commandFiles() const;

  CLI::App app{"particles: 2D particle systems and rigid bodies after Witkin & Baraff", "particles"};
  CommonOptions common;
  RunOptions run;
  RenderCommandOptions render;
  StabilityOptionsCli stability;
  CompareOptions compare;
  ConcatOptions concat;
  PlotOptions plot;
  SchemaOptions schema;
  JobOptions job;
  SweepOptions sweep;
  GatherOptions gather;
  RunJobOptions runJob;

  CLI::App *checkCmd = nullptr, *runCmd = nullptr, *renderCmd = nullptr, *stabilityCmd = nullptr, *compareCmd = nullptr,
           *concatCmd = nullptr, *plotCmd = nullptr, *schemaCmd = nullptr, *sweepCmd = nullptr, *gatherCmd = nullptr,
           *runJobCmd = nullptr;
};

}  // namespace particles::app
