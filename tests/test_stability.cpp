// The stability search against cases with a closed-form limit.
#include <doctest/doctest.h>

#include <cmath>

#include "core/stability.hpp"
#include "sanitizer.hpp"
#include "skip.hpp"
#include "support.hpp"

using namespace particles;
using namespace particles::test;

TEST_CASE("stable steps are rounded down to two significant digits, to the double nearest the decimal") {
  CHECK(roundDownTwoDigits(0.0137) == doctest::Approx(0.013));
  CHECK(roundDownTwoDigits(0.013) == doctest::Approx(0.013));
  CHECK(roundDownTwoDigits(2.83) == doctest::Approx(2.8));
  CHECK(roundDownTwoDigits(150.0) == doctest::Approx(150.0));
  CHECK(roundDownTwoDigits(0.0) == 0.0);
  // Exactly the double nearest the decimal, so CSV files read 0.013, not 0.013000000000000001.
  CHECK(roundDownTwoDigits(0.0131) == 0.013);
  CHECK(roundDownTwoDigits(0.00549) == 0.0054);
}

namespace {

// A linear oscillator: rest length 10 m against amplitudes well below it, so the spring never
// folds through its anchor (which would make it nonlinear) while the search probes unstable steps.
System linearOscillator(double k, double kd) {
  SystemBuilder b;
  const int anchor = b.addParticle(particleAt(0, 0, 1.0, true));
  const int bob = b.addParticle(particleAt(10.5, 0));
  b.emplaceForce<DampedSpringForce>().add({Endpoint::ofParticle(bob), Endpoint::ofParticle(anchor), 10.0, k, kd});
  return b.build();
}

}  // namespace

TEST_CASE("RK4 on an undamped oscillator is stable up to h·omega = 2*sqrt(2)") {
  // |R(iy)| = 1 at y = 2√2 for RK4's stability polynomial R(z) = 1 + z + z²/2 + z³/6 + z⁴/24;
  // just above it the energy grows 30 % per step, just below it decays.
  const double omega = 1.0;  // k = 1, m = 1
  const SystemFactory make = [] { return linearOscillator(1.0, 0.0); };
  StabilityOptions options;
  options.startDt = 0.1;
  options.referenceDt = 0.01;
  const auto results = findStabilityLimits(make, 300.0, {Integrator::rk4}, options).results;
  REQUIRE(results.size() == 1);
  const double limit = 2.0 * std::sqrt(2.0) / omega;
  CAPTURE(results[0].maxStableDt);
  CHECK(results[0].maxStableDt == doctest::Approx(limit).epsilon(0.02));
  CHECK(results[0].maxStableDt <= limit * 1.005);
  CHECK(results[0].firstUnstable.verdict != RunVerdict::stable);
  CHECK(results[0].maxSmoothDt <= results[0].maxStableDt);
}

TEST_CASE("explicit Euler on a damped oscillator is stable up to h = c / omega^2") {
  // One particle stepped some 10^6 times by the stability search on one thread: 29 s under ASan +
  // UBSan and 16 s under TSan for no code that the shorter studies here do not reach there.
  if (kUnderSanitizer) return skipTest("a stability limit's numbers: checked in the plain build, not under a sanitizer");
  // Eigenvalues λ = −c/2 ± i√(ω² − c²/4); |1 + hλ|² = 1 + h (h ω² − c) ≤ 1  ⇔  h ≤ c/ω².
  // k = 100 N/m, m = 1 kg, k_d = 2 N·s/m: ω² = 100, c = 2, h_max = 0.02 s.
  const SystemFactory make = [] { return linearOscillator(100.0, 2.0); };
  StabilityOptions options;
  options.startDt = 0.001;
  options.referenceDt = 0.001;
  const auto results = findStabilityLimits(make, 400.0, {Integrator::euler, Integrator::midpoint}, options).results;
  REQUIRE(results.size() == 2);
  CAPTURE(results[0].maxStableDt);
  CHECK(results[0].maxStableDt == doctest::Approx(0.02).epsilon(0.02));
  CHECK(results[0].evalsPerStep == 1);
  CHECK(results[0].evalsPerSimSecond == doctest::Approx(1.0 / results[0].maxSmoothDt));
  CHECK(results[0].speedVsEuler == doctest::Approx(1.0));
  // Midpoint survives a larger step on the same problem and reports its cost relative to Euler.
  CHECK(results[1].maxStableDt > results[0].maxStableDt);
  CHECK(results[1].speedVsEuler == doctest::Approx(results[0].evalsPerSimSecond / results[1].evalsPerSimSecond));
}

