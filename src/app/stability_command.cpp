// `particles stability`: see stability_command.hpp.
#include "app/stability_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "input/printable_text.hpp"
#include "app/cli_support.hpp"
#include "app/job_record.hpp"
#include "app/thread_count.hpp"
#include "core/stability.hpp"
#include "output/output_file.hpp"
#include "plot/stability_figure.hpp"

namespace particles::app {

namespace {

std::vector<Integrator> parseIntegrators(const std::vector<std::string>& names) {
  std::vector<Integrator> out;
  for (const std::string& name : names) {
    const auto i = integratorFromName(name);
    if (!i) {
      std::vector<std::string> known = integratorNames();
      const std::string last = known.back();
      known.pop_back();
      throw InputError(fmt::format("--integrators: unknown integrator {} (expected {} or {})", input::quotedValue(name),
                                   fmt::join(known, ", "), last));
    }
    if (std::find(out.begin(), out.end(), *i) == out.end()) out.push_back(*i);
  }
  return out;
}

std::string describe(const RunAssessment& a) {
  switch (a.verdict) {
    case RunVerdict::stable: return "stable";
    case RunVerdict::shaking: return fmt::format("shaking index {:.2f}", a.shakingIndex);
    case RunVerdict::exploded: return fmt::format("exploded after {} steps", a.steps);
    case RunVerdict::runaway:
      return fmt::format("energy {:.2g}×S above its bound after {} steps", a.maxEnergyExcess, a.steps);
    case RunVerdict::overstretched:
      return fmt::format("a spring at {:.2f}× its rest length after {} steps", a.maxStretch, a.steps);
  }
  return "";
}

// --reference NAME=DT or NAME=LO:HI, for the figure; NAME must be one of the integrators studied.
std::map<std::string, plot::Reference> parseReferences(const std::vector<std::string>& texts,
                                                       const std::vector<Integrator>& studied) {
  std::map<std::string, plot::Reference> out;
  for (const std::string& text : texts) {
    const auto fail = [&](const std::string& why) {
      throw InputError(fmt::format("--reference {}: {} (expected NAME=DT or NAME=LO:HI, e.g. rk4=0.3:0.4)",
                                   input::quotedValue(text), why));
    };
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0) fail("no integrator name");
    const std::string name = text.substr(0, eq);
    std::vector<std::string> names;
    for (Integrator i : studied) names.emplace_back(integratorName(i));
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      fail(fmt::format("{} is not an integrator studied here ({})", input::quotedValue(name), fmt::join(names, ", ")));
    }
    const std::string values = text.substr(eq + 1);
    const std::size_t colon = values.find(':');
    const auto number = [&](const std::string& field) {
      double v = 0;
      const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
      if (field.empty() || ec != std::errc() || end != field.data() + field.size() || !(v > 0) || !std::isfinite(v)) {
        fail(fmt::format("{} is not a positive number of seconds", input::quotedValue(field)));
      }
      return v;
    };
    plot::Reference r{};
    r.lo = number(values.substr(0, colon));
    r.hi = colon == std::string::npos ? r.lo : number(values.substr(colon + 1));
    if (r.hi < r.lo) fail("LO is larger than HI");
    if (!out.emplace(name, r).second) fail(fmt::format("a second value for {}", name));
  }
  return out;
}

// The criteria behind the figure's values (docs/stability.md), in words, for its caption.
std::vector<std::string> criteriaCaption(const scenario::Scenario& s, const StabilityOptions& study,
                                         const StabilityStudy& found, const StabilityOptionsCli& options) {
  std::vector<std::string> caption = {
      fmt::format("Each dt runs the whole {} s. Stable: no NaN or explosion, total energy never above E(0) + the "
                  "mouse's work by more than {} × the energy scale, no spring longer than {:.3g}× its rest length "
                  "({}× an RK4 run at dt = {:.3g} s).",
                  s.simulation.duration, options.energyTolerance, found.maxStretch, options.stretchFactor,
                  found.referenceDt),
      fmt::format("Without shaking: stable, and over the second half the velocities' second difference stays "
                  "under {} of their RMS. Limits bisected to {:.1f} %; dt tried from {:.3g} s to {:.3g} s.",
                  options.shakeThreshold, 100 * study.relativePrecision, study.minDt, study.maxDt)};
  if (!options.references.empty()) {
    caption.push_back(
        fmt::format("{}: a diamond (a value) or a bar (the limit lies between its ends).", options.referenceName));
  }
  return caption;
}

