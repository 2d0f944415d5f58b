// `particles golden`: see golden_command.hpp.
#include "app/golden_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "input/available_cores.hpp"
#include "app/cli_support.hpp"
#include "app/gl_options.hpp"
#include "golden/check.hpp"
#include "golden/references.hpp"
#include "golden/results.hpp"
#include "output/confined_folder.hpp"
#include "output/distinct_files.hpp"
#include "output/output_error.hpp"
#include "output/printable_text.hpp"
#include "output/staging_directory.hpp"
#include "render/image_compare.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::app {

namespace fs = std::filesystem;

namespace {

void addRunOptions(CLI::App& command, GoldenRunOptions& o) {
  command.add_option("manifest", o.manifest, "The golden manifest (YAML, golden/README.md)")->capture_default_str();
  command
      .add_option("-j,--jobs", o.jobs,
                  "Entries simulated at once (default: half the CPUs this process may use, at least 1)")
      ->check(CLI::Range(1, 256));
  command
      .add_option("--gl", o.gl,
                  fmt::format("GL backend: auto (EGL, else OSMesa), egl or osmesa (default: ${}, else auto)",
                              kGlEnvironmentVariable))
      ->check(CLI::IsMember(render::glBackendNames()));
  addMaxInputOption(command, o.maxInputMiB, "a manifest, scenario or reference");
  command.add_flag("-q,--quiet", o.quiet, "No progress and no list of failures; the summary line is still printed");
}

void addGoldenOptions(CLI::App& command, GoldenOptions& o) {
  command.require_subcommand(1);
  command.footer(
      "Guide: golden/README.md (golden-test your own scenarios in CI). Each subcommand's options:\n"
      "  particles golden check --help\n");
  CLI::App* check = command.add_subcommand("check", "Compare the manifest's frames and states with their references");
  o.checkCommand = check;
  addRunOptions(*check, o.check.run);
  check->add_option("-o,--output", o.check.output, "The report folder: report.html, junit.xml, results.json")
      ->capture_default_str();
  check->add_option("--shard", o.check.shard, "Only the K-th of N near-equal parts of the checks (CI jobs: 1/2, 2/2)")
      ->type_name("K/N");
  check->add_option("--only", o.check.only, "Only this frame or state (repeatable)")
      ->type_name("NAME")
      ->allow_extra_args(false);
  check->add_option("--raster", o.check.raster, "The raster path for entries that do not set their own")
      ->check(CLI::IsMember(render::rasterNames()));
  check->add_option("--threshold", o.check.threshold, "The threshold for entries that do not set their own (0 … 255)")
      ->check(CLI::Range(0, 255));
  check->add_option("--max-share", o.check.maxShare, "The share bound for entries that do not set their own (0 … 1)")
      ->check(CLI::Range(0.0, 1.0));
  check->footer(fmt::format(
      "Exit codes: 0 every check passed, 1 one failed, has no reference yet or could not run (its scenario or\n"
      "simulation failed), 2 a bad manifest or usage or an\n"
      "unusable reference (a FIFO, too large, not a PNG: the report is still written), 3 the report could not be\n"
      "written. Guide: golden/README.md.\n"
      "Examples:\n"
      "  particles golden check\n"
      "  particles golden check golden/golden.yaml -o golden-report --gl egl\n"
      "  particles golden check --shard 1/2 -o report-1 && particles golden check --shard 2/2 -o report-2\n"
      "  particles golden check --only cloth_t2.5 --raster tiles --max-share 0.0005\n"));

  CLI::App* update = command.add_subcommand("update", "Write references: render them, or accept a report's (--from)");
  o.updateCommand = update;
  addRunOptions(*update, o.update.run);
  update->add_option("names", o.update.names, "Only these frames and states (after the manifest)")->type_name("NAME");
  update
      ->add_option("--from", o.update.from,
                   "Accept the actual frames and states of this report folder without rendering (repeatable: "
                   "folders that disagree are refused)")
      ->allow_extra_args(false);
  update->add_flag("--missing", o.update.missing, "Only the references that do not exist yet");
  update->footer(
      "Exit codes: 0 written (or unchanged), 1 a check could not be rendered or a --from folder's frames were\n"
      "refused, 2 a bad manifest, name or folder, 3 a reference could not be written.\n"
      "Examples:\n"
      "  particles golden update --missing\n"
      "  particles golden update golden/golden.yaml cloth_t2.5 soft_body\n"
      "  particles golden update --from ~/Downloads/golden-report\n");

  CLI::App* report = command.add_subcommand("report", "Merge the report folders of shards into one report");
  o.reportCommand = report;
  report->add_option("folders", o.report.folders, "The shards' report folders")->required();
  report->add_option("-o,--output", o.report.output, "The merged report folder")->capture_default_str();
  addMaxInputOption(*report, o.report.maxInputMiB, "a results.json or kept file");
  report->add_flag("-q,--quiet", o.report.quiet, "Only the summary line");
  report->footer("Example:\n  particles golden report report-1 report-2 -o golden-report\n");
}

// How the commands that reproduce a result spell this program: its path relative to here when it
// is below, else absolute (a report is read where the check ran).
std::string programPath() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "particles";
  const fs::path relative = self.lexically_relative(fs::current_path(ec));
  if (!ec && !relative.empty() && *relative.begin() != "..") return relative.string();
  return self.string();
}

