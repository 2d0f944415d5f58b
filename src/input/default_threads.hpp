#pragma once
// How many threads a simulation runs on when the caller names no count: the environment variable
// PARTICLES_THREADS (for CI and job scripts), else the CPUs this process may use (availableCores:
// its affinity mask and cgroup quota, so a container limited to 2 CPUs on a 64-core host starts 2).
// The command line's --threads and the library's particles::defaultThreads() both read it here.

#include <stdexcept>

namespace particles::input {

inline constexpr const char* kThreadsEnvironmentVariable = "PARTICLES_THREADS";

// PARTICLES_THREADS is set but not a whole number from 1 to maxThreads.
class BadThreadCount : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Whether PARTICLES_THREADS is set (to anything but the empty string): a count the user named.
bool threadCountInEnvironment();

// PARTICLES_THREADS when set (throws BadThreadCount for a value that is not a whole number from 1
// to maxThreads), else availableCores() capped at maxThreads.
int defaultThreads(int maxThreads);

}  // namespace particles::input
