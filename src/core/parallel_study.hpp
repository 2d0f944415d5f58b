#pragma once
// Internal to the core: the stability study's searches run in parallel (findStabilityLimits,
// core/stability.hpp), and what they share with the serial search of stability.cpp.
//
// The trials of all the integrators' searches form one queue that the
// `threads` tasks of a WorkerPool take from, one search loop each; the table is the serial one
// because a search's next dt is decided only by replaying the serial search (searchIntegrator)
// over finished trials, and a trial's outcome depends on its dt alone (point 3 of the contract in
// core/worker_pool.hpp: the order in which verdicts arrive changes which trials start, never a
// verdict kept).
//
// Integrators are independent, but each search is a chain: every probe waits for the previous
// one's verdict. Explicit Euler's chain is most of the cloth's study (23 trials at the smallest
// steps), so near the end one thread would have it alone. Threads with nothing certain to do
// therefore run trials the search may need next: the replay, given a guess for a running trial's
// verdict, names the probe after it. Only finished trials ever answer a replay, so a wrong guess
// costs time, never a different table; a guessed trial whose branch a verdict rules out is
// abandoned at once.

#include <atomic>
#include <functional>
#include <optional>
#include <vector>

#include "core/stability.hpp"

namespace particles {

// assessRun with the system on `threads` threads (0: as `make` built it). Returns nothing when
// *abandoned becomes true during the run: a speculative trial that the search no longer needs
// (findStabilityLimits) gives its thread back at once instead of at the end of the run.
std::optional<RunAssessment> assessRunUnlessAbandoned(const SystemFactory& make, Integrator integrator, double dt,
                                                      double duration, const StabilityCriteria& criteria, int threads,
                                                      const std::atomic<bool>* abandoned);

// One integrator's search as the serial study runs it: the largest stable dt, then the largest
// smooth one, from the assessments `run` returns. It is a pure function of those assessments,
// which is what lets the parallel study replay it.
StabilityResult searchIntegrator(Integrator integrator, const StabilityOptions& options,
                                 const std::function<RunAssessment(double)>& run);

// Every integrator's search on `threads` threads (of a WorkerPool of its own): the serial
// searches' results, in the order of `integrators`, with their timing (wallPerSimSecond).
std::vector<StabilityResult> runParallelStudy(const SystemFactory& make, double duration,
                                              const std::vector<Integrator>& integrators,
                                              const StabilityOptions& options, int threads);

}  // namespace particles
