#pragma once
// How long a sweep's job will take, roughly, so that `particles sweep` can start the longest jobs
// first (docs/sweeps.md, "Order and threads"): a job's cost is the work of its simulation,
//   steps × derivative evaluations per step × size,   size = points + springs,
// in arbitrary units, comparable between the jobs of one sweep (they all run one command).
//
// The steps are the scenario's, duration / dt, except for a stability study: its searches end at
// each integrator's stability limit, whatever dt the scenario gives, and those limits fall with
// the stiffest mode's angular frequency ω_max (hω < 2 for symplectic Euler and Verlet, 2.8 for
// RK4; the cloth's measured limits follow 1/ω_max: docs/sweep_cloth_stiffness.csv). So a study
// is counted as stepping at min(dt, 2/ω_max): four times stiffer springs, twice the steps.

#include <string_view>

#include "core/system.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

// The largest angular frequency of the system's small oscillations about its current state,
// rad/s: √λ_max of the stiffness per mass W·K (K = −∂F/∂x), by power iteration on finite
// differences of derivEval's accelerations (forces and colliders; constraint forces left out).
// A fixed start vector and iteration count: the same bits every time. 0 for a system without
// stiffness. Costs a few dozen derivative evaluations; `system` is only read from, though
// derivEval's scratch space is reused.
double fastestAngularFrequency(System& system);

// The job's estimated cost (see the top of this file) for `command`: run, render (or a segment of
// one) or stability.
double estimatedJobCost(scenario::Scenario& scenario, std::string_view command);

// Whether the job keeps more threads than one busy when it has them: a stability study (its
// searches run at once), a render (llvmpipe and x264 take the threads too), or a run of a scene
// large enough that a derivative evaluation has work for several (System::spreadsOverThreads).
bool jobSpreadsOverThreads(const scenario::Scenario& scenario, std::string_view command);

}  // namespace particles::app
