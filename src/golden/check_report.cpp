#include "golden/check_report.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <set>

#include "golden/references.hpp"
#include "input/available_cores.hpp"
#include "golden/results.hpp"
#include "output/confined_folder.hpp"
#include "output/distinct_files.hpp"
#include "output/output_error.hpp"
#include "output/partial_names.hpp"
#include "input/printable_text.hpp"

namespace particles::golden {

namespace fs = std::filesystem;

namespace {

// The files an earlier report in `folder` consists of: its three pages, the files its results.json
// lists, and the folders they are in. Everything in the folder must be one of those, or the
// folder is no report of ours and is refused (ReportFolderError), left as it is.
std::vector<std::string> earlierReport(const fs::path& folder, std::uintmax_t maxInputMiB,
                                       const std::string& folderName) {
  const std::string shown = input::printableText(folder.string());
  golden::GoldenResults earlier;
  try {
    earlier = golden::readResults(folder, maxInputMiB);
  } catch (const std::exception& e) {
    throw ReportFolderError(
        fmt::format("{} {}: a folder that holds something other than a golden report ({}); choose "
                    "another or empty it (it is replaced whole)",
                    folderName, shown, e.what()));
  }
  // frames/ and states/ are made by every check, kept files or none.
  std::set<std::string> files = golden::reportFiles(earlier), folders = {"frames", "states"};
  for (const std::string& file : files) {
    for (fs::path up = fs::path(file).parent_path(); !up.empty(); up = up.parent_path()) folders.insert(up.string());
  }
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string relative = it->path().lexically_relative(folder).generic_string();
    const fs::file_type type = it->symlink_status(ec).type();
    const bool listed = type == fs::file_type::regular     ? files.count(relative) > 0
                        : type == fs::file_type::directory ? folders.count(relative) > 0
                                                           : false;
    if (!listed) {
      throw ReportFolderError(
          fmt::format("{} {}: it holds {}, which is not part of the golden report there; choose another "
                      "folder or remove it (only a folder that is entirely an earlier report is replaced)",
                      folderName, shown, input::printableText(relative)));
    }
  }
  if (ec) throw ReportFolderError(fmt::format("{} {}: cannot list it: {}", folderName, shown, ec.message()));
  std::vector<std::string> all(files.begin(), files.end());
  all.insert(all.end(), folders.begin(), folders.end());
  return all;
}


}  // namespace

// The report folder: made new, or replacing a folder that is entirely an earlier report (its
// results.json reads back as one, and it holds only what that report lists); anything else is
// refused, not overwritten. That it holds nothing the command reads is the rule of its files
// (goldenFiles, and reportFolderHoldsNoInput for what the manifest names). Returns the earlier
// report's files and folders, the only things `publish` removes.
namespace {

// The folder's identity (device and inode), or nothing where there is none.
std::optional<std::pair<dev_t, ino_t>> folderIdentity(const fs::path& folder) {
  struct stat st {};
  if (::lstat(folder.c_str(), &st) != 0) return std::nullopt;
  return std::pair{st.st_dev, st.st_ino};
}

std::vector<std::string> checkReportFolderOnce(const fs::path& folder, std::uintmax_t maxInputMiB,
                                               const std::string& folderName) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(folder, ec);
  if (st.type() == fs::file_type::not_found) return {};
  const std::string shown = input::printableText(folder.string());
  if (st.type() == fs::file_type::symlink) {
    throw ReportFolderError(
        fmt::format("{} {}: a symbolic link; give the folder itself (it is replaced whole)", folderName, shown));
  }
  if (st.type() != fs::file_type::directory) {
    throw ReportFolderError(fmt::format("{} {}: not a folder; the report is a folder", folderName, shown));
  }
  if (fs::is_empty(folder, ec)) return {};
  return earlierReport(folder, maxInputMiB, folderName);
}

}  // namespace