TEST_CASE("a run that explodes, overstretches or shakes is classified as such") {
  const SystemFactory make = [] { return linearOscillator(100.0, 0.0); };  // ω = 10
  StabilityCriteria criteria;
  const RunAssessment smooth = assessRun(make, Integrator::rk4, 0.001, 5.0, criteria);
  CHECK(smooth.verdict == RunVerdict::stable);
  CHECK(smooth.shakingIndex == doctest::Approx(std::pow(std::sin(0.01 / 2), 2)).epsilon(0.01));
  CHECK(smooth.maxStretch == doctest::Approx(1.05).epsilon(1e-3));
  // ωh = 0.5: about 13 steps per period, sin²(¼) = 0.061 < 0.1: smooth.
  const RunAssessment resolved = assessRun(make, Integrator::rk4, 0.05, 20.0, criteria);
  CHECK(resolved.verdict == RunVerdict::stable);
  CHECK(resolved.shakingIndex == doctest::Approx(std::pow(std::sin(0.25), 2)).epsilon(0.02));
  // ωh = 1: six steps per period, sin²(½) = 0.23 > 0.1: shaking, though stable.
  const RunAssessment coarse = assessRun(make, Integrator::rk4, 0.1, 20.0, criteria);
  CHECK(coarse.verdict == RunVerdict::shaking);
  CHECK(coarse.stable());
  CHECK(coarse.shakingIndex == doctest::Approx(std::pow(std::sin(0.5), 2)).epsilon(0.02));
  const RunAssessment blown = assessRun(make, Integrator::euler, 0.05, 50.0, criteria);
  CHECK_FALSE(blown.stable());
  // Just inside RK4's limit (ωh = 2.7) the oscillator survives but alternates step by step.
  const RunAssessment shaking = assessRun(make, Integrator::rk4, 0.27, 20.0, criteria);
  CAPTURE(shaking.shakingIndex);
  CHECK(shaking.verdict == RunVerdict::shaking);
  StabilityCriteria strict = criteria;
  strict.maxStretch = 1.04;
  CHECK(assessRun(make, Integrator::rk4, 0.001, 5.0, strict).verdict == RunVerdict::overstretched);
}

TEST_CASE("an integrator that never fails is reported at the ceiling, and costed at the cap") {
  // An overdamped oscillator (k = 100, c = 100: rates 1 and 99 s⁻¹, no oscillation): backward
  // Euler is stable and smooth at any step, so the search stops at maxDt, the result says so, and
  // the costs are given at costDtCap; RK4 is limited by the fast rate (h < 2.78 / 99).
  const SystemFactory make = [] { return linearOscillator(100.0, 100.0); };
  StabilityOptions options;
  options.referenceDt = 0.001;
  options.startDt = 0.01;
  options.maxDt = 0.5;
  options.costDtCap = 0.04;
  options.timingBudget = 0.0;
  const StabilityStudy study = findStabilityLimits(make, 5.0, {Integrator::backwardEuler, Integrator::rk4}, options);
  const StabilityResult& be = study.results[0];
  CHECK(be.stableAtMaxDt);
  CHECK(be.smoothAtMaxDt);
  CHECK(be.maxStableDt == 0.5);
  CHECK(be.maxSmoothDt == 0.5);
  CHECK(be.costDt == 0.04);
  CHECK(be.evalsPerSimSecond == doctest::Approx(25.0));
  const StabilityResult& rk4 = study.results[1];  // limited below the ceiling: costed at its own step
  CHECK_FALSE(rk4.stableAtMaxDt);
  CHECK(rk4.maxStableDt < 0.5);
  CHECK(rk4.costDt == rk4.maxSmoothDt);
  CHECK(rk4.wallPerSimSecond == 0.0);  // not timed
}

TEST_CASE("the stretch bound comes from a reference run, and an unstable reference is an error") {
  const SystemFactory make = [] { return linearOscillator(100.0, 0.0); };
  StabilityOptions options;
  options.referenceDt = 0.001;
  options.startDt = 0.01;
  const StabilityStudy study = findStabilityLimits(make, 5.0, {Integrator::rk4}, options);
  CHECK(study.reference.maxStretch == doctest::Approx(1.05).epsilon(1e-3));
  CHECK(study.maxStretch == doctest::Approx(1.5 * 1.05).epsilon(1e-3));
  CHECK(study.referenceDt == 0.001);
  options.referenceDt = 0.5;  // ωh = 5: RK4 blows up
  CHECK_THROWS_AS(findStabilityLimits(make, 5.0, {Integrator::rk4}, options), std::runtime_error);
  // Allowed to halve: 0.25 (ωh = 2.5) is inside RK4's limit ωh = 2√2, and is what is used.
  options.minReferenceDt = 0.2;
  const StabilityStudy halved = findStabilityLimits(make, 5.0, {Integrator::rk4}, options);
  CHECK(halved.referenceDt == 0.25);
  CHECK(halved.reference.stable());
  options.minReferenceDt = 0.3;  // no room to halve
  CHECK_THROWS_AS(findStabilityLimits(make, 5.0, {Integrator::rk4}, options), std::runtime_error);
}
