#pragma once
// How many threads a simulation runs on (core/worker_pool.hpp): --threads N, else what
// input::defaultThreads says (PARTICLES_THREADS, else the CPUs this process may use). Results are
// the same bits for every count; only the time changes.

#include "core/worker_pool.hpp"
#include "input/default_threads.hpp"

namespace particles::app {

using input::kThreadsEnvironmentVariable;
using particles::kMaxThreads;  // core/worker_pool.hpp

// `option` is --threads' value, 0 when not given. Throws InputError (exit 2) for a
// PARTICLES_THREADS that is not a whole number from 1 to kMaxThreads.
int threadCountOf(int option);

// Whether the user named a thread count (--threads, or PARTICLES_THREADS set): a hard cap on every
// thread the command starts. Without one, the libraries that pick their own counts (x264, llvmpipe)
// keep them (render_command.cpp).
bool threadCountGiven(int option);

}  // namespace particles::app