scenario::GoldenManifest loadManifest(const GoldenRunOptions& o) {
  scenario::GoldenManifest m = scenario::loadGoldenManifestFile(o.manifest, o.maxInputMiB);
  golden::checkRenderSettings(m);
  return m;
}

golden::CheckOptions checkOptionsOf(const GoldenRunOptions& o) {
  golden::CheckOptions c;
  c.manifestGiven = o.manifest;
  c.gl = glRequestOf(o.gl, false);
  c.jobs = o.jobs > 0 ? o.jobs : std::max(1, input::availableCores() / 2);
  c.maxInputMiB = o.maxInputMiB;
  c.program = programPath();
  return c;
}

// K/N as written; its range is runCheck's to check.
std::optional<std::pair<int, int>> shardOf(const std::string& text) {
  if (text.empty()) return std::nullopt;
  int k = 0, n = 0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, k);
  if (ec == std::errc() && p < end && *p == '/') {
    auto [q, ec2] = std::from_chars(p + 1, end, n);
    if (ec2 == std::errc() && q == end) return std::pair{k, n};
  }
  throw InputError(fmt::format("--shard {}: expected K/N with 1 ≤ K ≤ N, e.g. 1/2", text));
}

// The files an earlier report in `folder` consists of: its three pages, the files its results.json
// lists, and the folders they are in. Everything in the folder must be one of those, or the
// folder is no report of ours and is refused (InputError, exit 2), left as it is.
std::vector<std::string> earlierReport(const fs::path& folder, std::uintmax_t maxInputMiB) {
  const std::string shown = output::printableText(folder.string());
  golden::GoldenResults earlier;
  try {
    earlier = golden::readResults(folder, maxInputMiB);
  } catch (const std::exception& e) {
    throw InputError(
        fmt::format("-o {}: a folder that holds something other than a golden report ({}); choose "
                    "another or empty it (it is replaced whole)",
                    shown, e.what()));
  }
  // frames/ and states/ are made by every check, kept files or none.
  std::set<std::string> files = golden::reportFiles(earlier), folders = {"frames", "states"};
  for (const std::string& file : files) {
    for (fs::path up = fs::path(file).parent_path(); !up.empty(); up = up.parent_path()) folders.insert(up.string());
  }
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string relative = it->path().lexically_relative(folder).generic_string();
    const fs::file_type type = it->symlink_status(ec).type();
    const bool listed = type == fs::file_type::regular     ? files.count(relative) > 0
                        : type == fs::file_type::directory ? folders.count(relative) > 0
                                                           : false;
    if (!listed) {
      throw InputError(
          fmt::format("-o {}: it holds {}, which is not part of the golden report there; choose another "
                      "folder or remove it (only a folder that is entirely an earlier report is replaced)",
                      shown, output::printableText(relative)));
    }
  }
  if (ec) throw InputError(fmt::format("-o {}: cannot list it: {}", shown, ec.message()));
  std::vector<std::string> all(files.begin(), files.end());
  all.insert(all.end(), folders.begin(), folders.end());
  return all;
}

