#pragma once
// Job records (docs/sweeps.md): what makes a sweep's jobs idempotent under any engine. A command
// given `--record FILE` (run, render, stability, concat) first reads FILE: when it records the
// same command line run by the same version, exit 0 and every output still present, the command
// is skipped, so a killed sweep resumes where it stopped whether it runs here, under GNU parallel
// or as a Slurm array; `--force` runs it anyway. After running, whatever the outcome, it writes
// FILE (atomically, after its outputs): version, command, exit code, error message, seconds, outputs
// and the job's headline numbers, which `particles gather` collects into one table.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/exit_codes.hpp"
#include "input/text_file.hpp"
#include "output/shell_words.hpp"

namespace CLI {
class App;
}

namespace particles::app {

struct JobOptions {
  std::string record;                                // --record FILE; empty: not a sweep job
  bool force = false;                                // --force: run even when the record says done
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;  // the record is read within the command's --max-input
};

void addJobOptions(CLI::App& command, JobOptions& options);

// Numbers a command reports about its job (a run's final energy, a study's limits, a render's
// frames), kept for its record. Reported in order; a key reported again replaces its value.
void reportHeadline(const std::string& key, double value);

struct JobRecord {
  std::string version;  // programVersion() of the binary that ran it
  std::string command;  // commandText of its arguments
  int exitCode = -1;
  std::string message;  // the error printed, on one line; empty on success
  double seconds = 0;   // the whole command, loading included
  std::vector<std::string> outputs;
  std::vector<std::pair<std::string, double>> headline;
};

// The arguments as one shell command line (always one line: see shellQuote), without --force (a
// forced rerun is the same job). It is for people to read and copy, and for records to compare:
// the program never hands it to a shell. splitCommandText reads it back into the arguments
// (`particles job` runs a sweep's job from it); nullopt when the text is not commandText's.
std::string commandText(const std::vector<std::string>& args);
std::optional<std::vector<std::string>> splitCommandText(std::string_view text);
// shellQuote: output/shell_words.hpp.
using output::isPlainShellChar;
using output::shellQuote;

// nullopt when the file is missing or is not a record. A file that cannot be read as one (a
// FIFO, a device, a file past maxInputMiB, binary bytes) throws input::ReadError: such a thing
// was not written by a job, and reading it could block or exhaust memory.
std::optional<JobRecord> readJobRecord(const std::filesystem::path& file, std::uintmax_t maxInputMiB);
// The record a text holds; nullopt when it is not one. Linear in the text.
std::optional<JobRecord> parseJobRecord(std::string_view text);
// Throws output::OutputError.
void writeJobRecord(const std::filesystem::path& file, const JobRecord& record);

// Whether `record` shows this command done by this binary (exit 0, outputs present); when not,
// `why` says what differs, for messages.
bool jobDone(const std::optional<JobRecord>& record, const std::string& command, std::string* why = nullptr);

// The version jobs are recorded with.
std::string programVersion();

// Refuses (InputError) a --record that could not be written, before the job runs: a path that is
// a directory, a FIFO or anything else not a regular file, or one in a folder that does not exist.
void requireRecordPath(const std::filesystem::path& record);

// Runs `command` as a recorded job (see the top of this file) and returns its exit code.
int runRecordedJob(const JobOptions& options, const std::vector<std::string>& args,
                   const std::vector<std::string>& outputs, const ErrorContext& context,
                   const std::function<int()>& command);

}  // namespace particles::app