std::string dtText(double dt, bool atMax) {
  if (atMax) return fmt::format("≥ {:.2g} s", dt);
  return dt > 0.0 ? fmt::format("{:.2g} s", dt) : std::string("none ≥ min");
}

// The criteria and the range of dt from the command line; throws InputError for values outside
// their ranges. Returns the smallest dt tried.
double checkedMinDt(const StabilityOptionsCli& options, const scenario::Scenario& s) {
  const double minDt = options.minDt > 0 ? options.minDt : s.simulation.dt / kMinDtDivisor;
  // Written as "not inside" so that NaN, which fails every comparison, is refused too.
  const bool inside = options.energyTolerance > 0 && std::isfinite(options.energyTolerance) &&
                      options.stretchFactor > 1 && std::isfinite(options.stretchFactor) && options.shakeThreshold > 0 &&
                      options.shakeThreshold <= 1 && options.minDt >= 0 && std::isfinite(minDt) &&
                      options.maxDt > minDt && std::isfinite(options.maxDt);
  if (!inside) {
    throw InputError(
        "need --energy-tolerance > 0, --stretch-factor > 1, 0 < --shake-threshold ≤ 1 and 0 < --min-dt < "
        "--max-dt");
  }
  return minDt;
}

// The study's settings: the criteria, the range of dt, the reference run, the threads.
StabilityOptions studyOptions(const StabilityOptionsCli& options, const scenario::Scenario& s, double minDt) {
  StabilityOptions study;
  study.criteria.energyTolerance = options.energyTolerance;
  study.stretchFactor = options.stretchFactor;
  study.criteria.shakeThreshold = options.shakeThreshold;
  study.startDt = s.simulation.dt;
  study.referenceDt = s.simulation.dt / 4.0;
  study.minReferenceDt = std::max(minDt, std::ldexp(study.referenceDt, -kReferenceHalvings));
  study.minDt = minDt;
  study.maxDt = options.maxDt;
  study.costDtCap = 1.0 / s.render.fps;
  // --threads (or PARTICLES_THREADS, or the CPUs this process may use): the study's trial runs share them.
  study.threads = threadCountOf(options.common.threads);
  return study;
}

// What each trial run builds a fresh system from: the scenario's text, read once, and its overrides.
struct TrialScenario {
  std::string file, text;
  std::vector<scenario::Override> overrides;
  scenario::SceneLimits limits;
};

TrialScenario trialScenario(const CommonOptions& common) {
  return {common.scenario, scenario::readScenarioText(common.scenario, common.maxInputMiB), overridesOf(common),
          sceneLimitsOf(common)};
}

// Runs the study; an explosion, or a reference run that is itself unstable, is a failed simulation.
StabilityStudy runStudy(const TrialScenario& trial, double duration, const std::vector<Integrator>& integrators,
                        const StabilityOptions& study) {
  const SystemFactory make = [&] {
    return scenario::loadScenarioText(trial.text, trial.file, trial.overrides, trial.limits).system;
  };
  try {
    return findStabilityLimits(make, duration, integrators, study);
  } catch (const std::runtime_error& e) {
    throw SimulationFailure(e.what());
  }
}

// The figure's rows, with each limit reported as the job's headline numbers (a limit found at
// --max-dt is a lower bound; the headline gives the value found).
std::vector<plot::StabilityRow> stabilityRows(const std::vector<StabilityResult>& results) {
  std::vector<plot::StabilityRow> rows;
  for (const StabilityResult& r : results) {
    reportHeadline(fmt::format("max_stable_dt.{}", integratorName(r.integrator)), r.maxStableDt);
    reportHeadline(fmt::format("max_smooth_dt.{}", integratorName(r.integrator)), r.maxSmoothDt);
    rows.push_back({std::string(integratorName(r.integrator)), r.evalsPerStep, r.maxStableDt, r.maxSmoothDt,
                    r.evalsPerSimSecond, r.speedVsEuler, r.stableAtMaxDt, r.smoothAtMaxDt});
  }
  return rows;
}