std::vector<std::string> checkReportFolder(const fs::path& folder, std::uintmax_t maxInputMiB,
                                           const std::string& folderName) {
  // Another check publishing into the same folder meanwhile swaps it whole (publish): a look that
  // began on one folder and ended on another, or on none, read two reports, or neither, and says
  // nothing about either. It is taken again, on the folder as it is then; a few times at most.
  for (int attempt = 0;; ++attempt) {
    const auto before = folderIdentity(folder);
    try {
      std::vector<std::string> earlier = checkReportFolderOnce(folder, maxInputMiB, folderName);
      if (folderIdentity(folder) == before || attempt == 4) return earlier;
    } catch (const ReportFolderError&) {
      if (folderIdentity(folder) == before || attempt == 4) throw;
    }
  }
}


// What the manifest names that `golden check` reads besides the manifest itself (which the
// command line names: goldenFiles): the references' folder and the scenarios. None may lie in
// the report folder, which is replaced whole.
void reportFolderHoldsNoInput(const std::filesystem::path& folder, const std::string& folderName,
                              const std::filesystem::path& manifestFile, const scenario::GoldenManifest& manifest) {
  std::vector<output::NamedFile> inputs = {
      {"the manifest", manifestFile},
      {"the references", manifest.references.empty() ? fs::path(".") : manifest.references}};
  for (const auto* entries : {&manifest.frames, &manifest.states}) {
    for (const scenario::GoldenEntry& e : *entries) inputs.push_back({"the scenario", e.scenario});
  }
  output::requireDistinctFiles({{folderName, folder, true}}, inputs);
}


// The folder the report folder goes in, made when it is not there (a build tree's golden/).
void makeParent(const fs::path& folder) {
  const fs::path parent = fs::absolute(folder).parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", parent.string(), ec.message()));
}

namespace {

// renameat2(2), which glibc 2.28 declares in <stdio.h> only with _GNU_SOURCE: called by number, so
// that the room builds the same everywhere. -1 with errno ENOSYS where the kernel lacks it.
int renameWithFlags(const fs::path& from, const fs::path& to, unsigned flags) {
#if defined(SYS_renameat2)
  return int(::syscall(SYS_renameat2, AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), flags));
#else
  (void)from, (void)to, (void)flags;
  errno = ENOSYS;
  return -1;
#endif
}
constexpr unsigned kRenameNoReplace = 1u << 0;  // RENAME_NOREPLACE
constexpr unsigned kRenameExchange = 1u << 1;   // RENAME_EXCHANGE

// Removes an earlier report that publish moved aside to `aside`: the files and folders its
// results.json lists (checkReportFolder), one by one through its folder's descriptor, deepest
// first, then the folder. Anything else there (put there after the check looked) is left, and said.
void removeEarlierReport(const fs::path& aside, std::uintmax_t maxInputMiB, const std::string& folderName) {
  try {
    std::vector<std::string> earlier = checkReportFolder(aside, maxInputMiB, folderName);
    std::sort(earlier.begin(), earlier.end(), [](const std::string& a, const std::string& b) { return a > b; });
    const output::ConfinedFolder old(aside);
    for (const std::string& entry : earlier) old.remove(entry);
  } catch (const std::exception&) {
    // Left below, said so.
  }
  std::error_code ec;
  if (!fs::remove(aside, ec)) {
    fmt::print(stderr, "note: left {}: it holds files that were not part of the earlier report\n",
               input::printableText(aside.string()));
  }
}

}  // namespace

