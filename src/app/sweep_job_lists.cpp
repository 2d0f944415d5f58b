// A sweep's job lists for GNU parallel and Slurm: see sweep_job_lists.hpp.
#include "app/sweep_job_lists.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <string>

#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "input/default_threads.hpp"
#include "input/printable_text.hpp"
#include "output/confined_folder.hpp"
#include "output/output_file.hpp"
#include "output/shell_words.hpp"

namespace particles::app {

namespace {

// The job lists hold one line per job, `PROGRAM job OUT INDEX`: two paths and fixed words, quoted
// by shellQuote. A control character in either path would need bash's $'…', which the shell GNU
// parallel starts (often sh) may not read, so such a path is refused.
void checkListPath(const std::string& what, const std::string& path) {
  if (std::any_of(path.begin(), path.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    throw InputError(
        fmt::format("{} {} holds a control character (a line break?): the job lists are lines of "
                    "shell text, so give a path without one",
                    what, input::quotedValue(shellQuote(path))));
  }
}

std::string jobLine(const SweepPlan& plan, size_t index) {
  return commandText({plan.program, "job", plan.outDir.string(), std::to_string(index)});
}

void writeLines(const std::string& name, const SweepPlan& plan, size_t from, size_t to) {
  output::OutputFile out(output::ConfinedFolder(plan.outDir), name);
  for (size_t i = from; i < to; ++i) out.write(jobLine(plan, i) + "\n");
  out.commit();
}

// A Slurm array script: task i runs job first + i. Nothing of the sweep's values is in it, only
// the program and the output folder, quoted; the task id comes from Slurm and is only ever a number
// added to `first` by bash's arithmetic; `particles job` refuses an index past the end.
// Writes the script `name` in the sweep's folder, executable.
void writeScript(const SweepPlan& plan, const std::string& name, const std::string& text, mode_t executable) {
  const output::ConfinedFolder folder(plan.outDir);
  output::OutputFile out(folder, name);
  out.write(text);
  out.commit();
  const output::PlacedName placed = folder.place(name, true);
  struct stat st {};
  if (::fstatat(placed.folder.get(), placed.name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode)) {
    ::fchmodat(placed.folder.get(), placed.name.c_str(), (st.st_mode & 07777) | executable, 0);
  }
}

void writeArrayScript(const std::string& name, const SweepPlan& plan, size_t first, size_t count,
                      const std::string& what) {
  const std::string logs = (plan.outDir / "logs").string();
  output::ConfinedFolder(plan.outDir).openFolder("logs", output::ConfinedFolder::Create::yes);
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
  writeScript(plan, name, text, S_IXUSR | S_IXGRP);
}

}  // namespace

void checkListPaths(const SweepPlan& plan) {
  checkListPath("the program's path", plan.program);
  checkListPath("the output folder", plan.outDir.string());
}

std::string emitParallel(const SweepPlan& plan) {
  checkListPaths(plan);
  const auto jobs = plan.outDir / "jobs.txt";
  writeLines("jobs.txt", plan, 0, plan.firstStageCount);
  // parallel runs one job per CPU unless told otherwise (-j), so one thread each: together they
  // fill the CPUs without oversubscribing them (docs/sweeps.md, "Order and threads").
  std::string how = fmt::format("{}=1 parallel --joblog {} < {}", kThreadsEnvironmentVariable,
                                shellQuote((plan.outDir / "joblog.txt").string()), shellQuote(jobs.string()));
  if (plan.firstStageCount < plan.jobs.size()) {
    const auto concat = plan.outDir / "concat.txt";
    writeLines("concat.txt", plan, plan.firstStageCount, plan.jobs.size());
    how += fmt::format(" && parallel < {}", shellQuote(concat.string()));
  }
  return how;
}

std::string emitSlurm(const SweepPlan& plan) {
  checkListPaths(plan);
  const auto script = plan.outDir / "sweep.sbatch";
  writeArrayScript("sweep.sbatch", plan, 0, plan.firstStageCount, fmt::format("{} jobs", plan.firstStageCount));
  if (plan.firstStageCount == plan.jobs.size()) return fmt::format("sbatch {}", shellQuote(script.string()));

  const auto concatScript = plan.outDir / "concat.sbatch";
  writeArrayScript("concat.sbatch", plan, plan.firstStageCount, plan.jobs.size() - plan.firstStageCount,
                   "the joins of the split renders");
  const auto submit = plan.outDir / "submit.sh";
  writeScript(plan, "submit.sh",
              fmt::format("#!/bin/bash\n"
                          "# Submits the segments, then the joins once every segment has succeeded (docs/sweeps.md).\n"
                          "set -eu\n"
                          "segments=$(sbatch --parsable \"$@\" {})\n"
                          "sbatch --dependency=afterok:\"${{segments%%;*}}\" \"$@\" {}\n",
                          shellQuote(script.string()), shellQuote(concatScript.string())),
              S_IXUSR);
  return fmt::format("bash {}   # sbatch's options (e.g. --wait) may follow", shellQuote(submit.string()));
}

}  // namespace particles::app
