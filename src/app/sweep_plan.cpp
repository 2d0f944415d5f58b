// A sweep file turned into jobs: see sweep_plan.hpp.
#include "app/sweep_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "input/printable_text.hpp"
#include "app/cli.hpp"
#include "app/cli_support.hpp"
#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "app/job_table.hpp"
#include "app/thread_count.hpp"
#include "output/confined_folder.hpp"
#include "output/csv_writer.hpp"
#include "output/output_error.hpp"
#include "output/output_file.hpp"
#include "render/video/frame_writer.hpp"
#include "scenario/override_check.hpp"
#include "scenario/scaled_value.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

namespace {

using scenario::Override;
using scenario::ScenarioError;
using scenario::SweepParameter;
using scenario::SweepSpec;

bool isShorthand(const std::string& key) {
  return key == "integrator" || key == "dt" || key == "duration";
}

// The key path a parameter sets in the scenario.
std::string overridePath(const SweepParameter& p) {
  return isShorthand(p.key) ? "simulation." + p.key : p.key;
}

// A parameter's value as an override of the scenario, and as command-line arguments.
Override overrideOf(const SweepParameter& p, const std::string& text) {
  return {overridePath(p), text, fmt::format("the sweep's {}={}", p.name, text)};
}
void appendArgs(std::vector<std::string>& args, const SweepParameter& p, const std::string& text) {
  if (isShorthand(p.key)) {
    args.push_back("--" + p.key);
    args.push_back(text);
  } else {
    args.push_back("--set");
    args.push_back(p.key + "=" + text);
  }
}

std::vector<std::string> optionArgs(const SweepSpec& spec) {
  std::vector<std::string> args;
  for (const auto& o : spec.options) {
    args.push_back("--" + o.name);
    if (!o.flag) args.push_back(o.value);
  }
  for (const auto& [path, value] : spec.sets) {
    args.push_back("--set");
    args.push_back(path + "=" + value);
  }
  return args;
}

// The command's output arguments for a job writing into `dir`.
std::vector<std::string> outputArgs(const std::string& command, const std::filesystem::path& dir,
                                    const std::string& frames, std::vector<std::string>& outputs) {
  if (command == "run") {
    outputs = {(dir / "stats.csv").string()};
    return {"--stats", outputs[0]};
  }
  if (command == "stability") {
    outputs = {(dir / "stability.csv").string()};
    return {"--csv", outputs[0]};
  }
  outputs = {(dir / (frames.empty() ? "video.mp4" : "segment.mp4")).string()};
  std::vector<std::string> args = {"-o", outputs[0]};
  if (!frames.empty()) {
    args.push_back("--frames");
    args.push_back(frames);
  }
  return args;
}

// Parses a job's command line as main() would, without running it; the parse error's message, or
// empty when it parses.
std::string parseError(const std::vector<std::string>& args) {
  Cli probe;
  try {
    probe.parse(args);
  } catch (const CLI::ParseError& e) {
    return e.get_exit_code() == 0 ? std::string("--help and --version are not options for a job") : e.what();
  }
  return {};
}

// Where the sweep file writes the option a CLI11 message names, else the command.
scenario::SweepPosition optionPosition(const SweepSpec& spec, const std::string& message) {
  for (const auto& o : spec.options) {
    if (message.find("--" + o.name) != std::string::npos) return o.at;
  }
  for (const auto& o : spec.options) {
    if (!o.value.empty() && message.find(o.value) != std::string::npos) return o.at;
  }
  return spec.options.empty() ? spec.commandAt : spec.options.front().at;
}

// The scenario as a job's command line names it: absolute, so that the job lists run from any
// folder (a parallel --sshlogin host, a Slurm node that starts elsewhere), and lexically normal
// (`sweeps/../cloth.yaml` as `cloth.yaml`) so that it reads as the file it is, links left as they
// are. Unless that names another file: `..` after a link leads from the link's target, not from
// the folder the link is in, so then the links are resolved (weakly_canonical): the job must read
// the file the sweep checked.
std::string scenarioArgument(const std::filesystem::path& path) {
  const std::filesystem::path absolute = std::filesystem::absolute(path);
  const std::filesystem::path normal = absolute.lexically_normal();
  std::error_code ec;
  if (std::filesystem::equivalent(absolute, normal, ec)) return normal.string();
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.string() : resolved.string();  // as given, `..` and all, the kernel's reading
}

// The next combination of the groups' values, counting with the last group fastest; false after
// the last one.
bool nextCombination(std::vector<size_t>& digit, const std::vector<scenario::SweepGroup>& groups) {
  for (size_t g = digit.size(); g-- > 0;) {
    if (++digit[g] < groups[g].size()) return true;
    digit[g] = 0;
  }
  return false;
}

}  // namespace

