// `particles job OUT INDEX`: see job_command.hpp.
#include "app/job_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <memory>

#include "app/cli.hpp"
#include "app/cli_support.hpp"
#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "app/job_table.hpp"
#include "app/thread_count.hpp"
#include "output/confined_folder.hpp"
#include "input/printable_text.hpp"
#include "output/write_sandbox.hpp"

namespace particles::app {

namespace {

// The command a stage's job runs.
std::string commandOfStage(const std::string& stage) {
  if (stage == "segment") return "render";
  return stage;  // run, render, stability, concat (parseJobTable admits no other)
}

void addRunJobOptions(CLI::App& command, RunJobOptions& o) {
  command.add_option("outdir", o.outDir, "The sweep's output folder (with jobs.csv)")->required();
  command.add_option("index", o.index, "The job's index: 0 for the first row of jobs.csv")->required();
  command.add_flag("--force", o.force, "Run the job even when its record says it is done");
  command
      .add_option("--threads", o.threads,
                  "Threads for the job's command, unless its line in jobs.csv sets --threads (not recorded: the "
                  "results are the same for every count)")
      ->check(CLI::Range(1, kMaxThreads));
  addMaxInputOption(command, o.maxInputMiB, "a job table or record");
  command.footer(
      "The job lists that 'particles sweep --emit' writes are lines of this command: GNU parallel and Slurm\n"
      "run them as they are. The job's record makes a rerun of a finished job a no-op.\n"
      "Examples:\n"
      "  particles job cloth-sweep 0\n"
      "  particles job cloth-sweep 0 --threads 2          # what 'particles sweep' starts: its share of the CPUs\n"
      "  SLURM_ARRAY_TASK_ID=3 bash cloth-sweep/sweep.sbatch   # what a Slurm array task runs\n");
}

// Every file the row's command writes lies beneath the sweep's folder (output/confined_folder.hpp):
// its command line names it inside the folder, and it is reached from there without a link that
// leads out. The job's folder and record are what `particles sweep` made them: a folder, and a
// record or nothing; a link or a file of another kind there is refused, as is an output that is a
// link. The folder is anyone's to touch (docs/sweeps.md): a row edited to
// `--stats /elsewhere/victim.csv` stops here, exit 2.
void requireFilesBeneath(const std::filesystem::path& outDir, const JobTable& table, size_t index, const Cli& cli) {
  const std::string where = fmt::format("{}:{}: job {}", table.file, table.rowLines[index], index);
  const output::ConfinedFolder folder(outDir);
  const std::string& jobDir = table.rows[index][table.dirColumn()];
  const output::PlacedName dir = folder.place(jobDir, false);
  if (dir.kind != output::EntryKind::directory && dir.kind != output::EntryKind::absent) {
    throw InputError(fmt::format("{}: its folder {} is {}; a job's folder is a folder that `particles sweep` made",
                                 where, dir.shown.string(),
                                 dir.kind == output::EntryKind::symlink ? "a symbolic link" : "not a folder"));
  }
  std::vector<output::NamedFile> files = cli.commandFiles().outputs;
  const std::string record = cli.recordFile();
  if (!record.empty()) files.push_back({"--record", record});
  for (const output::NamedFile& f : files) {
    if (f.path.empty()) continue;
    const std::filesystem::path relative = output::relativeBeneath(f.path, outDir);
    if (relative.empty()) {
      throw InputError(fmt::format("{}: {} {} is outside the sweep's folder {}; a job writes only beneath it", where,
                                   f.role, f.path.string(), outDir.string()));
    }
    // Within the folder, a job writes only in its own: never over jobs.csv, which it reads, nor
    // into another job's folder, whose record and outputs are that job's.
    if (output::relativeBeneath(f.path, outDir / jobDir).empty()) {
      throw InputError(
          fmt::format("{}: {} {} is outside the job's own folder {}", where, f.role, f.path.string(), jobDir));
    }
    const output::PlacedName placed = folder.place(relative, false);  // throws OutsideFolderError
    const bool folderOutput = f.role != "--record" && placed.kind == output::EntryKind::directory;  // a PNG sequence
    if (placed.kind != output::EntryKind::absent && placed.kind != output::EntryKind::regular && !folderOutput) {
      throw InputError(fmt::format(
          "{}: {} {} is {}; a job's files are regular files, left as they are here", where, f.role,
          placed.shown.string(), placed.kind == output::EntryKind::symlink ? "a symbolic link" : "not a regular file"));
    }
  }
}

int runJobCommand(const RunJobOptions& o) {
  const JobTable table = readJobTable(o.outDir, o.maxInputMiB);
  size_t index = 0;
  const auto [end, ec] = std::from_chars(o.index.data(), o.index.data() + o.index.size(), index);
  if (o.index.empty() || ec != std::errc() || end != o.index.data() + o.index.size()) {
    throw InputError(fmt::format("job index {}: expected a whole number from 0", input::quotedValue(o.index)));
  }
  if (index >= table.rows.size()) {
    throw InputError(fmt::format("no job {} in {}: it has {} (0 … {})", index, table.file, table.rows.size(),
                                 table.rows.empty() ? std::string("none") : std::to_string(table.rows.size() - 1)));
  }
  const std::vector<std::string>& row = table.rows[index];
  std::vector<std::string> args = *splitCommandText(row[table.commandColumn()]);  // checked by parseJobTable
  args.erase(args.begin());                                                       // the program: this one runs the job
  const std::string command = commandOfStage(row[JobTable::kStage]);
  if (args.front() != command) {
    throw InputError(fmt::format("{}:{}: job {} is a {} job, but its command runs {}", table.file,
                                 table.rowLines[index], index, row[JobTable::kStage],
                                 input::quotedValue(args.front())));
  }
  if (o.force) args.push_back("--force");

  auto parsed = [&](const std::vector<std::string>& line) {
    auto cli = std::make_unique<Cli>();
    try {
      cli->parse(line);
    } catch (const CLI::ParseError& e) {
      throw InputError(fmt::format("{}:{}: job {}'s command line: {}", table.file, table.rowLines[index], index,
                                   e.get_exit_code() == 0 ? "--help and --version are not jobs" : e.what()));
    }
    return cli;
  };
  std::unique_ptr<Cli> cli = parsed(args);
  if (o.threads > 0) {
    const CLI::Option* threads = cli->command(command).get_option_no_throw("--threads");
    if (threads != nullptr && threads->count() == 0) {
      std::vector<std::string> withThreads = args;
      withThreads.insert(withThreads.end(), {"--threads", std::to_string(o.threads)});
      cli = parsed(withThreads);
    }
  }
  requireFilesBeneath(o.outDir, table, index, *cli);
  // From here on the kernel refuses writes outside the folder, where it can (write_sandbox.hpp).
  output::restrictWritesBeneath(o.outDir);
  // The record names the job's own line, `args`, whatever threads it runs on.
  return cli->dispatch(args);
}

}  // namespace

const CommandDescriptor<RunJobOptions> kRunJobCommand = {
    .name = "job",
    .summary = "Run one job of a sweep, by its index in OUT/jobs.csv",
    .addOptions = addRunJobOptions,
    .run = runJobCommand,
};

}  // namespace particles::app
