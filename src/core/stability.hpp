#pragma once
// The time-step stability study (the report's headline table): for each integrator, the largest
// dt at which a scenario stays stable over its duration, and the largest at which it also runs
// smoothly, found by bracketing and bisection. Simulation only. docs/stability.md defines the
// criteria; in short, a run at dt is
//   exploded   when the state becomes non-finite or the solver's explosion guard trips,
//   runaway    when the total energy ever exceeds its bound by more than energyTolerance × S:
//              a passive system's energy never rises above E(0); the scripted mouse adds the work
//              W(t) its moving target does, so the bound is E(0) + W(t). S is the system's energy
//              scale (System::energyScale), which makes the tolerance independent of units,
//   overstretched when any spring's length over rest length ever exceeds maxStretch. The study
//              sets maxStretch to stretchFactor × the largest such ratio of a reference run (RK4
//              at a quarter of the scenario's dt): a scripted drag may stretch a soft spring a lot
//              in a correct simulation, so the bound must come from one,
//   shaking    when, over the second half of the run, the second difference of the velocities,
//              ¼|v[n+1] − 2v[n] + v[n−1]|, exceeds shakeThreshold of their RMS. For motion at a
//              single frequency ω the ratio is sin²(ωh/2); 0.1 is ωh = 0.64, under ten steps per
//              period of the motion that carries the velocity — a sustained jitter near the step
//              rate that a converged simulation (ωh ≪ 1) does not show. Measured on the demos:
//              converged runs stay below 0.01 (cloth, RK4 at 0.01 s: 0.007; soft body, RK4 at the
//              report's 0.15: 0.063), runs just inside the stability limit reach 0.15–0.43,
//   stable     otherwise.
// "Stable" below means not exploded, runaway or overstretched; "smooth" means stable and not shaking.

#include <functional>
#include <string>
#include <vector>

#include "core/integrators.hpp"
#include "core/system.hpp"

namespace particles {

struct StabilityCriteria {
  double energyTolerance = 0.1;  // of the energy scale S
  double maxStretch = 1e300;     // spring length / rest length; the study derives it (see above)
  double shakeThreshold = 0.1;   // see "shaking" above
};

enum class RunVerdict { stable, shaking, exploded, runaway, overstretched };
std::string_view verdictName(RunVerdict verdict);

struct RunAssessment {
  RunVerdict verdict = RunVerdict::stable;
  long steps = 0;             // steps taken (fewer than planned when the run stopped early)
  double maxEnergyExcess = 0; // max (E − E(0) − W) / S
  double maxStretch = 0;      // max |l| / rest over all springs
  double shakingIndex = 0;    // see above
  std::string detail;         // for exploded runs, the solver's message
  bool stable() const { return verdict == RunVerdict::stable || verdict == RunVerdict::shaking; }
  bool smooth() const { return verdict == RunVerdict::stable; }
};

using SystemFactory = std::function<System()>;

// Runs a fresh system for `duration` seconds at step dt and judges it.
RunAssessment assessRun(const SystemFactory& make, Integrator integrator, double dt, double duration,
                        const StabilityCriteria& criteria);

struct StabilityOptions {
  StabilityCriteria criteria;      // maxStretch is replaced by stretchFactor × the reference's
  double stretchFactor = 1.5;      // × the reference run's largest stretch
  double referenceDt = 0.0025;     // RK4 step of the reference run (e.g. the scenario's dt / 4)
  // An unstable reference is retried at half the step, down to this; 0: no retry. A stiff scene
  // whose dt suits an implicit integrator (cloth_stiff: one backward Euler step per frame) needs
  // an RK4 reference several times finer than dt / 4.
  double minReferenceDt = 0.0;
  double startDt = 0.01;          // where bracketing starts (e.g. the scenario's dt)
  double minDt = 1e-6;            // below this the search gives up: nothing is stable
  double maxDt = 10.0;            // above this the search stops growing: stable beyond measure
  double relativePrecision = 0.005;  // bisection stops when (hi − lo) ≤ this × lo: 2 significant digits
  // Trial runs at once (below 1: one), each on one thread; the caller decides (the program: --threads).
  // The table is the same for every count (core/worker_pool.hpp); only the wall-clock timings may differ.
  int threads = 1;
  double timingBudget = 0.5;      // s of timed runs per integrator (at least one run); 0: no timing
  // Costs of an integrator still smooth at maxDt are given at this step instead (the frame
  // interval, 1/fps: an animation takes at least one step per frame); 0: at maxDt.
  double costDtCap = 0.0;
};

struct StabilityResult {
  Integrator integrator;
  int evalsPerStep = 0;
  double maxStableDt = 0;    // 0 when nothing down to minDt was stable
  double maxSmoothDt = 0;
  double costDt = 0;             // the step the costs are given at: maxSmoothDt, or costDtCap when smoothAtMaxDt
  double evalsPerSimSecond = 0;  // evalsPerStep / costDt: the cost at the largest usable step
  double speedVsEuler = 0;       // Euler's evals per simulated second / this one's
  // Wall-clock seconds per simulated second at costDt, measured (the fastest of a few timed
  // runs, one integrator at a time): an implicit step costs Jacobians and a sparse solve besides
  // its one evaluation, so evaluations alone no longer compare integrators fairly. 0 when
  // nothing was smooth or the study was asked not to time.
  double wallPerSimSecond = 0;
  // The search reached options.maxDt with the verdict still good: the limit lies beyond what was
  // tried (backward Euler's, which damps instead of blowing up), and the dt shown is maxDt itself.
  bool stableAtMaxDt = false, smoothAtMaxDt = false;
  int runs = 0;                  // simulations the search needed
  RunAssessment firstUnstable;   // the run just above maxStableDt (why it failed)
  RunAssessment firstShaking;    // the run just above maxSmoothDt
};

struct StabilityStudy {
  RunAssessment reference;  // the RK4 run the stretch bound comes from
  double referenceDt = 0;   // its step: options.referenceDt, halved while it was unstable
  double maxStretch = 0;    // the bound used: stretchFactor × reference.maxStretch
  std::vector<StabilityResult> results;
};

// Largest dt in [minDt, maxDt] for which `ok` holds, assuming it holds below some threshold and
// fails above (bracketing by factors of 2, then bisection). Returns 0 when even minDt fails.
// `lastFail` receives the assessment of the last failing run, which is the one at the smallest
// failing dt tried (each failure lowers the upper bracket); it is left as it was when no dt
// failed. `runs` is increased by the number of simulations run.
double findLargestDt(const std::function<RunAssessment(double)>& run, const std::function<bool(const RunAssessment&)>& ok,
                     const StabilityOptions& options, int& runs, RunAssessment& lastFail);

// Rounds down to two significant digits (0.0137 → 0.013): the precision the search guarantees.
double roundDownTwoDigits(double x);

// Runs the reference, then every integrator's search (searchIntegrator in the .cpp) and timing on
// options.threads threads: the same table, bit for bit, on any number of them. Throws
// std::runtime_error when the reference run itself is not stable (its dt is too large).
StabilityStudy findStabilityLimits(const SystemFactory& make, double duration, const std::vector<Integrator>& integrators,
                                   const StabilityOptions& options);

}  // namespace particles