// The report folder: made new, or replacing a folder that is entirely an earlier report (its
// results.json reads back as one, and it holds only what that report lists); anything else is
// refused, not overwritten. That it holds nothing the command reads is the rule of its files
// (goldenFiles, and reportFolderHoldsNoInput for what the manifest names). Returns the earlier
// report's files and folders, the only things `publish` removes.
std::vector<std::string> checkReportFolder(const fs::path& folder, std::uintmax_t maxInputMiB) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(folder, ec);
  if (st.type() == fs::file_type::not_found) return {};
  const std::string shown = output::printableText(folder.string());
  if (st.type() == fs::file_type::symlink) {
    throw InputError(fmt::format("-o {}: a symbolic link; give the folder itself (it is replaced whole)", shown));
  }
  if (st.type() != fs::file_type::directory) {
    throw InputError(fmt::format("-o {}: not a folder; the report is a folder", shown));
  }
  if (fs::is_empty(folder, ec)) return {};
  return earlierReport(folder, maxInputMiB);
}

// The report folder as one of the command's files: an output replaced whole, so that no input may
// lie beneath it (output/distinct_files.hpp).
output::NamedFile reportFolder(const std::string& folder) {
  return {"-o", folder, true};
}

// What the manifest names that `golden check` reads besides the manifest itself (which the
// command line names: goldenFiles): the references' folder and the scenarios. None may lie in
// the report folder, which is replaced whole.
void reportFolderHoldsNoInput(const std::string& folder, const scenario::GoldenManifest& manifest) {
  std::vector<output::NamedFile> inputs = {
      {"the references", manifest.references.empty() ? fs::path(".") : manifest.references}};
  for (const auto* entries : {&manifest.frames, &manifest.states}) {
    for (const scenario::GoldenEntry& e : *entries) inputs.push_back({"the scenario", e.scenario});
  }
  output::requireDistinctFiles({reportFolder(folder)}, inputs);
}

// The folder the report folder goes in, made when it is not there (a build tree's golden/).
void makeParent(const fs::path& folder) {
  const fs::path parent = fs::absolute(folder).parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", parent.string(), ec.message()));
}

// Moves the staged report into place: the earlier one out of the way first, then its files removed
// (`earlier`, from checkReportFolder), one by one through its folder's descriptor. Whatever else
// appeared there meanwhile is left, in FOLDER.previous-PID, and said so.
void publish(output::StagingDirectory& staged, const fs::path& folder, std::vector<std::string> earlier) {
  std::error_code ec;
  fs::path previous;
  if (fs::exists(fs::symlink_status(folder, ec))) {
    previous = folder;
    previous += fmt::format(".previous-{}", ::getpid());
    fs::rename(folder, previous, ec);
    if (ec) throw output::OutputError(fmt::format("cannot replace {}: {}", folder.string(), ec.message()));
  }
  fs::rename(staged.path(), folder, ec);
  if (ec) {
    if (!previous.empty()) fs::rename(previous, folder);
    throw output::OutputError(fmt::format("cannot write {}: {}", folder.string(), ec.message()));
  }
  if (previous.empty()) return;
  // Deepest first: a folder's files before the folder.
  std::sort(earlier.begin(), earlier.end(), [](const std::string& a, const std::string& b) { return a > b; });
  try {
    const output::ConfinedFolder old(previous);
    for (const std::string& entry : earlier) old.remove(entry);
  } catch (const std::exception&) {
    // Left below, said so.
  }
  if (!fs::remove(previous, ec)) {
    fmt::print(stderr, "note: left {}: it holds files that were not part of the earlier report\n",
               output::printableText(previous.string()));
  }
}

