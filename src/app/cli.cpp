// The command line: see cli.hpp. Each command's options and work are in its own file pair
// (check_command, run_command, …), listed in command_table.cpp; errors become exit codes and
// messages in exit_codes.cpp only.
#include "app/cli.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "input/printable_text.hpp"
#include "app/command_table.hpp"
#include "app/exit_codes.hpp"
#include "app/gl_options.hpp"
#include "app/job_record.hpp"
#include "input/closest_name.hpp"

namespace particles::app {

Cli::Cli() {
  // The version, and on a second line the GL backend and renderer `render` would use.
  app.set_version_flag("--version", [] { return "particles " + programVersion() + "\n" + glVersionLine(); });
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 simulation failure (explosion; for compare: the frames differ),\n"
      "2 bad input or usage, 3 output failure.\n"
      "Run 'particles COMMAND --help' for the options of a command.\n");
  for (const AddCommand add : kCommands) commands_.push_back(add(app));
}

void Cli::parse(const std::vector<std::string>& args) {
  if (BoundCommand* command = namedCommand(args)) command->addOptions();
  app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 takes them last first
}

CLI::App& Cli::command(std::string_view name) {
  for (const auto& command : commands_) {
    if (command->name() == name) return command->addOptions();
  }
  throw std::logic_error(fmt::format("Cli::command: no command {}", name));
}

BoundCommand* Cli::namedCommand(const std::vector<std::string>& args) {
  // The program's own options (--help, --version) take no value, so the first word that is not an
  // option is the command.
  const auto word = std::find_if(args.begin(), args.end(), [](const std::string& a) { return !a.starts_with('-'); });
  if (word == args.end()) return nullptr;
  std::vector<std::string> names;
  for (const auto& command : commands_) {
    if (command->name() == *word) return command.get();
    names.emplace_back(command->name());
  }
  const std::string nearest = input::closestName(*word, names);
  throw CLI::ParseError(
      fmt::format("unknown command {}{}; the commands are {}", input::quotedValue(*word),
                  nearest.empty() ? std::string() : fmt::format(" (did you mean {}?)", input::quotedValue(nearest)),
                  fmt::join(names, ", ")),
      CLI::ExitCodes::ExtrasError);
}

const BoundCommand* Cli::parsedCommand() const {
  for (const auto& command : commands_) {
    if (command->parsed()) return command.get();
  }
  return nullptr;
}

CommandFiles Cli::commandFiles() const {
  const BoundCommand* command = parsedCommand();
  return command ? command->files() : CommandFiles{};
}

std::string Cli::recordFile() const {
  const BoundCommand* command = parsedCommand();
  return command ? command->job().record : std::string();
}

int Cli::dispatch(const std::vector<std::string>& args) {
  const BoundCommand* command = parsedCommand();
  if (!command) throw std::logic_error("Cli::dispatch: no command was parsed");
  const ErrorContext context = command->errorContext();
  const auto run = [command] { return command->run(); };
  CommandFiles files = command->files();
  std::vector<std::string> outputs;  // what a job record lists, before --record joins them
  for (const output::NamedFile& f : files.outputs) {
    if (!f.path.empty()) outputs.push_back(f.path.string());
  }
  const JobOptions job = command->job();
  if (!job.record.empty()) files.outputs.push_back({"--record", job.record});
  // Before anything runs, and before a record is read or written: a --record that names another of
  // the command's files, a folder or a missing folder is refused without writing it.
  const int refused = runReportingErrors(context, [&] {
    if (!job.record.empty()) requireRecordPath(job.record);
    output::requireDistinctFiles(files.outputs, files.inputs);
    return kOk;
  });
  if (refused != kOk) return refused;
  if (job.record.empty()) return runReportingErrors(context, run);
  // A sweep's job: skipped when its record says it is done, recorded whatever its outcome.
  return runRecordedJob(job, args, outputs, context, run);
}

}  // namespace particles::app