// Moves the staged report into place in one step where the file system can (renameat2): a new
// folder by RENAME_NOREPLACE, an earlier one by RENAME_EXCHANGE, which swaps the two whole, so the
// folder is never missing and never half one report. The earlier report then sits at the staging
// name and is removed as a report (removeEarlierReport), which also covers another check into the
// same folder at the same time: each swaps its report in, the last one stays, and each removes
// the one it swapped out. Where renameat2 is refused (an older kernel, a file system without it),
// the earlier folder is moved aside to a name of this call's own first (nextPartialPath), and a
// folder that reappears meanwhile is moved aside again, a few times at most.
void publish(output::StagingDirectory& staged, const fs::path& folder, std::uintmax_t maxInputMiB,
             const std::string& folderName) {
  if (renameWithFlags(staged.path(), folder, kRenameNoReplace) == 0) {
    staged.release();
    return;
  }
  if (errno == EEXIST && renameWithFlags(staged.path(), folder, kRenameExchange) == 0) {
    removeEarlierReport(staged.release(), maxInputMiB, folderName);
    return;
  }
  if (errno != ENOSYS && errno != EINVAL && errno != EEXIST) {
    throw output::OutputError(fmt::format("cannot write {}: {}", folder.string(), std::strerror(errno)));
  }
  std::error_code ec;
  for (int attempt = 0;; ++attempt) {
    fs::path aside;
    if (fs::exists(fs::symlink_status(folder, ec))) {
      aside = output::nextPartialPath(folder);
      fs::rename(folder, aside, ec);
      if (ec && ec != std::errc::no_such_file_or_directory) {
        throw output::OutputError(fmt::format("cannot replace {}: {}", folder.string(), ec.message()));
      }
      if (ec) aside.clear();  // gone meanwhile
    }
    fs::rename(staged.path(), folder, ec);
    if (!ec) {
      staged.release();
      if (!aside.empty()) removeEarlierReport(aside, maxInputMiB, folderName);
      return;
    }
    if (!aside.empty()) removeEarlierReport(aside, maxInputMiB, folderName);
    const bool reappeared = ec == std::errc::directory_not_empty || ec == std::errc::file_exists;
    if (!reappeared || attempt == 4) {
      throw output::OutputError(fmt::format("cannot write {}: {}", folder.string(), ec.message()));
    }
  }
}

fs::path reportFolderPath(const fs::path& given, const std::string& folderName) {
  std::string text = given.lexically_normal().string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  const fs::path folder(text);
  if (text.empty() || folder.filename() == "." || folder.filename() == ".." || text == "/") {
    throw ReportFolderError(
        fmt::format("{} {}: name the report folder itself (e.g. golden-report/): it is replaced "
                    "whole",
                    folderName, input::quotedValue(given.string())));
  }
  return folder;
}

std::optional<std::pair<int, int>> shardFromText(const std::string& text, const std::string& optionName) {
  if (text.empty()) return std::nullopt;
  int k = 0, n = 0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, k);
  if (ec == std::errc() && p < end && *p == '/') {
    auto [q, ec2] = std::from_chars(p + 1, end, n);
    if (ec2 == std::errc() && q == end) return std::pair{k, n};
  }
  throw std::invalid_argument(
      fmt::format("{} {}: expected K/N with 1 ≤ K ≤ N, e.g. 1/2", optionName, input::printableText(text)));
}

int defaultJobs() { return std::max(1, input::availableCores() / 2); }

scenario::GoldenManifest loadManifest(const fs::path& file, std::uintmax_t maxInputMiB) {
  scenario::GoldenManifest manifest = scenario::loadGoldenManifestFile(file, maxInputMiB);
  checkRenderSettings(manifest);
  return manifest;
}

CheckRun checkIntoReport(const scenario::GoldenManifest& manifest, const ReportRequest& request) {
  requireReferencesInPlace(manifest, false);
  const fs::path folder = reportFolderPath(request.folder, request.folderName);
  checkReportFolder(folder, request.check.maxInputMiB, request.folderName);
  reportFolderHoldsNoInput(folder, request.folderName, request.manifestFile, manifest);
  makeParent(folder);
  output::StagingDirectory staged(folder);
  const auto start = std::chrono::steady_clock::now();
  CheckRun run = runCheck(manifest, staged.path(), request.check);
  RunFacts& facts = run.results.runs.front();
  facts.manifest = request.check.manifestGiven;
  facts.program = request.program;
  if (const char* threads = std::getenv("LP_NUM_THREADS")) facts.lpNumThreads = threads;
  facts.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeReport(staged.path(), run.results);
  publish(staged, folder, request.check.maxInputMiB, request.folderName);
  return run;
}

}  // namespace particles::golden
