#pragma once
// A sweep's job table, OUT/jobs.csv (docs/sweeps.md): one row per job with its index, stage,
// scenario, parameter values, segment, folder and command line. `particles sweep` writes it;
// `particles job` runs a row of it and `particles gather` reads all of them. The folder may have
// been touched by anyone since, so reading it checks everything a reader relies on: the fixed
// columns where they belong, no column named twice, each row's index its position and its folder
// jobs/NNNNNN of that index (a row cannot point a reader at another job's record, or outside the
// folder), a command line commandText wrote.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace particles::app {

struct JobTable {
  std::string file;                            // for messages
  std::vector<std::string> parameters;         // the parameter columns, in order
  std::vector<std::vector<std::string>> rows;  // each with every column of the header
  std::vector<int> rowLines;                   // the line each row starts on

  static constexpr size_t kIndex = 0, kStage = 1, kScenario = 2;
  size_t segmentColumn() const { return kScenario + 1 + parameters.size(); }
  size_t dirColumn() const { return segmentColumn() + 1; }
  size_t commandColumn() const { return segmentColumn() + 2; }
  size_t parameterColumn(size_t p) const { return kScenario + 1 + p; }
};

// A job's folder relative to the output folder: jobs/NNNNNN.
std::string jobFolder(size_t index);

// The header jobs.csv starts with.
std::vector<std::string> jobTableHeader(const std::vector<std::string>& parameters);

// Throws InputError naming `file` and the line.
JobTable parseJobTable(std::string_view text, const std::string& file);
// OUT/jobs.csv, a regular file within maxInputMiB; throws InputError.
JobTable readJobTable(const std::filesystem::path& outDir, std::uintmax_t maxInputMiB);

}  // namespace particles::app
