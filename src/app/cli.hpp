#pragma once
// The command line (docs/physics.md §12): every command of kCommands (command_table.hpp), and the
// options of the one a command line names with where they are parsed into, built once per parse.
// main() parses argv with it;
// `sweep` parses each job's command line with a fresh one before any job runs, so a bad option in
// a sweep file is found up front.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "app/command.hpp"

namespace particles::app {

class Cli {
 public:
  Cli();
  Cli(const Cli&) = delete;
  Cli& operator=(const Cli&) = delete;

  // Parses `args` (argv without argv[0]) into the commands' options. Throws CLI::ParseError, which
  // app.exit() prints: the help or the version (exit code 0), or a usage error. A first word that
  // names no command is a usage error that names it, even before --help (CLI11 would answer
  // `particles golden --help` with the main help and success).
  // Only the named command's options are added (BoundCommand::addOptions): the main help lists
  // the commands by name and summary, and a command's own help is the one with its options.
  void parse(const std::vector<std::string>& args);
  // The command called `name`, with its options (its help, its options by name); throws
  // std::logic_error when no command has that name.
  CLI::App& command(std::string_view name);
  // Runs the parsed command (with its job record, when it has --record) and returns the exit
  // code; errors are printed and mapped by runReportingErrors. `args` is argv without argv[0], as the
  // job record names the command (`particles job` leaves out the --threads it adds: job_command.hpp).
  int dispatch(const std::vector<std::string>& args);
  // The parsed command's files, --record aside: those its command line names (command.hpp).
  CommandFiles commandFiles() const;
  // The parsed command's --record, or empty.
  std::string recordFile() const;

  CLI::App app{"particles: 2D particle systems and rigid bodies after Witkin & Baraff", "particles"};

 private:
  // The command the first word that is not an option names; nullptr when every word is an option.
  // Throws CLI::ParseError when that word is no command's name.
  BoundCommand* namedCommand(const std::vector<std::string>& args);
  // The command the parse named; nullptr before a parse.
  const BoundCommand* parsedCommand() const;

  std::vector<std::unique_ptr<BoundCommand>> commands_;  // kCommands' order
};

}  // namespace particles::app
