#pragma once
// A sweep's job lists (docs/sweeps.md): the planned jobs (app/sweep_plan.hpp) as lines for GNU
// parallel, or as Slurm array scripts, each line or task `PROGRAM job OUT INDEX`. Nothing of the
// sweep's values is in them: only the program and the output folder, quoted, and job numbers.

#include <string>

#include "app/sweep_plan.hpp"

namespace particles::app {

// Throws InputError when the program's or the output folder's path holds a control character,
// which a job list (lines of shell text) cannot hold; checked before anything is written.
void checkListPaths(const SweepPlan& plan);

// --emit parallel: jobs.txt (and concat.txt for split renders), one line `PROGRAM job OUT INDEX`
// per job, for `parallel < jobs.txt`. Returns what to run, for the user (with PARTICLES_THREADS=1:
// parallel runs one job per CPU). Throws InputError when the program's or the output folder's path
// holds a control character.
std::string emitParallel(const SweepPlan& plan);
// --emit slurm: sweep.sbatch (an array job whose task i runs `PROGRAM job OUT i`, with `--threads
// $SLURM_CPUS_PER_TASK` when the task has that many CPUs; concat.sbatch and submit.sh for split
// renders). Returns what to run.
std::string emitSlurm(const SweepPlan& plan);

}  // namespace particles::app
