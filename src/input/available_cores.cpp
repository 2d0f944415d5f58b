#include "input/available_cores.hpp"

#include <sched.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "input/text_file.hpp"

namespace particles::input {

namespace {

namespace fs = std::filesystem;

// A whole number ending the text or followed by white space; nothing otherwise.
std::optional<long long> wholeNumber(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  long long x = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return x;
}

std::optional<int> coresOf(long long quota, long long period) {
  if (quota <= 0 || period <= 0) return std::nullopt;
  return int(std::min<long long>((quota + period - 1) / period, 1 << 20));
}

// A small file of /proc or /sys, or nothing.
std::optional<std::string> readSmall(const fs::path& file) {
  try {
    return input::readTextFile(file, 1);
  } catch (const input::ReadError&) {
    return std::nullopt;
  }
}

// The process's cgroup paths: "" → its v2 path; a controller list holding "cpu" → its v1 path.
struct CgroupPaths {
  std::optional<std::string> v2, v1cpu;
};

CgroupPaths cgroupPaths() {
  CgroupPaths out;
  const std::optional<std::string> text = readSmall("/proc/self/cgroup");
  if (!text) return out;
  size_t at = 0;
  while (at < text->size()) {
    const size_t end = std::min(text->find('\n', at), text->size());
    const std::string_view line(text->data() + at, end - at);
    at = end + 1;
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string_view::npos || second == std::string_view::npos) continue;
    const std::string_view controllers = line.substr(first + 1, second - first - 1);
    const std::string path(line.substr(second + 1));
    if (controllers.empty()) {
      out.v2 = path;
      continue;
    }
    for (size_t c = 0; c <= controllers.size();) {
      const size_t comma = std::min(controllers.find(',', c), controllers.size());
      if (controllers.substr(c, comma - c) == "cpu") out.v1cpu = path;
      c = comma + 1;
    }
  }
  return out;
}

// The smallest quota of `leaf` and its ancestors below `root`, each read by `quotaAt`.
template <class QuotaAt>
std::optional<int> smallestQuota(const fs::path& root, const std::string& leaf, QuotaAt quotaAt) {
  std::optional<int> smallest;
  for (fs::path p = fs::path(leaf).relative_path();; p = p.parent_path()) {
    if (const std::optional<int> q = quotaAt(root / p)) smallest = smallest ? std::min(*smallest, *q) : *q;
    if (p.empty()) break;
  }
  return smallest;
}

}  // namespace

std::optional<int> coresOfCpuMax(std::string_view text) {
  const size_t space = text.find(' ');
  if (space == std::string_view::npos) return std::nullopt;
  const std::optional<long long> quota = wholeNumber(text.substr(0, space));
  const std::optional<long long> period = wholeNumber(text.substr(space + 1));
  if (!quota || !period) return std::nullopt;  // "max": no limit
  return coresOf(*quota, *period);
}

std::optional<int> coresOfCfsQuota(std::string_view quota, std::string_view period) {
  const std::optional<long long> q = wholeNumber(quota), p = wholeNumber(period);
  if (!q || !p) return std::nullopt;
  return coresOf(*q, *p);
}

int availableCores() {
  int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) cores = std::max(1, CPU_COUNT(&set));
  const CgroupPaths paths = cgroupPaths();
  std::optional<int> quota;
  if (paths.v2) {
    quota = smallestQuota("/sys/fs/cgroup", *paths.v2, [](const fs::path& dir) -> std::optional<int> {
      const std::optional<std::string> text = readSmall(dir / "cpu.max");
      return text ? coresOfCpuMax(*text) : std::nullopt;
    });
  }
  if (!quota && paths.v1cpu) {
    for (const char* mount : {"/sys/fs/cgroup/cpu", "/sys/fs/cgroup/cpu,cpuacct"}) {
      quota = smallestQuota(mount, *paths.v1cpu, [](const fs::path& dir) -> std::optional<int> {
        const std::optional<std::string> q = readSmall(dir / "cpu.cfs_quota_us");
        const std::optional<std::string> p = readSmall(dir / "cpu.cfs_period_us");
        return q && p ? coresOfCfsQuota(*q, *p) : std::nullopt;
      });
      if (quota) break;
    }
  }
  return std::max(1, quota ? std::min(cores, *quota) : cores);
}

}  // namespace particles::input
