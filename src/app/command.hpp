#pragma once
// What a command of the program is (docs/architecture.md, "Adding a command"). Each command's file
// pair (run_command, render_command, …) exports one CommandDescriptor: its name and one-line
// summary for the main help, the function that adds its options to its CLI::App bound to its
// options struct, its run function, and the files its command line names. kCommands
// (command_table.hpp) lists them, and Cli (cli.hpp) builds the command line and dispatches from
// that list.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "app/cli_support.hpp"
#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "output/distinct_files.hpp"

namespace particles::app {

// The files a command writes and reads, as its command line names them (empty: an option not
// given). Checked against each other before the command runs (output/distinct_files.hpp); the
// outputs are listed in its job record.
struct CommandFiles {
  std::vector<output::NamedFile> outputs, inputs;
};

template <class Options>
struct CommandDescriptor {
  using OptionsType = Options;
  std::string_view name;
  std::string_view summary;  // one line, in the main help's list of commands
  // Adds the options, bound to `options`, and the help's footer to the command.
  void (*addOptions)(CLI::App& command, Options& options);
  // Returns the exit code of an outcome that is not an error (kOk on success) and throws for an
  // error, which runReportingErrors prints and maps to its code (exit_codes.hpp).
  int (*run)(const Options& options);
  // The files the command line names; nullptr for a command that names none. Files named in a file
  // the command reads (gather's records, the scenarios of a sweep or a golden manifest) are checked
  // by the command once it has read that file, against the same outputs.
  CommandFiles (*files)(const Options& options) = nullptr;
  // A command that reads a scenario: its options, whose scenario the messages of a failed
  // simulation name and whose --max-input its job record is read within. Null for the others.
  CommonOptions Options::*common = nullptr;
  // A command a sweep runs as a job: its --record and --force (addJobOptions). Null for the others.
  JobOptions Options::*job = nullptr;
};

// One command after the parse: its options, which CLI11 fills, and what runs on them.
class BoundCommand {
 public:
  virtual ~BoundCommand() = default;
  virtual std::string_view name() const = 0;
  // Adds the command's options (once; again does nothing). Cli adds only the named command's: each
  // command has dozens, and the program parses one command line per start, a sweep one per job.
  virtual CLI::App& addOptions() = 0;
  virtual bool parsed() const = 0;
  virtual int run() const = 0;
  virtual CommandFiles files() const = 0;
  virtual ErrorContext errorContext() const = 0;
  // Its --record options, with the --max-input its record is read within; an empty record for a
  // command that takes none.
  virtual JobOptions job() const = 0;
};

template <class Options>
class BoundCommandOf final : public BoundCommand {
 public:
  // Adds the command to `app`, without its options (addOptions). The options live here, where
  // CLI11 writes them: not copyable.
  BoundCommandOf(CLI::App& app, const CommandDescriptor<Options>& descriptor) : descriptor_(descriptor) {
    command_ = app.add_subcommand(std::string(descriptor.name), std::string(descriptor.summary));
  }
  BoundCommandOf(const BoundCommandOf&) = delete;
  BoundCommandOf& operator=(const BoundCommandOf&) = delete;

  std::string_view name() const override { return descriptor_.name; }
  CLI::App& addOptions() override {
    if (!optionsAdded_) descriptor_.addOptions(*command_, options_);
    optionsAdded_ = true;
    return *command_;
  }
  bool parsed() const override { return command_->parsed(); }
  int run() const override { return descriptor_.run(options_); }
  CommandFiles files() const override { return descriptor_.files ? descriptor_.files(options_) : CommandFiles{}; }
  ErrorContext errorContext() const override {
    return {.scenario = descriptor_.common ? (options_.*descriptor_.common).scenario : std::string()};
  }
  JobOptions job() const override {
    if (!descriptor_.job) return {};
    JobOptions job = options_.*descriptor_.job;
    if (descriptor_.common) job.maxInputMiB = (options_.*descriptor_.common).maxInputMiB;
    return job;
  }

 private:
  const CommandDescriptor<Options>& descriptor_;
  Options options_;
  CLI::App* command_ = nullptr;
  bool optionsAdded_ = false;
};

// Adds the command `descriptor` describes to `app`, its options not yet (BoundCommand::addOptions):
// what a row of kCommands holds.
using AddCommand = std::unique_ptr<BoundCommand> (*)(CLI::App& app);
template <const auto& descriptor>
std::unique_ptr<BoundCommand> addCommand(CLI::App& app) {
  return std::make_unique<BoundCommandOf<typename std::remove_cvref_t<decltype(descriptor)>::OptionsType>>(app,
                                                                                                           descriptor);
}

}  // namespace particles::app