// One line of what a command prints, with the control characters of names and messages from files
// escaped (output/printable_text.hpp).
void printLine(const std::string& line) {
  fmt::print("{}\n", output::printableText(line));
}

void printFailures(const golden::GoldenResults& r) {
  for (const golden::FrameResult& f : r.frames) {
    if (f.outcome != golden::Outcome::passed)
      printLine(fmt::format("{} {}: {}", golden::outcomeName(f.outcome), f.name, f.message));
  }
  for (const golden::StateResult& s : r.states) {
    if (s.outcome != golden::Outcome::passed)
      printLine(fmt::format("{} {}: {}", golden::outcomeName(s.outcome), s.name, s.message));
  }
}

// Runs the checks into `folder` with progress on a terminal; the options' errors are bad input.
golden::CheckRun runChecks(const scenario::GoldenManifest& manifest, const fs::path& folder, golden::CheckOptions c,
                           bool quiet) {
  Progress progress(!quiet, "checks");
  c.progress = [&](long done, long total, const std::string& name) { progress.update(done, total, name); };
  try {
    return golden::runCheck(manifest, folder, c);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

int goldenCheck(const GoldenCheckOptions& o) {
  const scenario::GoldenManifest manifest = loadManifest(o.run);
  golden::CheckOptions c = checkOptionsOf(o.run);
  c.shard = shardOf(o.shard);
  c.only = o.only;
  if (!o.raster.empty()) c.overrides.raster = render::rasterFromName(o.raster);
  c.overrides.threshold = o.threshold;
  c.overrides.maxShare = o.maxShare;
  const fs::path folder = o.output;
  golden::requireReferencesInPlace(manifest, false);
  std::vector<std::string> earlier = checkReportFolder(folder, o.run.maxInputMiB);
  reportFolderHoldsNoInput(o.output, manifest);
  makeParent(folder);
  output::StagingDirectory staged(folder);
  const auto start = std::chrono::steady_clock::now();
  golden::CheckRun run = runChecks(manifest, staged.path(), c, o.run.quiet);
  golden::RunFacts& facts = run.results.runs.front();
  facts.manifest = o.run.manifest;
  facts.program = fmt::format("particles {}", PARTICLES_VERSION);
  if (const char* threads = std::getenv("LP_NUM_THREADS")) facts.lpNumThreads = threads;
  facts.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  golden::writeReport(staged.path(), run.results);
  publish(staged, folder, std::move(earlier));
  if (!o.run.quiet) printFailures(run.results);
  printLine(golden::summaryLine(run.results, folder));
  if (run.badReference) return kBadInput;
  return run.results.allPassed() ? kOk : kSimulationFailed;
}

int printUpdate(const golden::UpdateOutcome& u, bool quiet) {
  long created = 0, changed = 0, unchanged = 0;
  for (const golden::ReferenceChange& c : u.changes) {
    switch (c.kind) {
      case golden::ReferenceChange::Kind::created:
        ++created;
        printLine(fmt::format("created {}{}", c.name, c.from.empty() ? "" : " from " + c.from));
        break;
      case golden::ReferenceChange::Kind::changed:
        ++changed;
        printLine(fmt::format("changed {}: {}{}", c.name, c.how, c.from.empty() ? "" : " (from " + c.from + ")"));
        break;
      case golden::ReferenceChange::Kind::unchanged:
        ++unchanged;
        if (!quiet) printLine(fmt::format("unchanged {}", c.name));
        break;
    }
  }
  for (const std::string& note : u.notes) printLine(note);
  for (const golden::Refusal& r : u.refused) printLine(fmt::format("refused {}: {}", r.name, r.why));
  for (const std::string& e : u.errors) printLine(fmt::format("error {}", e));
  printLine(fmt::format("golden update: {} created, {} changed, {} unchanged{}{}", created, changed, unchanged,
                        u.refused.empty() ? "" : fmt::format(", {} refused", u.refused.size()),
                        u.errors.empty() ? "" : fmt::format(", {} could not be made", u.errors.size())));
  return u.refused.empty() && u.errors.empty() ? kOk : kSimulationFailed;
}

int goldenUpdate(const GoldenUpdateOptions& o) {
  const scenario::GoldenManifest manifest = loadManifest(o.run);
  golden::requireReferencesInPlace(manifest, true);
  if (!o.from.empty()) {
    if (o.missing) throw InputError("--missing and --from: --from accepts what the report failed on, missing or not");
    std::vector<fs::path> folders(o.from.begin(), o.from.end());
    try {
      return printUpdate(golden::acceptReferences(manifest, folders, o.names, o.run.maxInputMiB), o.run.quiet);
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
  }
  golden::CheckOptions c = checkOptionsOf(o.run);
  c.only = o.names;
  c.missingOnly = o.missing;
  c.keepAll = true;
  const fs::path references = manifest.references.empty() ? fs::path(".") : manifest.references;
  std::error_code ec;
  fs::create_directories(references, ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", references.string(), ec.message()));
  output::StagingDirectory staged(references / ".golden-update");
  const golden::CheckRun run = runChecks(manifest, staged.path(), c, o.run.quiet);
  return printUpdate(golden::writeRenderedReferences(manifest, staged.path(), run, o.run.maxInputMiB), o.run.quiet);
}

int goldenReport(const GoldenReportOptions& o) {
  const fs::path folder = o.output;
  std::vector<fs::path> inputs(o.folders.begin(), o.folders.end());
  std::vector<std::string> earlier = checkReportFolder(folder, o.maxInputMiB);
  makeParent(folder);
  output::StagingDirectory staged(folder);
  golden::GoldenResults merged;
  try {
    merged = golden::mergeReports(inputs, staged.path(), o.maxInputMiB);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  golden::writeReport(staged.path(), merged);
  publish(staged, folder, std::move(earlier));
  if (!o.quiet) printFailures(merged);
  printLine(golden::summaryLine(merged, folder));
  return merged.allPassed() ? kOk : kSimulationFailed;
}

int goldenCommand(const GoldenOptions& o) {
  if (o.checkCommand && o.checkCommand->parsed()) return goldenCheck(o.check);
  if (o.updateCommand && o.updateCommand->parsed()) return goldenUpdate(o.update);
  return goldenReport(o.report);
}

// The files the command line names: the report folder (replaced whole) and what the command reads
// from it. What the manifest names is checked once it is read (reportFolderHoldsNoInput); `update`
// writes into the references' folder the manifest names, checked there (golden/references.hpp).
CommandFiles goldenFiles(const GoldenOptions& o) {
  if (o.checkCommand && o.checkCommand->parsed()) {
    return {{reportFolder(o.check.output)}, {{"the manifest", o.check.run.manifest}}};
  }
  if (o.updateCommand && o.updateCommand->parsed()) {
    CommandFiles files{{}, {{"the manifest", o.update.run.manifest}}};
    for (const std::string& folder : o.update.from) files.inputs.push_back({"--from", folder});
    return files;
  }
  CommandFiles files{{reportFolder(o.report.output)}, {}};
  for (const std::string& folder : o.report.folders) files.inputs.push_back({"the report folder", folder});
  return files;
}

}  // namespace

const CommandDescriptor<GoldenOptions> kGoldenCommand = {
    .name = "golden",
    .summary = "Golden tests of a manifest's frames and states: check, update references, merge reports",
    .addOptions = addGoldenOptions,
    .run = goldenCommand,
    .files = goldenFiles,
};

}  // namespace particles::app
