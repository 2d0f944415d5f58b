#pragma once
// How many CPUs this process may use, for the defaults of --jobs: not the machine's cores
// (std::thread::hardware_concurrency) but those of its affinity mask (taskset, a container's
// cpuset), fewer when a cgroup CPU quota allows less (docker --cpus 2 on a 64-core host: 2).

#include <optional>
#include <string_view>

namespace particles::input {

// The CPUs of the affinity mask, capped by the quotas of the process's cgroup and its ancestors
// (v2: cpu.max; v1: cpu.cfs_quota_us over cpu.cfs_period_us), rounded up; at least 1.
int availableCores();

// A cgroup v2 cpu.max ("200000 100000": 2 CPUs; "150000 100000": 2; "max 100000": no limit) in
// whole CPUs, rounded up; nothing for no limit or text that is not a quota.
std::optional<int> coresOfCpuMax(std::string_view text);
// The same from cgroup v1's cpu.cfs_quota_us (-1: no limit) and cpu.cfs_period_us.
std::optional<int> coresOfCfsQuota(std::string_view quota, std::string_view period);

}  // namespace particles::input
