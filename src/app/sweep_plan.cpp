// A sweep file turned into jobs: see sweep_plan.hpp.
#include "app/sweep_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "app/cli.hpp"
#include "app/csv_table.hpp"
#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "app/job_table.hpp"
#include "app/thread_count.hpp"
#include "output/output_error.hpp"
#include "output/output_file.hpp"
#include "render/frame_writer.hpp"
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

// A parameter's value as an override of the scenario, and as command-line arguments.
Override overrideOf(const SweepParameter& p, const std::string& text) {
  const std::string path = isShorthand(p.key) ? "simulation." + p.key : p.key;
  return {path, text, fmt::format("the sweep's {}={}", p.name, text)};
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

SweepPlan planSweep(const SweepSpec& spec, const std::filesystem::path& outDir, const std::string& program,
                    std::uintmax_t maxInputMiB) {
  SweepPlan plan;
  plan.spec = spec;
  plan.outDir = std::filesystem::absolute(outDir).lexically_normal();
  plan.program = program;
  std::vector<const SweepParameter*> parameters;
  for (const auto& g : spec.groups) {
    for (const auto& p : g.parameters) {
      parameters.push_back(&p);
      plan.columns.push_back(p.name);
      for (const auto& o : spec.options) {
        const std::string key = isShorthand(p.key) ? "simulation." + p.key : p.key;
        if (isShorthand(o.name) && key == "simulation." + o.name) {
          failInSweep(
              spec, p.at,
              fmt::format("'{}' is varied here and also given in options ({}:{})", p.key, spec.file, o.at.line));
        }
      }
    }
  }

  // Every scenario loads with the options' --set overrides.
  std::vector<Override> fixed;
  // The options' shorthands (--duration, --dt, --integrator) change the scenario as a parameter
  // would: a split render counts its frames from the duration the job will run.
  for (const auto& o : spec.options) {
    if (isShorthand(o.name) && !o.flag) {
      fixed.push_back({"simulation." + o.name, o.value,
                       fmt::format("the sweep's options.{} ({}:{})", o.name, spec.file, o.at.line)});
    }
  }
  for (size_t k = 0; k < spec.sets.size(); ++k) {
    fixed.push_back({spec.sets[k].first, spec.sets[k].second,
                     fmt::format("the sweep's options.set ({}:{})", spec.file, spec.setsAt[k].line)});
  }
  std::vector<std::string> texts, scenarioArgs;
  for (const auto& s : spec.scenarios) {
    scenarioArgs.push_back(scenarioArgument(s.path));
    try {
      texts.push_back(scenario::readScenarioText(s.path, maxInputMiB));
      scenario::loadScenarioText(texts.back(), s.path.string(), fixed);
    } catch (const ScenarioError& e) {
      failInSweep(spec, s.at, e.what());
    }
  }

  // The command takes the options: one job's command line parsed as main() would.
  {
    std::vector<std::string> outputs;
    std::vector<std::string> args = {spec.command, scenarioArgs.front()};
    const auto options = optionArgs(spec);
    args.insert(args.end(), options.begin(), options.end());
    const auto out = outputArgs(spec.command, plan.outDir / "probe", "", outputs);
    args.insert(args.end(), out.begin(), out.end());
    const std::string error = parseError(args);
    if (!error.empty()) failInSweep(spec, optionPosition(spec, error), fmt::format("{}: {}", spec.command, error));
  }

  // Each value of each parameter, in each scenario: its text (a scaled one computed from the
  // scenario's own value) and that the scenario loads with it.
  // values[s][p][v]
  std::vector<std::vector<std::vector<std::string>>> valueTexts(spec.scenarios.size());
  for (size_t s = 0; s < spec.scenarios.size(); ++s) {
    const std::string file = spec.scenarios[s].path.string();
    for (const SweepParameter* p : parameters) {
      std::vector<std::string> texts_;
      for (const auto& v : p->values) {
        std::string text = v.text;
        try {
          if (p->scale) {
            const std::string path = isShorthand(p->key) ? "simulation." + p->key : p->key;
            text = scenario::ScaledValue(texts[s], file, path).times(*v.number);
          }
          std::vector<Override> overrides = fixed;
          overrides.push_back(overrideOf(*p, text));
          scenario::loadScenarioText(texts[s], file, overrides);
        } catch (const ScenarioError& e) {
          failInSweep(spec, p->scale ? p->at : v.at, e.what());
        }
        texts_.push_back(std::move(text));
      }
      valueTexts[s].push_back(std::move(texts_));
    }
  }

  double fpsOption = 0;
  for (const auto& o : spec.options) {
    if (o.name != "fps") continue;
    const auto [end, ec] = std::from_chars(o.value.data(), o.value.data() + o.value.size(), fpsOption);
    if (ec != std::errc() || end != o.value.data() + o.value.size() || !(fpsOption > 0) || !std::isfinite(fpsOption)) {
      failInSweep(spec, o.at, fmt::format("fps: expected a number of frames per second > 0, got '{}'", o.value));
    }
  }

  // The jobs: scenarios outermost, then the groups in order, the last one varying fastest.
  const auto options = optionArgs(spec);
  std::vector<size_t> digit(spec.groups.size(), 0);
  struct Pending {
    std::vector<size_t> segments;
    size_t scenario;
    std::vector<std::string> values;
  };
  std::vector<Pending> toJoin;
  for (size_t s = 0; s < spec.scenarios.size(); ++s) {
    std::fill(digit.begin(), digit.end(), 0);
    do {
      std::vector<std::string> params, shown;
      std::vector<Override> overrides = fixed;
      size_t column = 0;
      for (size_t g = 0; g < spec.groups.size(); ++g) {
        for (const auto& p : spec.groups[g].parameters) {
          const std::string& text = valueTexts[s][column][digit[g]];
          appendArgs(params, p, text);
          overrides.push_back(overrideOf(p, text));
          shown.push_back(p.values[digit[g]].text);
          ++column;
        }
      }
      std::vector<std::string> frames;
      if (spec.split > 1) {
        const auto loaded = [&] {
          try {
            return scenario::loadScenarioText(texts[s], spec.scenarios[s].path.string(), overrides);
          } catch (const ScenarioError& e) {
            failInSweep(spec, spec.scenarios[s].at, e.what());
          }
        }();
        const double fps = fpsOption > 0 ? fpsOption : loaded.render.fps;
        const long total = render::frameCount(loaded.simulation.duration, int(std::lround(fps)));
        if (total < spec.split) {
          failInSweep(spec, spec.splitAt, fmt::format("{} segments of a video of {} frames", spec.split, total));
        }
        for (int k = 0; k < spec.split; ++k) {
          frames.push_back(fmt::format("{}:{}", total * k / spec.split, total * (k + 1) / spec.split));
        }
      } else {
        frames.push_back("");
      }
      Pending join{{}, s, shown};
      for (size_t k = 0; k < frames.size(); ++k) {
        SweepJob job;
        job.index = plan.jobs.size();
        job.stage = spec.split > 1 ? "segment" : spec.command;
        job.scenario = spec.scenarios[s].given;
        job.values = shown;
        if (spec.split > 1) job.segment = fmt::format("{}/{}", k + 1, spec.split);
        job.dir = jobFolder(job.index);
        job.args = {spec.command, scenarioArgs[s]};
        job.args.insert(job.args.end(), options.begin(), options.end());
        job.args.insert(job.args.end(), params.begin(), params.end());
        const auto out = outputArgs(spec.command, plan.outDir / job.dir, frames[k], job.outputs);
        job.args.insert(job.args.end(), out.begin(), out.end());
        job.record = plan.outDir / job.dir / "record.txt";
        job.args.push_back("--record");
        job.args.push_back(job.record.string());
        job.scenarioIndex = s;
        job.overrides = overrides;
        join.segments.push_back(job.index);
        plan.jobs.push_back(std::move(job));
      }
      if (spec.split > 1) toJoin.push_back(std::move(join));

    } while (nextCombination(digit, spec.groups));
  }
  plan.firstStageCount = plan.jobs.size();

  for (const Pending& j : toJoin) {
    SweepJob job;
    job.index = plan.jobs.size();
    job.stage = "concat";
    job.scenario = spec.scenarios[j.scenario].given;
    job.values = j.values;
    job.scenarioIndex = j.scenario;
    job.dir = jobFolder(job.index);
    job.args = {"concat"};
    for (size_t k : j.segments) job.args.push_back(plan.jobs[k].outputs.front());
    job.outputs = {(plan.outDir / job.dir / "video.mp4").string()};
    job.args.insert(job.args.end(), {"-o", job.outputs.front()});
    job.record = plan.outDir / job.dir / "record.txt";
    job.args.insert(job.args.end(), {"--record", job.record.string()});
    job.after = j.segments;
    plan.jobs.push_back(std::move(job));
  }
  return plan;
}

void writeJobTable(const SweepPlan& plan) {
  std::error_code ec;
  for (const SweepJob& job : plan.jobs) {
    std::filesystem::create_directories(plan.outDir / job.dir, ec);
    if (ec)
      throw output::OutputError(fmt::format("cannot create {}: {}", (plan.outDir / job.dir).string(), ec.message()));
  }
  output::OutputFile csv(plan.outDir / "jobs.csv");
  csv.write(csvRow(jobTableHeader(plan.columns)));
  for (const SweepJob& job : plan.jobs) {
    std::vector<std::string> row = {std::to_string(job.index), job.stage, job.scenario};
    row.insert(row.end(), job.values.begin(), job.values.end());
    row.insert(row.end(), {job.segment, job.dir.string(), plan.commandLine(job)});
    csv.write(csvRow(row));
  }
  csv.commit();
}

namespace {

// The job lists hold one line per job, `PROGRAM job OUT INDEX`: two paths and fixed words, quoted
// by shellQuote. A control character in either path would need bash's $'…', which the shell GNU
// parallel starts (often sh) may not read, so such a path is refused.
void checkListPath(const std::string& what, const std::string& path) {
  if (std::any_of(path.begin(), path.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    throw InputError(
        fmt::format("{} '{}' holds a control character (a line break?): the job lists are lines of "
                    "shell text, so give a path without one",
                    what, shellQuote(path)));
  }
}

std::string jobLine(const SweepPlan& plan, size_t index) {
  return commandText({plan.program, "job", plan.outDir.string(), std::to_string(index)});
}

void writeLines(const std::filesystem::path& file, const SweepPlan& plan, size_t from, size_t to) {
  output::OutputFile out(file);
  for (size_t i = from; i < to; ++i) out.write(jobLine(plan, i) + "\n");
  out.commit();
}

// A Slurm array script: task i runs job first + i. Nothing of the sweep's values is in it, only
// the program and the output folder, quoted; the task id comes from Slurm and is only ever a number
// added to `first` by bash's arithmetic; `particles job` refuses an index past the end.
void writeArrayScript(const std::filesystem::path& file, const SweepPlan& plan, size_t first, size_t count,
                      const std::string& what) {
  const std::string logs = (plan.outDir / "logs").string();
  std::error_code ec;
  std::filesystem::create_directories(logs, ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", logs, ec.message()));
  std::string text = fmt::format(
      "#!/bin/bash\n"
      "# particles sweep {name}: {what} as a Slurm job array, one job per task; task i runs job {first} + i\n"
      "# of {table} (written by `particles sweep --emit slurm`, docs/sweeps.md). Jobs that are done\n"
      "# are skipped by their records, so resubmitting resumes. Afterwards: particles gather {out}\n"
      "#SBATCH --job-name=particles-{name}\n"
      "#SBATCH --array=0-{last}\n"
      "#SBATCH --ntasks=1\n"
      "{output}",
      fmt::arg("name", plan.spec.name), fmt::arg("what", what), fmt::arg("first", first),
      fmt::arg("table", (plan.outDir / "jobs.csv").string()), fmt::arg("out", shellQuote(plan.outDir.string())),
      fmt::arg("last", count - 1),
      // sbatch splits #SBATCH lines at spaces and reads % as a pattern: a log path with either
      // (or a quote) is left to Slurm's default, slurm-JOB_TASK.out in the submitting folder.
      fmt::arg("output",
               logs.find_first_of(" \t\"'\\%") == std::string::npos
                   ? fmt::format("#SBATCH --output={}/slurm-%A_%a.log\n", logs)
                   : std::string("# logs: Slurm's default (the output folder's path has a space, quote or %)\n")));
  for (const std::string& line : plan.spec.slurm) text += "#SBATCH " + line + "\n";
  // The job's threads: the task's CPUs when sbatch is asked for them (--cpus-per-task, e.g. in the
  // sweep file's slurm: list) and PARTICLES_THREADS does not give them already; otherwise the job's
  // default, the CPUs Slurm binds the task to (its affinity and cgroup). Slurm's number reaches the
  // job as one quoted argument, which `particles job` checks as a thread count.
  text += fmt::format(
      "set -eu\n"
      "if [ -n \"${{SLURM_CPUS_PER_TASK:-}}\" ] && [ -z \"${{PARTICLES_THREADS:-}}\" ]; then\n"
      "  exec {program} job {out} \"$(({first} + SLURM_ARRAY_TASK_ID))\" --threads \"$SLURM_CPUS_PER_TASK\"\n"
      "fi\n"
      "exec {program} job {out} \"$(({first} + SLURM_ARRAY_TASK_ID))\"\n",
      fmt::arg("program", shellQuote(plan.program)), fmt::arg("out", shellQuote(plan.outDir.string())),
      fmt::arg("first", first));
  output::OutputFile out(file);
  out.write(text);
  out.commit();
  std::filesystem::permissions(file, std::filesystem::perms::owner_exec | std::filesystem::perms::group_exec,
                               std::filesystem::perm_options::add, ec);
}

}  // namespace

void checkListPaths(const SweepPlan& plan) {
  checkListPath("the program's path", plan.program);
  checkListPath("the output folder", plan.outDir.string());
}

std::string emitParallel(const SweepPlan& plan) {
  checkListPaths(plan);
  const auto jobs = plan.outDir / "jobs.txt";
  writeLines(jobs, plan, 0, plan.firstStageCount);
  // parallel runs one job per CPU unless told otherwise (-j), so one thread each: together they
  // fill the CPUs without oversubscribing them (docs/sweeps.md, "Order and threads").
  std::string how = fmt::format("{}=1 parallel --joblog {} < {}", kThreadsEnvironmentVariable,
                                shellQuote((plan.outDir / "joblog.txt").string()), shellQuote(jobs.string()));
  if (plan.firstStageCount < plan.jobs.size()) {
    const auto concat = plan.outDir / "concat.txt";
    writeLines(concat, plan, plan.firstStageCount, plan.jobs.size());
    how += fmt::format(" && parallel < {}", shellQuote(concat.string()));
  }
  return how;
}

std::string emitSlurm(const SweepPlan& plan) {
  checkListPaths(plan);
  const auto script = plan.outDir / "sweep.sbatch";
  writeArrayScript(script, plan, 0, plan.firstStageCount, fmt::format("{} jobs", plan.firstStageCount));
  if (plan.firstStageCount == plan.jobs.size()) return fmt::format("sbatch {}", shellQuote(script.string()));

  const auto concatScript = plan.outDir / "concat.sbatch";
  writeArrayScript(concatScript, plan, plan.firstStageCount, plan.jobs.size() - plan.firstStageCount,
                   "the joins of the split renders");
  const auto submit = plan.outDir / "submit.sh";
  {
    output::OutputFile out(submit);
    out.write(
        fmt::format("#!/bin/bash\n"
                    "# Submits the segments, then the joins once every segment has succeeded (docs/sweeps.md).\n"
                    "set -eu\n"
                    "segments=$(sbatch --parsable \"$@\" {})\n"
                    "sbatch --dependency=afterok:\"${{segments%%;*}}\" \"$@\" {}\n",
                    shellQuote(script.string()), shellQuote(concatScript.string())));
    out.commit();
  }
  std::error_code ec;
  std::filesystem::permissions(submit, std::filesystem::perms::owner_exec, std::filesystem::perm_options::add, ec);
  return fmt::format("bash {}   # sbatch's options (e.g. --wait) may follow", shellQuote(submit.string()));
}

}  // namespace particles::app
