#include "core/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/parallel_study.hpp"
#include "core/solver.hpp"

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

  out.results = runParallelStudy(make, duration, integrators, options, threads);

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