std::string SweepPlan::commandLine(const SweepJob& job) const {
  std::vector<std::string> all = {program};
  all.insert(all.end(), job.args.begin(), job.args.end());
  return commandText(all);
}

namespace {

// planSweep's stages, in order, over what they share: the parameters, the overrides every job
// has, each scenario parsed and loaded once (its OverrideChecker), each value's text.
class SweepPlanner {
 public:
  SweepPlanner(const SweepSpec& spec, SweepPlan& plan, std::uintmax_t maxInputMiB, bool showProgress)
      : spec_(spec), plan_(plan), maxInputMiB_(maxInputMiB), showProgress_(showProgress) {}

  // The parameters in the sweep file's order, their columns; a key varied here and in options.
  void collectParameters() {
    for (const auto& g : spec_.groups) {
      for (const auto& p : g.parameters) {
        parameters_.push_back(&p);
        plan_.columns.push_back(p.name);
        for (const auto& o : spec_.options) {
          if (isShorthand(o.name) && overridePath(p) == "simulation." + o.name) {
            failInSweep(spec_, p.at,
                        fmt::format("{} is varied here and also given in options ({}:{})", input::quotedValue(p.key),
                                    spec_.file, o.at.line));
          }
        }
      }
    }
  }

  // What every job changes in its scenario: the options' shorthands (--duration, --dt,
  // --integrator) change it as a parameter would (a split render counts its frames from the
  // duration the job will run), then options.set.
  void collectFixedOverrides() {
    for (const auto& o : spec_.options) {
      if (isShorthand(o.name) && !o.flag) {
        fixed_.push_back({"simulation." + o.name, o.value,
                          fmt::format("the sweep's options.{} ({}:{})", o.name, spec_.file, o.at.line)});
      }
    }
    for (size_t k = 0; k < spec_.sets.size(); ++k) {
      fixed_.push_back({spec_.sets[k].first, spec_.sets[k].second,
                        fmt::format("the sweep's options.set ({}:{})", spec_.file, spec_.setsAt[k].line)});
    }
  }

  // Every scenario loads with the fixed overrides: parsed and loaded once, here.
  void loadScenarios() {
    for (const auto& s : spec_.scenarios) {
      scenarioArgs_.push_back(scenarioArgument(s.path));
      try {
        texts_.push_back(scenario::readScenarioText(s.path, maxInputMiB_));
        checkers_.emplace_back(texts_.back(), s.path.string(), fixed_);
      } catch (const ScenarioError& e) {
        failInSweep(spec_, s.at, e.what());
      }
    }
  }

  // The command takes the options: one job's command line parsed as main() would.
  void checkOptions() const {
    std::vector<std::string> outputs;
    std::vector<std::string> args = {spec_.command, scenarioArgs_.front()};
    const auto options = optionArgs(spec_);
    args.insert(args.end(), options.begin(), options.end());
    const auto out = outputArgs(spec_.command, plan_.outDir / "probe", "", outputs);
    args.insert(args.end(), out.begin(), out.end());
    const std::string error = parseError(args);
    if (!error.empty()) failInSweep(spec_, optionPosition(spec_, error), fmt::format("{}: {}", spec_.command, error));
  }

  // Each value of each parameter, in each scenario: its text (a scaled one computed from the
  // scenario's own value) and that the scenario loads with it, each at the value's line.
  void checkValues() {
    size_t total = 0, done = 0;
    for (const SweepParameter* p : parameters_) total += p->values.size() * spec_.scenarios.size();
    Progress progress(showProgress_, "values");
    valueTexts_.resize(spec_.scenarios.size());
    for (size_t s = 0; s < spec_.scenarios.size(); ++s) {
      for (const SweepParameter* p : parameters_) {
        std::optional<scenario::ScaledValue> scaled;
        std::vector<std::string> texts;
        for (const auto& v : p->values) {
          try {
            if (p->scale && !scaled) scaled.emplace(texts_[s], spec_.scenarios[s].path.string(), overridePath(*p));
            texts.push_back(scaled ? scaled->times(*v.number) : v.text);
            const Override o = overrideOf(*p, texts.back());
            checkers_[s].check(std::span(&o, 1));
          } catch (const ScenarioError& e) {
            failInSweep(spec_, p->scale ? p->at : v.at, e.what());
          }
          progress.update(long(++done), long(total));
        }
        valueTexts_[s].push_back(std::move(texts));
      }
    }
  }

