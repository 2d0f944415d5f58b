#include "output/partial_names.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <optional>
#include <string_view>
#include <system_error>

namespace particles::output {

namespace fs = std::filesystem;

namespace {

std::atomic<unsigned long> partialCounter{0};

bool allDigits(std::string_view text) {
  if (text.empty()) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// The pid in "<name>.partial-<pid>-<n>", or nothing when `entry` is not exactly of that form.
std::optional<pid_t> partialPid(std::string_view entry, std::string_view name) {
  const std::string_view marker = ".partial-";
  if (entry.size() <= name.size() + marker.size() || entry.substr(0, name.size()) != name ||
      entry.substr(name.size(), marker.size()) != marker) {
    return std::nullopt;
  }
  const std::string_view numbers = entry.substr(name.size() + marker.size());
  const std::size_t dash = numbers.find('-');
  if (dash == std::string_view::npos) return std::nullopt;
  const std::string_view pidDigits = numbers.substr(0, dash), counterDigits = numbers.substr(dash + 1);
  // Ten digits hold any pid_t; a longer run of digits was not written by us.
  if (!allDigits(pidDigits) || !allDigits(counterDigits) || pidDigits.size() > 10) return std::nullopt;
  long long pid = 0;
  for (char c : pidDigits) pid = pid * 10 + (c - '0');
  // kill(0, …) and kill(-1, …) would mean a process group and every process: not pids.
  if (pid <= 0 || pid > INT_MAX) return std::nullopt;
  return pid_t(pid);
}

bool processIsGone(pid_t pid) {
  return ::kill(pid, 0) != 0 && errno == ESRCH;
}

}  // namespace

fs::path nextPartialPath(const fs::path& beside) {
  fs::path partial = beside;
  partial += fmt::format(".partial-{}-{}", ::getpid(), partialCounter++);
  return partial;
}

int removeStalePartials(const fs::path& directory, const std::string& name) noexcept {
  int removed = 0;
  try {
    std::error_code ec;
    const fs::path listed = directory.empty() ? fs::path(".") : directory;
    for (const fs::directory_entry& entry : fs::directory_iterator(listed, ec)) {
      const std::string entryName = entry.path().filename().string();
      const std::optional<pid_t> pid = partialPid(entryName, name);
      if (!pid) continue;
      struct stat st {};
      if (::lstat(entry.path().c_str(), &st) != 0 || st.st_uid != ::geteuid()) continue;
      if (!S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) continue;
      if (!processIsGone(*pid)) continue;
      // remove_all does not follow links inside the directory: it removes them as entries.
      if (fs::remove_all(entry.path(), ec) > 0 && !ec) ++removed;
    }
  } catch (...) {
    // Cleaning up is a courtesy; it never stands in the way of the output being written.
  }
  return removed;
}

}  // namespace particles::output
