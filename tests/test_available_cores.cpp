// The CPUs a process may use (src/app/available_cores.hpp): cgroup quotas read as whole CPUs,
// rounded up, "max" and -1 as no limit, anything else as nothing; and the count for this process
// between 1 and its affinity mask's CPUs.
#include <doctest/doctest.h>
#include <sched.h>

#include <optional>

#include "input/available_cores.hpp"

using particles::input::availableCores;
using particles::input::coresOfCfsQuota;
using particles::input::coresOfCpuMax;

TEST_CASE("available cores: cgroup v2 cpu.max in whole CPUs, rounded up") {
  CHECK(coresOfCpuMax("200000 100000\n") == std::optional<int>(2));
  CHECK(coresOfCpuMax("150000 100000") == std::optional<int>(2));  // docker --cpus 1.5: 2 threads
  CHECK(coresOfCpuMax("50000 100000\n") == std::optional<int>(1));
  CHECK(coresOfCpuMax("6400000 100000\n") == std::optional<int>(64));
  CHECK_FALSE(coresOfCpuMax("max 100000\n"));
  CHECK_FALSE(coresOfCpuMax(""));
  CHECK_FALSE(coresOfCpuMax("200000"));
  CHECK_FALSE(coresOfCpuMax("0 100000"));
  CHECK_FALSE(coresOfCpuMax("2e5 100000"));
}

TEST_CASE("available cores: cgroup v1 cfs quota and period, -1 meaning no limit") {
  CHECK(coresOfCfsQuota("300000\n", "100000\n") == std::optional<int>(3));
  CHECK(coresOfCfsQuota("100001", "100000") == std::optional<int>(2));
  CHECK_FALSE(coresOfCfsQuota("-1\n", "100000\n"));
  CHECK_FALSE(coresOfCfsQuota("abc", "100000"));
  CHECK_FALSE(coresOfCfsQuota("100000", "0"));
}

TEST_CASE("available cores: between 1 and the CPUs of this process's affinity mask") {
  cpu_set_t set;
  CPU_ZERO(&set);
  REQUIRE(sched_getaffinity(0, sizeof set, &set) == 0);
  const int cores = availableCores();
  CHECK(cores >= 1);
  CHECK(cores <= CPU_COUNT(&set));
}