  // The jobs: scenarios outermost, then the groups in order, the last one varying fastest.
  void addJobs() {
    fpsOption_ = fpsOption(spec_);
    const auto options = optionArgs(spec_);
    Progress progress(showProgress_, "jobs");
    const long total = long(spec_.combinations());
    long done = 0;
    std::vector<size_t> digit(spec_.groups.size(), 0);
    for (size_t s = 0; s < spec_.scenarios.size(); ++s) {
      std::fill(digit.begin(), digit.end(), 0);
      do {
        addCombination(s, digit, options);
        progress.update(++done, total);
      } while (nextCombination(digit, spec_.groups));
    }
    plan_.firstStageCount = plan_.jobs.size();
  }

  // The joins of split renders: one concat job per video, after all segments.
  void addJoins() {
    for (const Pending& j : toJoin_) {
      SweepJob job;
      job.index = plan_.jobs.size();
      job.stage = "concat";
      job.scenario = spec_.scenarios[j.scenario].given;
      job.values = j.values;
      job.scenarioIndex = j.scenario;
      job.dir = jobFolder(job.index);
      job.args = {"concat"};
      for (size_t k : j.segments) job.args.push_back(plan_.jobs[k].outputs.front());
      job.outputs = {(plan_.outDir / job.dir / "video.mp4").string()};
      job.args.insert(job.args.end(), {"-o", job.outputs.front()});
      job.record = plan_.outDir / job.dir / "record.txt";
      job.args.insert(job.args.end(), {"--record", job.record.string()});
      job.after = j.segments;
      plan_.jobs.push_back(std::move(job));
    }
  }

 private:
  // A split render's segments, joined once they are all done.
  struct Pending {
    std::vector<size_t> segments;
    size_t scenario;
    std::vector<std::string> values;
  };

  static double fpsOption(const SweepSpec& spec) {
    double fps = 0;
    for (const auto& o : spec.options) {
      if (o.name != "fps") continue;
      const auto [end, ec] = std::from_chars(o.value.data(), o.value.data() + o.value.size(), fps);
      if (ec != std::errc() || end != o.value.data() + o.value.size() || !(fps > 0) || !std::isfinite(fps)) {
        failInSweep(
            spec, o.at,
            fmt::format("fps: expected a number of frames per second > 0, got {}", input::quotedValue(o.value)));
      }
    }
    return fps;
  }

  // One combination of the groups' values in scenario s: its job, or a split render's segments.
  void addCombination(size_t s, const std::vector<size_t>& digit, const std::vector<std::string>& options) {
    std::vector<std::string> params, shown;
    std::vector<Override> overrides;
    std::vector<const scenario::SweepValue*> values;
    size_t column = 0;
    for (size_t g = 0; g < spec_.groups.size(); ++g) {
      for (const auto& p : spec_.groups[g].parameters) {
        const std::string& text = valueTexts_[s][column][digit[g]];
        appendArgs(params, p, text);
        overrides.push_back(overrideOf(p, text));
        shown.push_back(p.values[digit[g]].text);
        values.push_back(&p.values[digit[g]]);
        ++column;
      }
    }
    const scenario::ScenarioSettings settings = checkTogether(s, overrides, values);
    const std::vector<std::string> frames = segmentFrames(settings);
    Pending join{{}, s, shown};
    for (size_t k = 0; k < frames.size(); ++k) {
      SweepJob job;
      job.index = plan_.jobs.size();
      job.stage = spec_.split > 1 ? "segment" : spec_.command;
      job.scenario = spec_.scenarios[s].given;
      job.values = shown;
      if (spec_.split > 1) job.segment = fmt::format("{}/{}", k + 1, spec_.split);
      job.dir = jobFolder(job.index);
      job.args = {spec_.command, scenarioArgs_[s]};
      job.args.insert(job.args.end(), options.begin(), options.end());
      job.args.insert(job.args.end(), params.begin(), params.end());
      const auto out = outputArgs(spec_.command, plan_.outDir / job.dir, frames[k], job.outputs);
      job.args.insert(job.args.end(), out.begin(), out.end());
      job.record = plan_.outDir / job.dir / "record.txt";
      job.args.push_back("--record");
      job.args.push_back(job.record.string());
      job.scenarioIndex = s;
      job.overrides = fixed_;
      job.overrides.insert(job.overrides.end(), overrides.begin(), overrides.end());
      join.segments.push_back(job.index);
      plan_.jobs.push_back(std::move(job));
    }
    if (spec_.split > 1) toJoin_.push_back(std::move(join));
  }

