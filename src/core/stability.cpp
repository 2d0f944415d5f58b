#include "core/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

#include "core/solver.hpp"
#include "core/worker_pool.hpp"

namespace particles {

std::string_view verdictName(RunVerdict verdict) {
  switch (verdict) {
    case RunVerdict::stable: return "stable";
    case RunVerdict::shaking: return "shaking";
    case RunVerdict::exploded: return "exploded";
    case RunVerdict::runaway: return "runaway energy";
    case RunVerdict::overstretched: return "overstretched";
  }
  return "unknown";
}

namespace {

double maxSpringStretch(const System& sys) {
  const StateView s = sys.view();
  double worst = 0.0;
  for (const auto& force : sys.forces()) worst = std::max(worst, force->maxStretchRatio(s));
  return worst;
}

}  // namespace

namespace {

// assessRun with the system on `threads` threads (0: as `make` built it). Returns nothing when
// *abandoned becomes true during the run: a speculative trial that the search no longer needs
// (findStabilityLimits) gives its thread back at once instead of at the end of the run.
std::optional<RunAssessment> assessRunUnlessAbandoned(const SystemFactory& make, Integrator integrator, double dt,
                                                      double duration, const StabilityCriteria& criteria, int threads,
                                                      const std::atomic<bool>* abandoned) {
  System sys = make();
  if (threads > 0) sys.setThreads(threads);
  Solver solver(integrator);
  RunAssessment a;
  const long steps = std::max(1L, std::lround(duration / dt));
  const double scale = sys.energyScale();
  std::vector<const Force*> scripted;  // forces that move by themselves: the hand's work
  for (const auto& force : sys.forces()) {
    if (force->isTimeDependent()) scripted.push_back(force.get());
  }
  const double e0 = sys.energy().total();
  double handWork = 0.0;  // W(t): energy the scripted mouse has put in by moving its target
  const StateLayout& layout = sys.layout();
  const Eigen::Index vOff = layout.velocityOffset(), vLen = 2 * Eigen::Index(layout.numPoints());
  Eigen::VectorXd vPrev2, vPrev1;
  double alternating = 0.0, magnitude = 0.0;
  const long checkEvery = std::max(1L, long(1e-3 / dt));

  for (long n = 1; n <= steps; ++n) {
    if (abandoned != nullptr && abandoned->load(std::memory_order_relaxed)) return std::nullopt;
    // The target's motion over this step at fixed positions changes the mouse potential by the
    // work the hand does (first order in dt, enough against the tolerance).
    for (const Force* m : scripted) {
      handWork += m->potentialEnergy(sys.model(), sys.view(), sys.time() + dt) -
                  m->potentialEnergy(sys.model(), sys.view(), sys.time());
    }
    try {
      solver.doStep(sys, dt);
    } catch (const SimulationError& e) {
      a.verdict = RunVerdict::exploded;
      a.detail = e.what();
      return a;
    }
    a.steps = n;
    const Eigen::VectorXd v = sys.state().segment(vOff, vLen);
    if (2 * n > steps && vPrev2.size() == v.size()) {
      alternating += (0.25 * (v - 2.0 * vPrev1 + vPrev2)).squaredNorm();
      magnitude += v.squaredNorm();
    }
    vPrev2 = std::move(vPrev1);
    vPrev1 = v;
    // Energy and stretch cost a pass over every spring: at tiny steps, look at most every
    // millisecond of simulated time (growth over 1 ms is small; the solver still checks every
    // step for non-finite states). Always on the last step.
    if (n % checkEvery != 0 && n != steps) continue;
    a.maxEnergyExcess = std::max(a.maxEnergyExcess, (sys.energy().total() - e0 - handWork) / scale);
    a.maxStretch = std::max(a.maxStretch, maxSpringStretch(sys));
    if (a.maxEnergyExcess > criteria.energyTolerance) {
      a.verdict = RunVerdict::runaway;
      return a;
    }
    if (a.maxStretch > criteria.maxStretch) {
      a.verdict = RunVerdict::overstretched;
      return a;
    }
  }
  a.shakingIndex = magnitude > 0.0 ? std::sqrt(alternating / magnitude) : 0.0;
  if (a.shakingIndex > criteria.shakeThreshold) a.verdict = RunVerdict::shaking;
  return a;
}

}  // namespace

RunAssessment assessRun(const SystemFactory& make, Integrator integrator, double dt, double duration,
                        const StabilityCriteria& criteria) {
  return *assessRunUnlessAbandoned(make, integrator, dt, duration, criteria, 0, nullptr);
}

double roundDownTwoDigits(double x) {
  if (!(x > 0.0)) return 0.0;
  const int exponent = int(std::floor(std::log10(x))) - 1;
  const double scale = std::pow(10.0, std::abs(exponent));
  // The small relative slack keeps an exact 0.013 from becoming 0.012 through round-off; dividing
  // by a power of ten (exact) rather than multiplying by 0.001 (inexact) makes 13e-3 read 0.013.
  const double digits = std::floor((exponent < 0 ? x * scale : x / scale) * (1.0 + 1e-12));
  return exponent < 0 ? digits / scale : digits * scale;
}

double findLargestDt(const std::function<RunAssessment(double)>& run,
                     const std::function<bool(const RunAssessment&)>& ok, const StabilityOptions& options, int& runs,
                     RunAssessment& lastFail) {
  double lo = 0.0, hi = 0.0;
  double dt = std::clamp(options.startDt, options.minDt, options.maxDt);
  auto test = [&](double h) {
    ++runs;
    RunAssessment a = run(h);
    if (ok(a)) return true;
    lastFail = std::move(a);
    return false;
  };
  if (test(dt)) {
    lo = dt;
    while (true) {
      if (lo >= options.maxDt) return lo;
      dt = std::min(2.0 * lo, options.maxDt);
      if (!test(dt)) {
        hi = dt;
        break;
      }
      lo = dt;
    }
  } else {
    hi = dt;
    while (true) {
      dt = 0.5 * hi;
      if (dt < options.minDt) return 0.0;
      if (test(dt)) {
        lo = dt;
        break;
      }
      hi = dt;
    }
  }
  while (hi - lo > options.relativePrecision * lo) {
    const double mid = 0.5 * (lo + hi);
    if (test(mid)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

namespace {

// One integrator's search as the serial study runs it: the largest stable dt, then the largest
// smooth one, from the assessments `run` returns. It is a pure function of those assessments,
// which is what lets the parallel study below replay it.
StabilityResult searchIntegrator(Integrator integrator, const StabilityOptions& options,
                                 const std::function<RunAssessment(double)>& run) {
  StabilityResult r;
  r.integrator = integrator;
  r.evalsPerStep = derivEvalsPerStep(integrator);
  // A limit found by bisection is rounded down to two digits; one at the ceiling is the ceiling.
  auto limit = [&](double found, bool& atMax) {
    atMax = found >= options.maxDt;
    return atMax ? options.maxDt : roundDownTwoDigits(found);
  };
  r.maxStableDt = limit(findLargestDt(
                            run, [](const RunAssessment& a) { return a.stable(); }, options, r.runs, r.firstUnstable),
                        r.stableAtMaxDt);
  // Smooth implies stable, so the smooth limit lies at or below the stable one.
  StabilityOptions smoothOptions = options;
  smoothOptions.startDt = r.maxStableDt > 0.0 ? r.maxStableDt : options.startDt;
  r.maxSmoothDt =
      limit(findLargestDt(
                run, [](const RunAssessment& a) { return a.smooth(); }, smoothOptions, r.runs, r.firstShaking),
            r.smoothAtMaxDt);
  r.maxSmoothDt = std::min(r.maxSmoothDt, r.maxStableDt);
  r.costDt = (r.smoothAtMaxDt && options.costDtCap > 0.0) ? std::min(r.maxSmoothDt, options.costDtCap) : r.maxSmoothDt;
  r.evalsPerSimSecond = r.costDt > 0.0 ? r.evalsPerStep / r.costDt : 0.0;
  return r;
}

// The parallel study. The trials of all the integrators' searches form one queue that the
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

// Thrown by a replayed search at the first dt whose outcome is neither known nor guessed.
struct UnknownProbe {
  double dt;
};

// Guessed verdicts of running trials, by dt: Stable (smooth), Shaking, or Exploded (unstable),
// the three outcomes the two searches tell apart.
using VerdictGuesses = std::map<double, RunVerdict>;

struct IntegratorProgress {
  Integrator integrator;
  std::map<double, RunAssessment> finished;     // by dt
  std::map<double, double> finishedSeconds;     // by dt: each finished trial's wall-clock time
  std::map<double, std::atomic<bool>> running;  // dt → "abandon it" (nodes stay put while running)
  std::optional<StabilityResult> result;        // once the search is complete
  int timedRuns = 0;
  bool timingRunning = false;
  double timedSeconds = 0.0, fastestSeconds = 1e300;
};

// The dt the serial search runs next given the finished trials and `guesses`; nothing when it
// is complete, and then *complete (if given) receives the result.
std::optional<double> nextProbe(const IntegratorProgress& p, const VerdictGuesses& guesses,
                                const StabilityOptions& options, StabilityResult* complete = nullptr) {
  const auto answer = [&](double dt) {
    if (const auto f = p.finished.find(dt); f != p.finished.end()) return f->second;
    const auto g = guesses.find(dt);
    if (g == guesses.end()) throw UnknownProbe{dt};
    RunAssessment guessed;
    guessed.verdict = g->second;
    return guessed;
  };
  try {
    StabilityResult r = searchIntegrator(p.integrator, options, answer);
    if (complete != nullptr) *complete = std::move(r);
    return std::nullopt;
  } catch (const UnknownProbe& unknown) {
    return unknown.dt;
  }
}

// The odds of each verdict class at dt, for choosing guesses: stable or not at even odds, and
// smooth or shaking at even odds when stable, except where the search's own assumption (both are
// monotone in dt) settles it from other verdicts: a stable trial at a larger step makes dt
// stable, an unstable one at a smaller step makes it unstable; the same for smooth. (The smooth
// search's probes above the stable limit are all settled that way.)
std::vector<std::pair<RunVerdict, double>> verdictOdds(const IntegratorProgress& p, const VerdictGuesses& guesses,
                                                       double dt) {
  bool canSmooth = true, canShake = true, canFail = true;
  const auto learn = [&](double at, RunVerdict verdict) {
    const bool stable = verdict == RunVerdict::stable || verdict == RunVerdict::shaking;
    const bool smooth = verdict == RunVerdict::stable;
    if (at > dt && stable) canFail = false;
    if (at > dt && smooth) canShake = false;
    if (at < dt && !stable) canSmooth = canShake = false;
    if (at < dt && !smooth) canSmooth = false;
  };
  for (const auto& [at, assessment] : p.finished) learn(at, assessment.verdict);
  for (const auto& [at, verdict] : guesses) learn(at, verdict);
  if (!canSmooth && !canShake && !canFail) canSmooth = canShake = canFail = true;  // not monotone after all
  std::vector<std::pair<RunVerdict, double>> odds;
  if (canSmooth) odds.emplace_back(RunVerdict::stable, 0.25);
  if (canShake) odds.emplace_back(RunVerdict::shaking, 0.25);
  if (canFail) odds.emplace_back(RunVerdict::exploded, 0.5);
  double total = 0.0;
  for (const auto& [verdict, weight] : odds) total += weight;
  for (auto& [verdict, weight] : odds) weight /= total;
  return odds;
}

// Below this chance of being needed a trial is not started on speculation.
constexpr double kMinSpeculationOdds = 1.0 / 32.0;
// At most this many branches of guesses per integrator and decision (a guard: the odds above
// keep the tree far smaller).
constexpr size_t kMaxGuessBranches = 256;

struct ProbeChances {
  std::map<double, double> startable;  // a dt no trial runs yet → the chance the search needs it
  std::set<double> wanted;             // running trials the search may still need
};

// Follows the search through every combination of verdicts of its running trials: the trials it
// would run next, and which running ones it may still need.
ProbeChances probeChances(const IntegratorProgress& p, const StabilityOptions& options) {
  struct Branch {
    VerdictGuesses guesses;
    double odds;
    double next;
  };
  ProbeChances out;
  std::vector<Branch> branches;
  if (const auto first = nextProbe(p, {}, options)) branches.push_back({{}, 1.0, *first});
  for (size_t k = 0; k < branches.size() && k < kMaxGuessBranches; ++k) {
    const Branch branch = branches[k];  // a copy: push_back below may move the vector
    if (!p.running.contains(branch.next)) {
      out.startable[branch.next] += branch.odds;
      continue;
    }
    out.wanted.insert(branch.next);
    // Verdicts that lead to the same next probe (shaking or smooth, to the stable search) are one
    // branch, guessed as the likelier of them.
    struct Outcome {
      RunVerdict guess;
      double guessOdds, odds;
    };
    std::map<double, Outcome> byNext;
    for (const auto& [verdict, odds] : verdictOdds(p, branch.guesses, branch.next)) {
      VerdictGuesses guesses = branch.guesses;
      guesses[branch.next] = verdict;
      const auto next = nextProbe(p, guesses, options);
      if (!next) continue;  // the search ends there
      auto [it, fresh] = byNext.try_emplace(*next, Outcome{verdict, odds, 0.0});
      if (odds > it->second.guessOdds) it->second.guess = verdict, it->second.guessOdds = odds;
      it->second.odds += odds;
    }
    for (const auto& [next, outcome] : byNext) {
      VerdictGuesses guesses = branch.guesses;
      guesses[branch.next] = outcome.guess;
      branches.push_back({std::move(guesses), branch.odds * outcome.odds, next});
    }
  }
  return out;
}

class ParallelStudy {
 public:
  ParallelStudy(const SystemFactory& make, double duration, const std::vector<Integrator>& integrators,
                const StabilityOptions& options)
      : make_(make), duration_(duration), options_(options), progress_(integrators.size()) {
    for (size_t k = 0; k < integrators.size(); ++k) progress_[k].integrator = integrators[k];
  }

  std::vector<StabilityResult> run(int threads) {
    // One search loop per thread. Any thread's loop finishes the study, so threads the pool could
    // not start, or that arrive late, change the time taken, never the table.
    WorkerPool pool(threads);
    pool.run(size_t(threads), [this](size_t) { work(); });
    if (error_) std::rethrow_exception(error_);
    std::vector<StabilityResult> results;
    for (const IntegratorProgress& p : progress_) {
      StabilityResult r = *p.result;
      if (p.timedRuns > 0) r.wallPerSimSecond = p.fastestSeconds / duration_;
      results.push_back(std::move(r));
    }
    return results;
  }

 private:
  enum class Kind { Probe, Timing };
  struct Task {
    Kind kind = Kind::Probe;
    size_t integrator = 0;
    double dt = 0.0;
  };

  // The most useful trial to start, or nothing: first the probes a search needs for sure, then
  // the timing runs, then probes on speculation, the likeliest first. Among equals, the one of
  // most steps (then the first integrator): the search at the smallest step has the longest chain
  // of costly trials ahead (explicit Euler's is half the cloth's study), so it must never wait.
  std::optional<Task> pick() {
    std::vector<ProbeChances> chances;
    for (const IntegratorProgress& p : progress_) chances.push_back(probeChances(p, options_));
    std::optional<Task> best;
    double bestOdds = 0.0, bestSteps = 0.0;
    const auto consider = [&](Task task, double odds) {
      const double steps = duration_ / task.dt;
      if (!best || odds > bestOdds || (odds == bestOdds && steps > bestSteps)) {
        best = task;
        bestOdds = odds;
        bestSteps = steps;
      }
    };
    for (size_t k = 0; k < progress_.size(); ++k) {
      for (const auto& [dt, odds] : chances[k].startable) {
        if (odds >= 1.0) consider({Kind::Probe, k, dt}, odds);
      }
    }
    if (best) return best;
    for (size_t k = 0; k < progress_.size(); ++k) {
      if (timingWanted(progress_[k])) return Task{Kind::Timing, k, progress_[k].result->costDt};
    }
    for (size_t k = 0; k < progress_.size(); ++k) {
      for (const auto& [dt, odds] : chances[k].startable) {
        if (odds >= kMinSpeculationOdds) consider({Kind::Probe, k, dt}, odds);
      }
    }
    return best;
  }

  // Timed after its search, at the step its costs are given at: the fastest of a few runs, at
  // least one (the search's own trial at that step counts), more while the budget lasts. Each
  // timed run has a thread of its own like any trial, and the study never runs more trials at
  // once than it has threads.
  bool timingWanted(const IntegratorProgress& p) const {
    if (!p.result || p.timingRunning || !timingOn() || p.result->costDt <= 0.0) return false;
    return p.timedRuns == 0 || (p.timedRuns < 5 && p.timedSeconds < options_.timingBudget);
  }

  bool timingOn() const { return options_.timingBudget > 0.0; }

  bool anyRunning() const {
    for (const IntegratorProgress& p : progress_) {
      if (!p.running.empty() || p.timingRunning) return true;
    }
    return false;
  }

  void work() {
    std::unique_lock lock(mutex_);
    while (!error_) {
      const std::optional<Task> task = pick();
      if (!task) {
        if (!anyRunning()) break;  // every search complete and timed
        changed_.wait(lock);
        continue;
      }
      IntegratorProgress& p = progress_[task->integrator];
      std::atomic<bool>* abandon = nullptr;
      if (task->kind == Kind::Timing) {
        p.timingRunning = true;
      } else {
        abandon = &p.running.try_emplace(task->dt).first->second;
      }
      lock.unlock();
      std::optional<RunAssessment> outcome;
      double seconds = 0.0;
      std::exception_ptr error;
      try {
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        outcome = assessRunUnlessAbandoned(make_, p.integrator, task->dt, duration_, options_.criteria, 1, abandon);
        seconds = std::chrono::duration<double>(Clock::now() - start).count();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !error_) {
        error_ = error;
        for (IntegratorProgress& q : progress_) {
          for (auto& [dt, abandoned] : q.running) abandoned = true;
        }
      }
      if (task->kind == Kind::Timing) {
        p.timingRunning = false;
        ++p.timedRuns;
        p.timedSeconds += seconds;
        p.fastestSeconds = std::min(p.fastestSeconds, seconds);
      } else {
        p.running.erase(task->dt);
        if (outcome) {
          p.finished.emplace(task->dt, std::move(*outcome));
          p.finishedSeconds.emplace(task->dt, seconds);
        }
        settle(p);
      }
      changed_.notify_all();
    }
    changed_.notify_all();
  }

  // After a verdict: the result once the search is complete, and abandoning the guessed trials
  // that no branch of the search can reach any more.
  void settle(IntegratorProgress& p) {
    if (!p.result) {
      StabilityResult r;
      if (!nextProbe(p, {}, options_, &r)) {
        // A trial of the search at the cost step (the smooth limit, when the search ran it) is a
        // timed run already: it ran the whole duration at that step on one thread.
        if (const auto ran = p.finishedSeconds.find(r.costDt); ran != p.finishedSeconds.end() && timingOn()) {
          p.timedRuns = 1;
          p.timedSeconds = p.fastestSeconds = ran->second;
        }
        p.result = std::move(r);
      }
    }
    const std::set<double> wanted = probeChances(p, options_).wanted;
    for (auto& [dt, abandoned] : p.running) {
      if (!wanted.contains(dt)) abandoned = true;
    }
  }

  const SystemFactory& make_;
  const double duration_;
  const StabilityOptions& options_;
  std::vector<IntegratorProgress> progress_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::exception_ptr error_;
};

}  // namespace

StabilityStudy findStabilityLimits(const SystemFactory& make, double duration, const std::vector<Integrator>& integrators,
                                   const StabilityOptions& given) {
  const int threads = std::max(1, given.threads);
  StabilityStudy out;
  StabilityCriteria unbounded = given.criteria;
  unbounded.maxStretch = 1e300;
  // The reference runs alone before any search (the searches need its bound): on every thread.
  const auto reference = [&] {
    return *assessRunUnlessAbandoned(make, Integrator::rk4, out.referenceDt, duration, unbounded, threads, nullptr);
  };
  out.referenceDt = given.referenceDt;
  out.reference = reference();
  while (!out.reference.stable() && 0.5 * out.referenceDt >= given.minReferenceDt && given.minReferenceDt > 0.0) {
    out.referenceDt *= 0.5;
    out.reference = reference();
  }
  if (!out.reference.stable()) {
    throw std::runtime_error(fmt::format(
        "the reference run (rk4, dt = {:.3g} s) is itself unstable ({}); give the scenario a smaller dt",
        out.referenceDt, verdictName(out.reference.verdict)));
  }
  out.maxStretch = given.stretchFactor * out.reference.maxStretch;
  StabilityOptions options = given;
  options.criteria.maxStretch = out.maxStretch;

  out.results = ParallelStudy(make, duration, integrators, options).run(threads);

  double eulerCost = 0.0;
  for (const auto& r : out.results) {
    if (r.integrator == Integrator::euler) eulerCost = r.evalsPerSimSecond;
  }
  for (auto& r : out.results) {
    r.speedVsEuler = (eulerCost > 0.0 && r.evalsPerSimSecond > 0.0) ? eulerCost / r.evalsPerSimSecond : 0.0;
  }
  return out;
}

}  // namespace particles
