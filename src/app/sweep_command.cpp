// `particles sweep`: see sweep_command.hpp. Running here is a bounded pool of child processes, each
// one job's command line with its stdout and stderr in its folder's log.txt; every job is the same
// command line GNU parallel or Slurm would run, records and all.
#include "app/sweep_command.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <map>

#include "input/available_cores.hpp"
#include "app/cli_support.hpp"
#include "app/exit_codes.hpp"
#include "app/gather_command.hpp"
#include "app/job_record.hpp"
#include "app/stop_signal.hpp"
#include "app/sweep_job_lists.hpp"
#include "app/sweep_plan.hpp"
#include "app/sweep_schedule.hpp"
#include "app/thread_count.hpp"
#include "input/text_file.hpp"
#include "output/distinct_files.hpp"
#include "output/output_error.hpp"
#include "scenario/sweep_spec.hpp"

namespace particles::app {

namespace {

std::string thisProgram() {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw InputError("cannot find this program's path (/proc/self/exe): give --program");
  return self.string();
}

// Starts job `index` as `program job OUT INDEX`, exactly the line the emitted lists hold (with
// `--threads N` when `threads` > 0: its share of the cores, which is no part of the job's record),
// with its output in `log`; the child gets SIGTERM if the sweep dies.
pid_t startJob(const SweepPlan& plan, size_t index, const std::filesystem::path& log, bool force, int threads) {
  std::vector<std::string> all = {plan.program, "job", plan.outDir.string(), std::to_string(index)};
  if (force) all.push_back("--force");
  if (threads > 0) all.insert(all.end(), {"--threads", std::to_string(threads)});
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string logPath = log.string();
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw output::OutputError(fmt::format("cannot start a job: fork: {}", std::strerror(errno)));
  if (pid == 0) {
    // Only async-signal-safe calls from here to exec.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(128 + SIGTERM);
    const int in = open("/dev/null", O_RDONLY);
    // Non-blocking, so that a FIFO put at the log's path fails here instead of waiting for a reader.
    const int out = open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NONBLOCK, 0644);
    if (in < 0 || out < 0 || fcntl(out, F_SETFL, 0) < 0 || dup2(in, 0) < 0 || dup2(out, 1) < 0 || dup2(out, 2) < 0) {
      _exit(127);
    }
    close(in);
    close(out);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

// The record at `file`, or nullopt when there is none or it cannot be read as one (the job
// itself then says why).
std::optional<JobRecord> recordOrNothing(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  try {
    return readJobRecord(file, maxInputMiB);
  } catch (const input::ReadError&) {
    return std::nullopt;
  }
}

// The last non-empty line of a job's log, read from its last 4 KiB only.
std::string lastLogLine(const std::filesystem::path& log) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(log, ec)) return {};
  std::ifstream in(log, std::ios::binary);
  const auto size = std::filesystem::file_size(log, ec);
  if (ec) return {};
  const std::uintmax_t tail = std::min<std::uintmax_t>(size, 4096);
  in.seekg(std::streamoff(size - tail));
  std::string text(tail, '\0');
  in.read(text.data(), std::streamsize(tail));
  text.resize(size_t(in.gcount()));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const size_t start = text.find_last_of('\n');
  return start == std::string::npos ? text : text.substr(start + 1);
}

// The error a failed job printed: its record's message, else the last line of its log.
std::string failureMessage(const SweepJob& job, const SweepPlan& plan, int code, std::uintmax_t maxInputMiB) {
  if (auto r = recordOrNothing(job.record, maxInputMiB); r && !r->message.empty()) return r->message;
  const std::string last = lastLogLine(plan.outDir / job.dir / "log.txt");
  if (code == 127 && last.empty()) return "could not start the program";
  return last.empty() ? fmt::format("exit {}", code) : last;
}

std::string describeJob(const SweepPlan& plan, const SweepJob& job) {
  std::string text = fmt::format("job {} ({}", job.index, job.scenario);
  for (size_t k = 0; k < plan.columns.size(); ++k) text += fmt::format(", {} = {}", plan.columns[k], job.values[k]);
  if (!job.segment.empty()) text += fmt::format(", segment {}", job.segment);
  if (job.stage == "concat") text += ", joined";
  return text + ")";
}

struct RunTally {
  size_t ran = 0, ok = 0, skipped = 0;
  std::vector<std::string> failures;
};

// How the jobs run here: at most `parallel` at once; with `cores` > 0, each started with its share of
// them as --threads (sweep_schedule.hpp), else with the threads the sweep file or PARTICLES_THREADS
// gives.
struct Workers {
  int parallel = 1;
  int cores = 0;
};

// Jobs [from, to) that are to run: not done before (by their records) and, for a join, with every
// segment it joins done. The others are tallied here.
std::vector<size_t> jobsToRun(const SweepPlan& plan, size_t from, size_t to, const SweepOptions& o, RunTally& tally,
                              std::vector<bool>& succeeded, size_t& done) {
  std::vector<size_t> pending;
  for (size_t i = from; i < to; ++i) {
    const SweepJob& job = plan.jobs[i];
    bool ready = true;
    for (size_t k : job.after) ready = ready && succeeded[k];
    if (!ready) {
      tally.failures.push_back(fmt::format("{}: not run: a segment it joins failed", describeJob(plan, job)));
      ++done;
    } else if (!o.force && jobDone(recordOrNothing(job.record, o.maxInputMiB), commandText(job.args))) {
      succeeded[job.index] = true;
      ++tally.skipped;
      ++done;
    } else {
      pending.push_back(i);
    }
  }
  return pending;
}

// Runs jobs [from, to), the longest first (sweep_schedule.hpp). Returns false when interrupted.
bool runJobs(const SweepPlan& plan, size_t from, size_t to, const Workers& workers, const SweepOptions& o,
             RunTally& tally, std::vector<bool>& succeeded, Progress& progress, size_t& done) {
  const std::vector<size_t> pending = jobsToRun(plan, from, to, o, tally, succeeded, done);
  const std::vector<JobEstimate> estimates = estimateJobs(plan, pending, o.maxInputMiB);
  const std::vector<size_t> order = longestFirst(estimates);
  // costAfter[k]: the estimated cost of the jobs after order[k].
  std::vector<double> costAfter(order.size() + 1, 0.0);
  for (size_t k = order.size(); k-- > 0;) costAfter[k] = costAfter[k + 1] + estimates[order[k]].cost;
  std::map<pid_t, size_t> running;
  bool alone = false;  // a job runs alone on every core (runsAlone): start none beside it
  size_t next = 0;
  const size_t total = plan.jobs.size();
  auto stopAll = [&] {
    for (const auto& [pid, index] : running) kill(pid, SIGTERM);
    while (!running.empty()) {
      int status = 0;
      const pid_t pid = waitpid(-1, &status, 0);
      if (pid > 0) running.erase(pid);
      if (pid < 0 && errno == ECHILD) break;
    }
  };
  while (next < order.size() || !running.empty()) {
    while (next < order.size() && int(running.size()) < workers.parallel && !alone && !stopSignal()) {
      const SweepJob& job = plan.jobs[pending[order[next]]];
      const JobEstimate& estimate = estimates[order[next]];
      alone = workers.cores > 0 && runsAlone(estimate, costAfter[next + 1], workers.parallel, running.size());
      const size_t toStart = order.size() - next++;  // this job and those after it
      // A join simulates nothing: it has no --threads.
      int threads = 0;
      if (alone) {
        threads = workers.cores;
      } else if (workers.cores > 0 && job.stage != "concat") {
        threads = threadShare(workers.cores, workers.parallel, running.size(), toStart);
      }
      running[startJob(plan, job.index, plan.outDir / job.dir / "log.txt", o.force, threads)] = job.index;
      ++tally.ran;
    }
    progress.update(long(done), long(total), fmt::format("{} running", running.size()));
    if (stopSignal()) {
      stopAll();
      return false;
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) continue;  // EINTR: a stop signal, handled above
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const SweepJob& job = plan.jobs[it->second];
    running.erase(it);
    if (running.empty()) alone = false;
    ++done;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (code == 0) {
      succeeded[job.index] = true;
      ++tally.ok;
    } else {
      const std::string failure =
          fmt::format("{}: exit {}: {}", describeJob(plan, job), code, failureMessage(job, plan, code, o.maxInputMiB));
      progress.finish();
      if (!o.quiet) fmt::print(stderr, "failed: {}\n", failure);
      tally.failures.push_back(failure);
    }
  }
  return true;
}

// Where the jobs' threads are set explicitly, which the sweep then respects: the sweep file's
// `threads` option (on every job's command line), else PARTICLES_THREADS, which the jobs inherit
// (checked here, before anything is written). Empty: nowhere, the sweep gives each job its share.
std::string explicitThreads(const scenario::SweepSpec& spec) {
  const auto& options = spec.options;
  if (std::any_of(options.begin(), options.end(), [](const auto& option) { return option.name == "threads"; })) {
    return "the sweep file's";
  }
  if (threadCountGiven(0)) {
    threadCountOf(0);  // throws InputError for a value that is not a thread count
    return kThreadsEnvironmentVariable;
  }
  return {};
}

void addSweepOptions(CLI::App& command, SweepOptions& o) {
  command.add_option("spec", o.spec, "The sweep file (YAML, see docs/sweeps.md)")->required();
  command.add_option("-o,--out", o.out,
                     "The output folder: jobs.csv, a folder per job, results.csv (default ./sweep-NAME)");
  command
      .add_option("-j,--jobs", o.jobs,
                  "Jobs at once here (0: one per CPU this process may use), the longest first, each with its share "
                  "of the CPUs as --threads")
      ->check(CLI::Range(0, 4096));
  command
      .add_option("--emit", o.emit,
                  "Write the jobs for another engine and run nothing: parallel (jobs.txt for GNU parallel) or slurm "
                  "(sweep.sbatch, a job array)")
      ->check(CLI::IsMember({"parallel", "slurm"}));
  command.add_option("--program", o.program,
                     "The particles program the jobs run (default: this one, by its full path)");
  command.add_flag("--force", o.force, "Run every job again, even those whose records say they are done");
  command.add_flag("-q,--quiet", o.quiet, "No progress and no summary; failures are still printed");
  addMaxInputOption(command, o.maxInputMiB, "a sweep or scenario file (or a record)");
  command.footer(
      "Every job is a plain 'particles …' command line with its outputs in OUT/jobs/NNNNNN/ and a record\n"
      "there: a rerun skips what is done, so an interrupted sweep resumes. After running, the results\n"
      "are gathered into OUT/results.csv (and OUT/results.svg when one parameter varies).\n"
      "Run here, the jobs start longest first (steps × size; a stability study's steps from its stiffest\n"
      "mode) and each gets --threads max(1, CPUs / min(JOBS, jobs unfinished)): jobs × threads stay within\n"
      "the CPUs, and the last jobs use the idle ones too; a job estimated to outlast all the others left\n"
      "(per other worker) runs alone on every CPU. A 'threads' option in the sweep file, or\n"
      "PARTICLES_THREADS, is kept instead. Records and results do not depend on either.\n"
      "Exit codes: 0 all jobs succeeded, 1 some failed (listed), 2 a bad sweep file, 3 an output failed.\n"
      "Examples:\n"
      "  particles sweep scenarios/sweeps/cloth_stiffness.yaml -o cloth-sweep --jobs 2\n"
      "  particles sweep my.yaml -o out --emit parallel && PARTICLES_THREADS=1 parallel < out/jobs.txt\n"
      "  particles sweep my.yaml -o out --emit slurm && sbatch out/sweep.sbatch\n"
      "  particles gather out\n");
}

// What the sweep itself writes in its folder `out` (each job checks its own files when it runs): the
// folder, the job table, the results and their figure, and the lists --emit writes.
std::vector<output::NamedFile> sweepOutputs(const std::filesystem::path& out, const std::string& emit) {
  std::vector<output::NamedFile> files = {{"the output folder", out},
                                          {"the job table", out / "jobs.csv"},
                                          {"the results", out / "results.csv"},
                                          {"the figure", out / "results.svg"}};
  const std::vector<std::string> lists = emit == "parallel" ? std::vector<std::string>{"jobs.txt", "concat.txt"}
                                         : emit == "slurm"
                                             ? std::vector<std::string>{"sweep.sbatch", "concat.sbatch", "submit.sh"}
                                             : std::vector<std::string>{};
  for (const std::string& list : lists) files.push_back({"the job list", out / list});
  return files;
}

// The files the command line names: the sweep file, and what the sweep writes when -o names its
// folder (the default folder is named after the sweep, checked once the file is read).
CommandFiles sweepFiles(const SweepOptions& o) {
  return {o.out.empty() ? std::vector<output::NamedFile>{} : sweepOutputs(o.out, o.emit), {{"the sweep file", o.spec}}};
}

// Nothing the sweep writes in its folder is the sweep file or one of its scenarios.
void requireInputsKept(const SweepOptions& o, const scenario::SweepSpec& spec, const std::filesystem::path& out) {
  std::vector<output::NamedFile> inputs = {{"the sweep file", o.spec}};
  for (const auto& s : spec.scenarios) inputs.push_back({"the scenario", s.path});
  output::requireDistinctFiles(sweepOutputs(out, o.emit), inputs);
}

// --emit: the job lists for GNU parallel or Slurm, and how to run them; nothing runs here.
int emitJobLists(const SweepPlan& plan, const SweepOptions& o) {
  const std::string how = o.emit == "parallel" ? emitParallel(plan) : emitSlurm(plan);
  if (!o.quiet) {
    fmt::print("{}: {} → {}/jobs.csv\nrun them with:\n  {}\nthen: particles gather {}\n", o.spec,
               plural(plan.jobs.size(), "job", "jobs"), plan.outDir.string(), how, shellQuote(plan.outDir.string()));
  }
  return kOk;
}

// After the jobs ran: their results gathered, the summary, the failures listed (exit 1).
int gatherResults(const SweepPlan& plan, const SweepOptions& o, const RunTally& tally, double seconds) {
  GatherOptions gather;
  gather.outDir = plan.outDir.string();
  gather.quiet = true;
  gather.maxInputMiB = o.maxInputMiB;
  gatherCommand(gather);
  if (!o.quiet) {
    fmt::print("{}: {} in {:.1f} s: {} ran ({} ok, {} failed), {} done before → {}\n", o.spec,
               plural(plan.jobs.size(), "job", "jobs"), seconds, tally.ran, tally.ok, tally.failures.size(),
               tally.skipped, (plan.outDir / "results.csv").string());
  }
  if (!tally.failures.empty()) {
    fmt::print(stderr, "{} failed:\n", plural(tally.failures.size(), "job", "jobs"));
    for (const std::string& f : tally.failures) fmt::print(stderr, "  {}\n", f);
    return kSimulationFailed;
  }
  return kOk;
}

int sweepCommand(const SweepOptions& o) {
  const scenario::SweepSpec spec = scenario::loadSweepFile(o.spec, o.maxInputMiB);
  const std::string program =
      o.program.empty() ? thisProgram() : std::filesystem::absolute(o.program).lexically_normal().string();
  const std::filesystem::path out =
      o.out.empty() ? std::filesystem::path("sweep-" + spec.name) : std::filesystem::path(o.out);
  requireInputsKept(o, spec, out);
  const SweepPlan plan = planSweep(spec, out, program, o.maxInputMiB, !o.quiet);
  if (!o.emit.empty()) checkListPaths(plan);
  const std::string threadsGiven = o.emit.empty() ? explicitThreads(spec) : std::string();
  writeJobTable(plan);

  if (!o.emit.empty()) return emitJobLists(plan, o);

  const int cores = input::availableCores();
  const Workers workers{.parallel = o.jobs > 0 ? o.jobs : cores, .cores = threadsGiven.empty() ? cores : 0};
  if (!o.quiet) {
    fmt::print(stderr, "{}: {} ({}), {} at once, longest first, threads: {} → {}\n", o.spec,
               plural(plan.jobs.size(), "job", "jobs"), spec.command, workers.parallel,
               threadsGiven.empty() ? fmt::format("shares of {}", plural(size_t(cores), "CPU", "CPUs")) : threadsGiven,
               plan.outDir.string());
  }
  const auto start = std::chrono::steady_clock::now();
  StopSignals signals(StopMode::interruptWaits);
  RunTally tally;
  std::vector<bool> succeeded(plan.jobs.size(), false);
  size_t done = 0;
  bool finished;
  {
    Progress progress(!o.quiet, "jobs");
    finished = runJobs(plan, 0, plan.firstStageCount, workers, o, tally, succeeded, progress, done) &&
               runJobs(plan, plan.firstStageCount, plan.jobs.size(), workers, o, tally, succeeded, progress, done);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!finished) {
    fmt::print(stderr, "{}: interrupted after {} of {} jobs; run the same command again to resume\n", o.spec, done,
               plan.jobs.size());
    return 128 + stopSignal();
  }

  return gatherResults(plan, o, tally, seconds);
}

}  // namespace

const CommandDescriptor<SweepOptions> kSweepCommand = {
    .name = "sweep",
    .summary = "Run one command over scenarios × parameters (here, or as job lists for GNU parallel and Slurm)",
    .addOptions = addSweepOptions,
    .run = sweepCommand,
    .files = sweepFiles,
};

}  // namespace particles::app
