#include "core/parallel_study.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <set>
#include <utility>

#include "core/worker_pool.hpp"

namespace particles {

namespace {

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

std::vector<StabilityResult> runParallelStudy(const SystemFactory& make, double duration,
                                              const std::vector<Integrator>& integrators,
                                              const StabilityOptions& options, int threads) {
  return ParallelStudy(make, duration, integrators, options).run(threads);
}

}  // namespace particles
