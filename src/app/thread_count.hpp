#pragma once
// How many threads a simulation runs on (core/worker_pool.hpp): --threads N, else the environment
// variable PARTICLES_THREADS (for CI and job scripts), else the CPUs this process may use
// (availableCores: its affinity mask and cgroup quota, so a container limited to 2 CPUs on a
// 64-core host starts 2). Results are the same bits for every count; only the time changes.

#include "core/worker_pool.hpp"

namespace particles::app {

inline constexpr const char* kThreadsEnvironmentVariable = "PARTICLES_THREADS";
using particles::kMaxThreads;  // core/worker_pool.hpp

// `option` is --threads' value, 0 when not given. Throws InputError (exit 2) for a
// PARTICLES_THREADS that is not a whole number from 1 to kMaxThreads.
int threadCountOf(int option);

}  // namespace particles::app
