#pragma once
// Job records (docs/sweeps.md): what makes a sweep's jobs idempotent under any engine. A command
// given `--record FILE` (run, render, stability, concat) first reads FILE: when it records the
// same command line run by the same version, exit 0 and every output still present, the command
// is skipped, so a killed sweep resumes where it stopped whether it runs here, under GNU parallel
// or as a Slurm array; `--force` runs it anyway. After running, whatever the outcome, it writes
// FILE (atomically, after its outputs): version, command, exit code, error message, seconds, outputs
// and the job's headline numbers, which `particles gather` collects into one table.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/exit_codes.hpp"

namespace CLI {
class App;
}

namespace particles::app {

struct JobOptions {
  std::string record;  // --record FILE; empty: not a sweep job
  bool force = false;  // --force: run even when the record says done
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

// The arguments as one shell command line, each quoted where the shell would read it otherwise,
// without --force (a forced rerun is the same job).
std::string commandText(const std::vector<std::string>& args);
std::string shellQuote(const std::string& arg);

// nullopt when the file is missing or is not a record.
std::optional<JobRecord> readJobRecord(const std::filesystem::path& file);
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