// The table on stdout: a line per integrator.
void printLimits(const std::vector<StabilityResult>& results) {
  fmt::print("{:<16} {:>10} {:>15} {:>22} {:>20} {:>15} {:>22}\n", "integrator", "evals/step", "max stable dt",
             "max dt without shaking", "evals per sim second", "speed vs euler", "wall s per sim second");
  for (const StabilityResult& r : results) {
    fmt::print("{:<16} {:>10} {:>15} {:>22} {:>20.4g} {:>15} {:>22}\n", integratorName(r.integrator), r.evalsPerStep,
               dtText(r.maxStableDt, r.stableAtMaxDt), dtText(r.maxSmoothDt, r.smoothAtMaxDt), r.evalsPerSimSecond,
               r.speedVsEuler > 0 ? fmt::format("{:.2f}×", r.speedVsEuler) : std::string("–"),
               r.wallPerSimSecond > 0 ? fmt::format("{:.3g}", r.wallPerSimSecond) : std::string("–"));
  }
}

// Below the table: the reference run, and why the next larger step of each integrator failed.
void printWhyNextFailed(const StabilityStudy& found, const StabilityOptions& study, double fps) {
  fmt::print("\nreference: rk4 at dt = {:.3g} s, longest spring {:.3g}× its rest length → bound {:.3g}×\n",
             found.referenceDt, found.reference.maxStretch, found.maxStretch);
  fmt::print("why the next larger steps failed:\n");
  bool anyAtMax = false;
  for (const StabilityResult& r : found.results) {
    anyAtMax = anyAtMax || r.stableAtMaxDt;
    fmt::print("  {:<16} unstable: {}; not smooth: {}  ({} runs)\n", integratorName(r.integrator),
               r.stableAtMaxDt ? fmt::format("none up to --max-dt {:.3g} s", study.maxDt) : describe(r.firstUnstable),
               r.smoothAtMaxDt ? fmt::format("none up to --max-dt {:.3g} s", study.maxDt) : describe(r.firstShaking),
               r.runs);
  }
  if (anyAtMax) {
    fmt::print(
        "≥: no limit below --max-dt. An implicit integrator damps a step that is too long instead of blowing\n"
        "up, so its step is bounded by accuracy, not stability: for an animation take at most one step per\n"
        "frame (1/fps = {:.3g} s here), which is the step its costs per simulated second are given at.\n",
        1.0 / fps);
  }
}

// --csv: a row per integrator.
void writeStabilityCsv(const std::string& path, const std::vector<StabilityResult>& results) {
  output::OutputFile csv(path);
  csv.write(
      "integrator,evals_per_step,max_stable_dt,max_smooth_dt,cost_dt,evals_per_sim_second,speed_vs_euler,"
      "wall_seconds_per_sim_second\n");
  for (const StabilityResult& r : results) {
    csv.write(fmt::format("{},{},{},{},{},{},{},{}\n", integratorName(r.integrator), r.evalsPerStep, r.maxStableDt,
                          r.maxSmoothDt, r.costDt, r.evalsPerSimSecond, r.speedVsEuler, r.wallPerSimSecond));
  }
  csv.commit();
}