  // A job's values together: each loaded alone in checkValues, here those that change one part of
  // the file are read together there (two keys of one force, dt with duration), once for each
  // distinct combination. An error is the sweep file's at the value it names.
  scenario::ScenarioSettings checkTogether(size_t s, const std::vector<Override>& overrides,
                                           const std::vector<const scenario::SweepValue*>& values) {
    try {
      return checkers_[s].checkTogether(overrides);
    } catch (const ScenarioError& e) {
      std::vector<std::string> together;
      size_t at = values.size() - 1;
      for (size_t k = 0; k < overrides.size(); ++k) {
        together.push_back(fmt::format("{}={}", parameters_[k]->name, overrides[k].value));
        if (overrides[k].origin == e.origin()) at = k;
      }
      failInSweep(spec_, values[at]->at, fmt::format("{} (with {})", e.what(), fmt::join(together, ", ")));
    }
  }

  // The frame ranges of a split render's segments (`A:B`, counted from the duration the job runs
  // and its fps); one empty range for a job that is not split.
  std::vector<std::string> segmentFrames(const scenario::ScenarioSettings& settings) const {
    if (spec_.split <= 1) return {""};
    const double fps = fpsOption_ > 0 ? fpsOption_ : settings.render.fps;
    const long total = render::frameCount(settings.simulation.duration, int(std::lround(fps)));
    if (total < spec_.split) {
      failInSweep(spec_, spec_.splitAt, fmt::format("{} segments of a video of {} frames", spec_.split, total));
    }
    std::vector<std::string> frames;
    for (int k = 0; k < spec_.split; ++k) {
      frames.push_back(fmt::format("{}:{}", total * k / spec_.split, total * (k + 1) / spec_.split));
    }
    return frames;
  }

  const SweepSpec& spec_;
  SweepPlan& plan_;
  const std::uintmax_t maxInputMiB_;
  const bool showProgress_;
  std::vector<const SweepParameter*> parameters_;
  std::vector<Override> fixed_;
  std::vector<std::string> texts_, scenarioArgs_;  // by scenario
  std::vector<scenario::OverrideChecker> checkers_;
  std::vector<std::vector<std::vector<std::string>>> valueTexts_;  // [scenario][parameter][value]
  double fpsOption_ = 0;
  std::vector<Pending> toJoin_;
};

}  // namespace

SweepPlan planSweep(const SweepSpec& spec, const std::filesystem::path& outDir, const std::string& program,
                    std::uintmax_t maxInputMiB, bool showProgress) {
  SweepPlan plan;
  plan.spec = spec;
  plan.outDir = std::filesystem::absolute(outDir).lexically_normal();
  plan.program = program;
  SweepPlanner planner(spec, plan, maxInputMiB, showProgress);
  planner.collectParameters();
  planner.collectFixedOverrides();
  planner.loadScenarios();
  planner.checkOptions();
  planner.checkValues();
  planner.addJobs();
  planner.addJoins();
  return plan;
}

void writeJobTable(const SweepPlan& plan) {
  // Everything the sweep writes lies beneath its folder (output/confined_folder.hpp): the folder
  // may be an earlier sweep's, touched by anyone since, and a `jobs` that is now a link out of it
  // must not make the sweep write elsewhere.
  const output::ConfinedFolder folder(plan.outDir, output::ConfinedFolder::Create::yes);
  for (const SweepJob& job : plan.jobs) folder.openFolder(job.dir, output::ConfinedFolder::Create::yes);
  output::OutputFile csv(folder, "jobs.csv");
  csv.write(output::csvRow(jobTableHeader(plan.columns)));
  for (const SweepJob& job : plan.jobs) {
    std::vector<std::string> row = {std::to_string(job.index), job.stage, job.scenario};
    row.insert(row.end(), job.values.begin(), job.values.end());
    row.insert(row.end(), {job.segment, job.dir.string(), plan.commandLine(job)});
    csv.write(output::csvRow(row));
  }
  csv.commit();
}

}  // namespace particles::app
