// The stability study on several threads gives the serial study's table: every field of every
// result (not the wall-clock timings), from the core and from `particles stability`.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <string>
#include <vector>

#include "cli_support.hpp"
#include "core/stability.hpp"
#include "sanitizer.hpp"
#include "scenario/scenario.hpp"

using namespace particles;
using namespace particles::test;

namespace {

// A 6×6 cloth like the demo (stiffness graded with height, a rail on top, a scripted drag), so
// that every verdict occurs: explosions, runaway energy, overstretching after the drag, shaking.
const std::string kSmallCloth =
    "name: small_cloth\n"
    "simulation: {integrator: rk4, dt: 0.01, duration: 1}\n"
    "render: {size: [160, 120], fps: 30, view: {center: [0, 0], height: 2}}\n"
    "grids:\n"
    "  - name: cloth\n"
    "    origin: [-0.2, 0.4]\n"
    "    size: [6, 6]\n"
    "    spacing: [0.08, 0.08]\n"
    "    mass: 0.002\n"
    "    springs:\n"
    "      structural: {ks: [25, 5], kd: 0.01}\n"
    "forces:\n"
    "  - {type: gravity, g: [0, -9.81]}\n"
    "  - {type: drag, kd: 0.002}\n"
    "constraints:\n"
    "  - {type: horizontal_line, particles: \"cloth[0][*]\", y: 0.4}\n"
    "mouse:\n"
    "  - {grab: \"cloth[5][3]\", from: 0.2, to: 0.6, path: [[0, -0.2], [0.3, -0.1]], ks: 2}\n";

// The thread counts compared with one thread. Under ASan + UBSan (build-asan), which looks for bad
// memory, not races, 3 alone: the study's table took 40 s there on 2, 3 and 4 threads.
const std::vector<int> kStudyThreadCounts = kUnderAddressSanitizer ? std::vector<int>{3} : std::vector<int>{2, 3, 4};
const std::vector<int> kCliStudyThreadCounts = kUnderAddressSanitizer ? std::vector<int>{1, 3} : std::vector<int>{1, 2, 3, 4};

StabilityStudy studySmallCloth(const std::vector<Integrator>& integrators, int threads, double timingBudget) {
  const SystemFactory make = [] { return scenario::loadScenarioText(kSmallCloth, "small_cloth.yaml").system; };
  StabilityOptions options;
  options.startDt = 0.01;
  options.referenceDt = 0.0025;
  options.minDt = 1e-5;
  options.maxDt = 1.0;
  options.costDtCap = 1.0 / 30;
  options.timingBudget = timingBudget;
  options.threads = threads;
  return findStabilityLimits(make, 1.0, integrators, options);
}

// Every field of a study but the wall-clock timings, as text: fmt writes a double in the shortest
// form that reads back exactly, so equal texts mean equal bits (and a failure shows the field).
std::string exactly(const RunAssessment& a) {
  return fmt::format("{} after {} steps, energy excess {}, stretch {}, shaking index {}, detail '{}'",
                     verdictName(a.verdict), a.steps, a.maxEnergyExcess, a.maxStretch, a.shakingIndex, a.detail);
}

std::string exactly(const StabilityStudy& study) {
  std::string out = fmt::format("reference at {}: {}; stretch bound {}\n", study.referenceDt, exactly(study.reference),
                                study.maxStretch);
  for (const StabilityResult& r : study.results) {
    out += fmt::format(
        "{}: {} evals/step, stable {} (at max {}), smooth {} (at max {}), cost dt {}, {} evals/s, {}× euler, {} runs\n"
        "  first unstable: {}\n  first shaking: {}\n",
        integratorName(r.integrator), r.evalsPerStep, r.maxStableDt, r.stableAtMaxDt, r.maxSmoothDt, r.smoothAtMaxDt,
        r.costDt, r.evalsPerSimSecond, r.speedVsEuler, r.runs, exactly(r.firstUnstable), exactly(r.firstShaking));
  }
  return out;
}

// The lines of `particles stability`'s output with the last word of the table's heading and rows
// (the measured wall time, right-aligned) removed with the spaces before it.
std::string withoutWallColumn(const std::string& out, size_t rows) {
  std::vector<std::string> kept = lines(out);
  for (size_t k = 0; k <= rows && k < kept.size(); ++k) {
    const std::string& line = kept[k];
    const size_t fieldStart = line.find_last_of(' ', line.find_last_not_of(' '));
    kept[k] = line.substr(0, line.find_last_not_of(' ', fieldStart) + 1);
  }
  std::string joined;
  for (const std::string& line : kept) joined += line + "\n";
  return joined;
}

}  // namespace

TEST_CASE("stability threads: the study's table is the serial one on 2, 3 and 4 threads") {
  const std::vector<Integrator> all = {Integrator::euler,           Integrator::midpoint, Integrator::rk4,
                                       Integrator::symplecticEuler, Integrator::verlet,   Integrator::backwardEuler};
  const StabilityStudy serial = studySmallCloth(all, 1, 0.0);
  // The cloth exercises the verdicts the search tells apart, or the comparison would prove little.
  bool exploded = false, shaking = false;
  for (const StabilityResult& r : serial.results) {
    exploded = exploded || !r.firstUnstable.stable();
    shaking = shaking || r.firstShaking.verdict == RunVerdict::shaking;
  }
  CHECK(exploded);
  CHECK(shaking);
  for (int threads : kStudyThreadCounts) {
    CAPTURE(threads);
    CHECK(exactly(studySmallCloth(all, threads, 0.0)) == exactly(serial));
  }
  // One integrator on four threads: every thread but one runs guessed probes of the same search.
  // Under ASan + UBSan one integrator: the same code.
  for (Integrator alone : kUnderAddressSanitizer ? std::vector<Integrator>{Integrator::euler}
                                                 : std::vector<Integrator>{Integrator::euler, Integrator::midpoint}) {
    CAPTURE(integratorName(alone));
    CHECK(exactly(studySmallCloth({alone}, 4, 0.0)) == exactly(studySmallCloth({alone}, 1, 0.0)));
  }
}

TEST_CASE("stability threads: every integrator is timed, on one thread or several") {
  for (int threads : {1, 3}) {
    CAPTURE(threads);
    const StabilityStudy study =
        studySmallCloth({Integrator::euler, Integrator::rk4, Integrator::backwardEuler}, threads, 0.01);
    for (const StabilityResult& r : study.results) {
      CAPTURE(integratorName(r.integrator));
      CHECK(r.wallPerSimSecond > 0.0);
    }
  }
}

TEST_CASE("cli stability: the printed table and the CSV are the same with 1, 2, 3 and 4 threads") {
  Scratch s;
  s.write("s.yaml", kSmallCloth);
  const std::string study = "stability s.yaml --integrators euler,midpoint,rk4,verlet,backward_euler --csv t.csv";
  std::string table, csv;
  for (int threads : kCliStudyThreadCounts) {
    CAPTURE(threads);
    const Result r = s.run(study + " --threads " + std::to_string(threads));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    // Without the measured wall time: the CSV's last column, the table's last.
    std::string rows;
    for (const std::string& row : lines(slurp(s.dir / "t.csv"))) rows += row.substr(0, row.rfind(',')) + "\n";
    const std::string printed = withoutWallColumn(r.out, 5);
    if (threads == 1) {
      table = printed;
      csv = rows;
      CHECK(csv.find("backward_euler,1,") != std::string::npos);
    } else {
      CHECK(printed == table);
      CHECK(rows == csv);
    }
  }
}