int stabilityCommand(const StabilityOptionsCli& options) {
  const CommonOptions& common = options.common;
  if (!options.plot.empty()) requireFigurePath("--plot", options.plot);
  const scenario::Scenario s = loadScenario(common);
  const std::vector<Integrator> integrators = parseIntegrators(options.integrators);
  const auto references = parseReferences(options.references, integrators);
  if (!references.empty() && options.plot.empty()) throw InputError("--reference is shown on --plot: give --plot too");
  const StabilityOptions study = studyOptions(options, s, checkedMinDt(options, s));
  const TrialScenario trial = trialScenario(common);

  if (!common.quiet) {
    fmt::print(
        stderr, "{}: searching the largest stable dt of {} over {} s with {} (this runs the scenario many times)\n",
        common.scenario, plural(integrators.size(), "integrator", "integrators"), s.simulation.duration, contents(s));
  }
  const StabilityStudy found = runStudy(trial, s.simulation.duration, integrators, study);
  const std::vector<plot::StabilityRow> rows = stabilityRows(found.results);
  if (!common.quiet) {
    printLimits(found.results);
    printWhyNextFailed(found, study, s.render.fps);
  }
  if (!options.csv.empty()) writeStabilityCsv(options.csv, found.results);
  if (!options.plot.empty()) {
    plot::StabilityFigureNotes notes;
    notes.scenario = s.name;
    notes.caption = criteriaCaption(s, study, found, options);
    notes.references = references;
    notes.referenceName = options.referenceName;
    plot::writeFigure(plot::stabilityFigure(rows, notes), options.plot);
  }
  return kOk;
}

void addStabilityOptions(CLI::App& command, StabilityOptionsCli& stability) {
  addCommonOptions(command, stability.common);
  command.add_option("--integrators", stability.integrators, "Integrators to study, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command.add_option("--csv", stability.csv,
                     "Write integrator,evals_per_step,max_stable_dt,max_smooth_dt,cost_dt,evals_per_sim_second,"
                     "speed_vs_euler,wall_seconds_per_sim_second to this CSV");
  command.add_option("--plot", stability.plot,
                     "Write the limits as a dot plot (log axis, criteria in the caption): .svg, .png or .pdf");
  command
      .add_option("--reference", stability.references,
                  "Values to show beside the limits on the plot, per integrator: NAME=DT (a point) or NAME=LO:HI "
                  "(the limit lies between), e.g. euler=0.003:0.005,rk4=0.3")
      ->delimiter(',')
      ->type_name("NAME=DT");
  command.add_option("--reference-name", stability.referenceName, "What the references are, in the legend")
      ->capture_default_str();
  command
      .add_option("--energy-tolerance", stability.energyTolerance,
                  "Unstable when energy exceeds E(0) + mouse work by this fraction of the energy scale")
      ->capture_default_str();
  command
      .add_option("--stretch-factor", stability.stretchFactor,
                  fmt::format("Unstable when a spring stretches beyond this multiple of the largest stretch of a "
                              "reference run (rk4 at a quarter of the scenario's dt, halved up to {} times until "
                              "stable)",
                              kReferenceHalvings))
      ->capture_default_str();
  command
      .add_option("--shake-threshold", stability.shakeThreshold,
                  "Shaking when the step-alternating share of velocity exceeds this (sin²(ωh/2))")
      ->capture_default_str();
  command.add_option("--min-dt", stability.minDt,
                     fmt::format("Smallest dt tried, s (default: the scenario's dt / {})", kMinDtDivisor));
  command.add_option("--max-dt", stability.maxDt, "Largest dt tried, s")->capture_default_str();
  command.footer(
      "Criteria and the report's results: docs/stability.md.\n"
      "Examples:\n"
      "  particles stability scenarios/cloth.yaml\n"
      "  particles stability scenarios/cloth.yaml --csv cloth_dt.csv --plot cloth_dt.svg\n"
      "  particles stability scenarios/soft_body.yaml --integrators midpoint,rk4 --duration 20\n"
      "  particles stability scenarios/cloth_report.yaml --integrators euler,midpoint,rk4 --plot dt.pdf \\\n"
      "      --reference euler=0.003:0.005,midpoint=0.03:0.05,rk4=0.3:0.4 --reference-name report\n");
  addJobOptions(command, stability.job);
}

CommandFiles stabilityFiles(const StabilityOptionsCli& o) {
  return {{{"--csv", o.csv}, {"--plot", o.plot}}, {{"the scenario", o.common.scenario}}};
}

}  // namespace

const CommandDescriptor<StabilityOptionsCli> kStabilityCommand = {
    .name = "stability",
    .summary = "Find the largest stable time step of each integrator on a scenario (simulation only)",
    .addOptions = addStabilityOptions,
    .run = stabilityCommand,
    .files = stabilityFiles,
    .common = &StabilityOptionsCli::common,
    .job = &StabilityOptionsCli::job,
};

}  // namespace particles::app
