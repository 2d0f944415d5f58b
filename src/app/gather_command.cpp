// `particles gather`: see gather_command.hpp. The figure has one panel per quantity and one line
// per integrator or scenario.
#include "app/gather_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "app/cli_support.hpp"
#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "app/job_table.hpp"
#include "input/text_file.hpp"
#include "output/confined_folder.hpp"
#include "output/csv_writer.hpp"
#include "output/distinct_files.hpp"
#include "output/output_file.hpp"
#include "plot/figure.hpp"

namespace particles::app {

namespace {

struct GatheredRow {
  std::vector<std::string> job;  // the jobs.csv row
  std::optional<JobRecord> record;
  std::string unreadable;  // why the record at the job's path could not be read
};

// Headline numbers that describe the job rather than its result: left out of the figure.
bool inFigure(const std::string& key) {
  return key != "steps" && key != "initial_energy" && key != "frames" && key != "video_seconds";
}

std::optional<double> numberOf(const std::string& text) {
  if (text.empty()) return std::nullopt;
  size_t used = 0;
  try {
    const double x = std::stod(text, &used);
    if (used == text.size() && std::isfinite(x)) return x;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// The quantity's unit, from how the jobs name it.
std::string axisLabel(const std::string& key) {
  auto endsWith = [&](std::string_view tail) {
    return key.size() >= tail.size() && key.compare(key.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (endsWith("_dt") || endsWith("seconds")) return key + " [s]";
  if (endsWith("energy")) return key + " [J]";
  if (endsWith("error") || endsWith("penetration")) return key + " [m]";
  return key;
}

plot::AxisScale scaleFor(const std::vector<double>& values) {
  double lo = INFINITY, hi = 0;
  for (double v : values) {
    if (!(v > 0)) return plot::AxisScale::Linear;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return !values.empty() && hi / lo >= 20 ? plot::AxisScale::Log : plot::AxisScale::Linear;
}

void addGatherOptions(CLI::App& command, GatherOptions& o) {
  command.add_option("outdir", o.outDir, "A sweep's output folder (with jobs.csv)")->required();
  command.add_option("-o,--output", o.output, "The CSV (default OUTDIR/results.csv)");
  command.add_option(
      "--plot", o.plot,
      "The figure, .svg, .pdf or .png (default OUTDIR/results.svg when one parameter varies; none: no figure)");
  command.add_flag("-q,--quiet", o.quiet, "Print nothing on success");
  addMaxInputOption(command, o.maxInputMiB, "a job table or record");
  command.footer(
      "Columns: index, stage, scenario, the parameters, segment, status (ok, failed or not run), exit,\n"
      "seconds, then the numbers the jobs report (run: final_energy, worst_constraint_error,\n"
      "worst_penetration, wall_seconds, …; stability: max_stable_dt.INTEGRATOR, max_smooth_dt.…; render:\n"
      "frames, wall_seconds), then message.\n"
      "Example:\n"
      "  particles gather cloth-sweep --plot cloth-sweep.png\n");
}

// The CSV, and the figure unless --plot none: their defaults lie in the sweep's folder.
std::filesystem::path resultsPath(const GatherOptions& o) {
  return o.output.empty() ? std::filesystem::path(o.outDir) / "results.csv" : std::filesystem::path(o.output);
}
std::filesystem::path figurePath(const GatherOptions& o) {
  if (o.plot == "none") return {};
  return o.plot.empty() ? std::filesystem::path(o.outDir) / "results.svg" : std::filesystem::path(o.plot);
}

// The files the command line names: the outputs, and the job table they may not be. The records
// the table lists are checked against the outputs once it is read (requireRecordsDistinct).
CommandFiles gatherFiles(const GatherOptions& o) {
  return {{{"-o", resultsPath(o)}, {"--plot", figurePath(o)}},
          {{"the job table", std::filesystem::path(o.outDir) / "jobs.csv"}}};
}

std::filesystem::path recordPath(const std::filesystem::path& dir, const JobTable& table,
                                 const std::vector<std::string>& job) {
  return dir / job[table.dirColumn()] / "record.txt";
}

// The outputs are never a record (output/distinct_files.hpp): checked before anything is read
// further or written.
void requireRecordsDistinct(const JobTable& table, const GatherOptions& o) {
  std::vector<output::NamedFile> records;
  for (const auto& job : table.rows) records.push_back({"the record", recordPath(o.outDir, table, job)});
  output::requireDistinctFiles(gatherFiles(o).outputs, records);
}

// The jobs' records, as far as they can be read, and the headline keys they report.
struct Gathered {
  std::vector<GatheredRow> rows;
  std::vector<std::string> keys;                     // headline keys in order of first appearance
  std::map<std::string, size_t, std::less<>> keyAt;  // … and where, so that many keys stay linear
  size_t unreadable = 0;
};

Gathered readRecords(const JobTable& table, const GatherOptions& o) {
  Gathered gathered;
  for (const auto& job : table.rows) {
    GatheredRow row{job, std::nullopt, {}};
    const std::filesystem::path file = recordPath(o.outDir, table, job);
    try {
      row.record = readJobRecord(file, o.maxInputMiB);
    } catch (const input::ReadError& e) {
      row.unreadable = fmt::format("{}: {}", file.string(), e.what());
      ++gathered.unreadable;
      if (!o.quiet) fmt::print(stderr, "warning: {}\n", row.unreadable);
    }
    if (row.record) {
      for (const auto& [k, v] : row.record->headline) {
        if (gathered.keyAt.emplace(k, gathered.keys.size()).second) gathered.keys.push_back(k);
      }
    }
    gathered.rows.push_back(std::move(row));
  }
  return gathered;
}

struct Tally {
  size_t ok = 0, failed = 0, notRun = 0;
};

// A job's row of results.csv: its jobs.csv row up to the segment, its outcome, its headline numbers
// in the columns of `gathered.keys`, its message.
std::vector<std::string> resultsRow(const GatheredRow& row, const Gathered& gathered, size_t segmentColumn,
                                    Tally& tally) {
  std::vector<std::string> fields(row.job.begin(), row.job.begin() + long(segmentColumn) + 1);
  if (!row.record) {
    ++tally.notRun;
    fields.insert(fields.end(), {row.unreadable.empty() ? "not run" : "unreadable", "", ""});
    fields.resize(fields.size() + gathered.keys.size());
    fields.push_back(row.unreadable);
    return fields;
  }
  const JobRecord& rec = *row.record;
  (rec.exitCode == 0 ? tally.ok : tally.failed)++;
  fields.insert(fields.end(), {rec.exitCode == 0 ? "ok" : "failed", std::to_string(rec.exitCode),
                               fmt::format("{:.3f}", rec.seconds)});
  const size_t first = fields.size();
  fields.resize(first + gathered.keys.size());
  for (const auto& [k, v] : rec.headline) fields[first + gathered.keyAt.find(k)->second] = fmt::format("{}", v);
  fields.push_back(rec.message);
  return fields;
}

// results.csv: a row per job.
Tally writeResultsTable(const Gathered& gathered, const JobTable& table, const GatherOptions& o) {
  // The default results.csv is the sweep folder's own file, written beneath it (output/confined_folder.hpp); a
  // file that -o names is the user's choice.
  std::optional<output::ConfinedFolder> sweepFolder;
  if (o.output.empty()) sweepFolder.emplace(o.outDir);
  output::OutputFile csv =
      sweepFolder ? output::OutputFile(*sweepFolder, "results.csv") : output::OutputFile(resultsPath(o));
  std::vector<std::string> head = {"index", "stage", "scenario"};
  head.insert(head.end(), table.parameters.begin(), table.parameters.end());
  head.insert(head.end(), {"segment", "status", "exit", "seconds"});
  head.insert(head.end(), gathered.keys.begin(), gathered.keys.end());
  head.push_back("message");
  csv.write(output::csvRow(head));
  Tally tally;
  for (const GatheredRow& row : gathered.rows) {
    csv.write(output::csvRow(resultsRow(row, gathered, table.segmentColumn(), tally)));
  }
  csv.commit();
  return tally;
}

// The figure's lines: per panel (a quantity, the key up to its first '.'), a series per integrator
// and scenario, each a point per job, in the order of first appearance.
struct FigureSeries {
  std::vector<std::string> panels;
  std::map<std::string, std::map<std::string, plot::Series>> series;  // panel → series name → series
  std::map<std::string, std::vector<std::string>> order;              // panel → series names
  std::vector<double> xs;
};

FigureSeries figureSeries(const std::vector<const GatheredRow*>& results, size_t xColumn) {
  std::set<std::string> scenarios;
  for (const GatheredRow* row : results) scenarios.insert(row->job[JobTable::kScenario]);
  FigureSeries f;
  for (const GatheredRow* row : results) {
    const double x = *numberOf(row->job[xColumn]);
    f.xs.push_back(x);
    for (const auto& [key, value] : row->record->headline) {
      if (!inFigure(key)) continue;
      const size_t dot = key.find('.');
      const std::string panel = key.substr(0, dot);
      std::string name = dot == std::string::npos ? std::string() : key.substr(dot + 1);
      const std::string& scenario = row->job[JobTable::kScenario];
      if (scenarios.size() > 1) name = name.empty() ? scenario : scenario + ": " + name;
      if (std::find(f.panels.begin(), f.panels.end(), panel) == f.panels.end()) f.panels.push_back(panel);
      auto& s = f.series[panel][name];
      if (s.x.empty()) {
        s.name = name;
        s.markers = true;
        f.order[panel].push_back(name);
      }
      s.x.push_back(x);
      s.y.push_back(value);
    }
  }
  return f;
}

// One panel of the figure, each line's points in order of x, so that it goes left to right
// whatever the job order.
plot::Panel figurePanel(const std::string& name, const FigureSeries& f) {
  plot::Panel panel;
  panel.yLabel = axisLabel(name);
  std::vector<double> ys;
  for (const std::string& s : f.order.at(name)) {
    const plot::Series& line = f.series.at(name).at(s);
    std::vector<size_t> order(line.x.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return line.x[a] < line.x[b]; });
    plot::Series sorted{line.name, {}, {}, true};
    for (size_t i : order) {
      sorted.x.push_back(line.x[i]);
      sorted.y.push_back(line.y[i]);
    }
    ys.insert(ys.end(), sorted.y.begin(), sorted.y.end());
    panel.series.push_back(std::move(sorted));
  }
  panel.yScale = scaleFor(ys);
  return panel;
}

// The parameters that take more than one value among `results`.
std::vector<size_t> varyingParameters(const std::vector<const GatheredRow*>& results, const JobTable& table) {
  std::vector<size_t> varying;
  for (size_t p = 0; p < table.parameters.size(); ++p) {
    std::set<std::string> seen;
    for (const GatheredRow* row : results) seen.insert(row->job[table.parameterColumn(p)]);
    if (seen.size() > 1) varying.push_back(p);
  }
  return varying;
}

// The figure: the final stage's rows that succeeded, against the one parameter that varies, at
// most four panels. Returns the line gather prints about it: where it is, or why there is none.
std::string writeResultsFigure(const Gathered& gathered, const JobTable& table, const GatherOptions& o) {
  if (o.plot == "none") return "no figure (--plot none)";
  std::vector<const GatheredRow*> results;
  for (const GatheredRow& row : gathered.rows) {
    if (row.job[JobTable::kStage] != "segment" && row.record && row.record->exitCode == 0) results.push_back(&row);
  }
  const std::vector<size_t> varying = varyingParameters(results, table);
  if (varying.size() != 1) {
    return varying.empty() ? "no figure: no parameter varies"
                           : fmt::format("no figure: {} parameters vary (a figure needs one)", varying.size());
  }
  const std::string& parameter = table.parameters[varying.front()];
  const size_t xColumn = table.parameterColumn(varying.front());
  for (const GatheredRow* row : results) {
    if (!numberOf(row->job[xColumn])) return fmt::format("no figure: {} is not a number", parameter);
  }
  FigureSeries series = figureSeries(results, xColumn);
  if (series.panels.size() > 4) series.panels.resize(4);
  plot::LineChart chart;
  chart.xLabel = parameter;
  chart.xScale = scaleFor(series.xs);
  for (const std::string& name : series.panels) chart.panels.push_back(figurePanel(name, series));
  plot::Figure figure;
  figure.title = fmt::format("{} against {}",
                             std::filesystem::absolute(o.outDir).lexically_normal().filename().string(), parameter);
  figure.heightPx = int(std::max<size_t>(1, chart.panels.size())) * 300 + 140;
  figure.chart = std::move(chart);
  const std::filesystem::path path = figurePath(o);
  plot::writeFigure(figure, path);
  return "figure: " + path.string();
}

}  // namespace

int gatherCommand(const GatherOptions& o) {
  if (!o.plot.empty() && o.plot != "none") requireFigurePath("--plot", o.plot);
  const JobTable table = readJobTable(o.outDir, o.maxInputMiB);
  requireRecordsDistinct(table, o);
  const Gathered gathered = readRecords(table, o);
  const Tally tally = writeResultsTable(gathered, table, o);
  const std::string figure = writeResultsFigure(gathered, table, o);
  if (!o.quiet) {
    fmt::print("{}: {} jobs: {} ok, {} failed, {} not run{} → {}\n", o.outDir, gathered.rows.size(), tally.ok,
               tally.failed, tally.notRun - gathered.unreadable,
               gathered.unreadable ? fmt::format(", {} with unreadable records", gathered.unreadable) : "",
               resultsPath(o).string());
    fmt::print("{}\n", figure);
  }
  return kOk;
}

const CommandDescriptor<GatherOptions> kGatherCommand = {
    .name = "gather",
    .summary = "Collect a sweep's results: one CSV row per job, and a figure",
    .addOptions = addGatherOptions,
    .run = gatherCommand,
    .files = gatherFiles,
};

}  // namespace particles::app
