#pragma once
// A golden check into its report folder, from the manifest's file to the published report: what
// `particles golden check` does and the library's particles::golden::check (include/particles/
// golden.hpp) does, one function for both; and the report folder's rules, which `golden report`
// follows too. The folder is replaced whole: made new, or replacing a folder that is entirely an
// earlier report, never anything else, and none of the check's inputs may lie in it.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "golden/check.hpp"
#include "output/staging_directory.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

// A report folder that may not be replaced (it holds something else, is a link or a file), or
// one of the check's inputs inside it: bad input (the command's exit 2).
class ReportFolderError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The manifest read and its entries' render settings checked (checkRenderSettings). Throws
// ScenarioError.
scenario::GoldenManifest loadManifest(const std::filesystem::path& file, std::uintmax_t maxInputMiB);

// The report folder as it is: nothing (or empty), or an earlier report, whose files and folders
// are returned (the only things publish removes); anything else is refused (ReportFolderError,
// naming the folder as `folderName`, "-o" or "output", says).
std::vector<std::string> checkReportFolder(const std::filesystem::path& folder, std::uintmax_t maxInputMiB,
                                           const std::string& folderName);

// None of what the check reads (the manifest, the references' folder, the scenarios) lies in the
// report folder. Throws output::SameFileError.
void reportFolderHoldsNoInput(const std::filesystem::path& folder, const std::string& folderName,
                              const std::filesystem::path& manifestFile, const scenario::GoldenManifest& manifest);

// The folder the report folder goes in, made when it is not there. Throws OutputError.
void makeParent(const std::filesystem::path& folder);

// The report folder as given, without trailing separators ("report/" is "report"), so that its
// siblings (the staged report, an earlier one moved aside) are made beside it, not in it.
// ReportFolderError for a path that names no folder of its own: "", ".", "..", "/".
std::filesystem::path reportFolderPath(const std::filesystem::path& given, const std::string& folderName);

// Moves the staged report into the folder (reportFolderPath's) in one step where the file system
// can, then removes the earlier report it replaced, as a report (checkReportFolder's list): another
// check into the same folder at the same time is safe. Throws OutputError.
void publish(output::StagingDirectory& staged, const std::filesystem::path& folder, std::uintmax_t maxInputMiB,
             const std::string& folderName);

// --shard's K/N ("2/3" → {2, 3}), nothing for empty text; std::invalid_argument naming it as
// `optionName` otherwise. Its range is runCheck's to check.
std::optional<std::pair<int, int>> shardFromText(const std::string& text, const std::string& optionName);

// How many entries a check runs at once when not told: half the CPUs this process may use (each
// entry's frames are drawn by llvmpipe's own threads), at least 1.
int defaultJobs();

struct ReportRequest {
  std::filesystem::path manifestFile;
  std::filesystem::path folder;     // the report folder
  std::string folderName = "-o";    // how messages name it
  std::string program;              // `particles 0.1.0`, the run's facts
  CheckOptions check;               // what to check and how (check.hpp)
};

// Checks the manifest's selected frames and states into the report folder, replaced whole when
// the report is complete: report.html, junit.xml, results.json and the kept files. Throws
// ReportFolderError or std::invalid_argument (--only, --shard) for bad input, SameFileError,
// OutputError; a check that could not run is its result's `error`.
CheckRun checkIntoReport(const scenario::GoldenManifest& manifest, const ReportRequest& request);

}  // namespace particles::golden
