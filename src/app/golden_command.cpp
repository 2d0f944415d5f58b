// `particles golden`: see golden_command.hpp.
#include "app/golden_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "app/cli_support.hpp"
#include "app/gl_options.hpp"
#include "golden/check.hpp"
#include "golden/check_report.hpp"
#include "golden/references.hpp"
#include "golden/results.hpp"
#include "output/distinct_files.hpp"
#include "output/output_error.hpp"
#include "input/printable_text.hpp"
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
      ->check(CLI::Range(1, golden::kMaxJobs));
  command
      .add_option("--gl", o.gl,
                  fmt::format("GL backend of the GL raster paths (the cpu path uses none): auto (EGL, else OSMesa), "
                              "egl or osmesa (default: ${}, else auto)",
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
  // Not update's: the references are llvmpipe's (golden/README.md, "On a GPU").
  check->add_flag("--gpu", o.check.run.gpu,
                  "Draw on a GPU through EGL instead of llvmpipe on the CPU: a check of the GPU's raster path "
                  "(golden/README.md, \"On a GPU\")");
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
  return golden::loadManifest(o.manifest, o.maxInputMiB);
}

golden::CheckOptions checkOptionsOf(const GoldenRunOptions& o) {
  golden::CheckOptions c;
  c.manifestGiven = o.manifest;
  c.gl = glRequestOf(o.gl, o.gpu);
  c.jobs = o.jobs > 0 ? o.jobs : golden::defaultJobs();
  c.maxInputMiB = o.maxInputMiB;
  c.program = programPath();
  return c;
}


// The report folder as one of the command's files: an output replaced whole, so that no input may
// lie beneath it (output/distinct_files.hpp).
output::NamedFile reportFolder(const std::string& folder) {
  return {"-o", folder, true};
}

// One line of what a command prints, with the control characters of names and messages from files
// escaped (output/printable_text.hpp).
void printLine(const std::string& line) {
  fmt::print("{}\n", input::printableText(line));
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
  golden::ReportRequest request;
  request.manifestFile = o.run.manifest;
  request.folder = o.output;
  request.program = fmt::format("particles {}", PARTICLES_VERSION);
  request.check = checkOptionsOf(o.run);
  request.check.only = o.only;
  if (!o.raster.empty()) request.check.overrides.raster = render::rasterFromName(o.raster);
  request.check.overrides.threshold = o.threshold;
  request.check.overrides.maxShare = o.maxShare;
  Progress progress(!o.run.quiet, "checks");
  request.check.progress = [&](long done, long total, const std::string& name) { progress.update(done, total, name); };
  golden::CheckRun run;
  try {
    request.check.shard = golden::shardFromText(o.shard, "--shard");
    run = golden::checkIntoReport(manifest, request);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  if (!o.run.quiet) printFailures(run.results);
  printLine(golden::summaryLine(run.results, request.folder));
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
  std::vector<fs::path> inputs(o.folders.begin(), o.folders.end());
  fs::path folder;
  try {
    folder = golden::reportFolderPath(o.output, "-o");
    golden::checkReportFolder(folder, o.maxInputMiB, "-o");
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  golden::makeParent(folder);
  output::StagingDirectory staged(folder);
  golden::GoldenResults merged;
  try {
    merged = golden::mergeReports(inputs, staged.path(), o.maxInputMiB);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  golden::writeReport(staged.path(), merged);
  golden::publish(staged, folder, o.maxInputMiB, "-o");
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
