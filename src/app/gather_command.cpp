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

}  // namespace

int gatherCommand(const GatherOptions& o) {
  if (!o.plot.empty() && o.plot != "none") requireFigurePath("--plot", o.plot);
  const std::filesystem::path dir = o.outDir;
  const JobTable table = readJobTable(dir, o.maxInputMiB);
  const std::vector<std::string>& parameters = table.parameters;
  const size_t stageCol = JobTable::kStage, scenarioCol = JobTable::kScenario, segmentCol = table.segmentColumn();

  // The outputs are never the table or a record (output/distinct_files.hpp): checked before
  // anything is read further or written.
  const std::filesystem::path csvPath = o.output.empty() ? dir / "results.csv" : std::filesystem::path(o.output);
  const std::filesystem::path plotPath = o.plot == "none" ? std::filesystem::path()
                                         : o.plot.empty() ? dir / "results.svg"
                                                          : std::filesystem::path(o.plot);
  {
    std::vector<output::NamedFile> inputs = {{"the job table", dir / "jobs.csv"}};
    for (const auto& job : table.rows) inputs.push_back({"the record", dir / job[table.dirColumn()] / "record.txt"});
    output::requireDistinctFiles({{"-o", csvPath}, {"--plot", plotPath}}, inputs);
  }

  std::vector<GatheredRow> rows;
  std::vector<std::string> keys;                     // headline keys in order of first appearance
  std::map<std::string, size_t, std::less<>> keyAt;  // … and where, so that many keys stay linear
  size_t unreadable = 0;
  for (const auto& job : table.rows) {
    GatheredRow row{job, std::nullopt, {}};
    const std::filesystem::path file = dir / job[table.dirColumn()] / "record.txt";
    try {
      row.record = readJobRecord(file, o.maxInputMiB);
    } catch (const input::ReadError& e) {
      row.unreadable = fmt::format("{}: {}", file.string(), e.what());
      ++unreadable;
      if (!o.quiet) fmt::print(stderr, "warning: {}\n", row.unreadable);
    }
    if (row.record) {
      for (const auto& [k, v] : row.record->headline) {
        if (keyAt.emplace(k, keys.size()).second) keys.push_back(k);
      }
    }
    rows.push_back(std::move(row));
  }

  // results.csv
  size_t ok = 0, failed = 0, notRun = 0;
  {
    // The default results.csv is the sweep folder's own file, written beneath it (issue 39); a
    // file that -o names is the user's choice.
    std::optional<output::ConfinedFolder> sweepFolder;
    if (o.output.empty()) sweepFolder.emplace(dir);
    output::OutputFile csv =
        sweepFolder ? output::OutputFile(*sweepFolder, "results.csv") : output::OutputFile(csvPath);
    std::vector<std::string> head = {"index", "stage", "scenario"};
    head.insert(head.end(), parameters.begin(), parameters.end());
    head.insert(head.end(), {"segment", "status", "exit", "seconds"});
    head.insert(head.end(), keys.begin(), keys.end());
    head.push_back("message");
    csv.write(output::csvRow(head));
    for (const GatheredRow& row : rows) {
      std::vector<std::string> fields(row.job.begin(), row.job.begin() + long(segmentCol) + 1);
      if (!row.record) {
        ++notRun;
        fields.insert(fields.end(), {row.unreadable.empty() ? "not run" : "unreadable", "", ""});
        fields.resize(fields.size() + keys.size());
        fields.push_back(row.unreadable);
      } else {
        const JobRecord& rec = *row.record;
        (rec.exitCode == 0 ? ok : failed)++;
        fields.insert(fields.end(), {rec.exitCode == 0 ? "ok" : "failed", std::to_string(rec.exitCode),
                                     fmt::format("{:.3f}", rec.seconds)});
        const size_t first = fields.size();
        fields.resize(first + keys.size());
        for (const auto& [k, v] : rec.headline) fields[first + keyAt.find(k)->second] = fmt::format("{}", v);
        fields.push_back(rec.message);
      }
      csv.write(output::csvRow(fields));
    }
    csv.commit();
  }

  // The figure: the final stage's rows that succeeded, against the one parameter that varies.
  std::vector<const GatheredRow*> results;
  for (const GatheredRow& row : rows) {
    if (row.job[stageCol] != "segment" && row.record && row.record->exitCode == 0) results.push_back(&row);
  }
  std::vector<size_t> varying;
  for (size_t p = 0; p < parameters.size(); ++p) {
    std::set<std::string> seen;
    for (const GatheredRow* row : results) seen.insert(row->job[scenarioCol + 1 + p]);
    if (seen.size() > 1) varying.push_back(p);
  }
  std::string figureNote;
  std::filesystem::path figurePath;
  if (o.plot == "none") {
    figureNote = "no figure (--plot none)";
  } else if (varying.size() != 1) {
    figureNote = varying.empty() ? "no figure: no parameter varies"
                                 : fmt::format("no figure: {} parameters vary (a figure needs one)", varying.size());
  } else {
    const size_t xCol = scenarioCol + 1 + varying.front();
    bool numeric = true;
    for (const GatheredRow* row : results) numeric = numeric && numberOf(row->job[xCol]).has_value();
    if (!numeric) {
      figureNote = fmt::format("no figure: {} is not a number", parameters[varying.front()]);
    } else {
      std::set<std::string> scenarios;
      for (const GatheredRow* row : results) scenarios.insert(row->job[scenarioCol]);
      // Panels: one per quantity (the key up to its first '.'), series per integrator and scenario.
      std::vector<std::string> panelNames;
      std::map<std::string, std::map<std::string, plot::Series>> series;  // panel → series name → series
      std::map<std::string, std::vector<std::string>> seriesOrder;
      std::vector<double> xs;
      for (const GatheredRow* row : results) {
        const double x = *numberOf(row->job[xCol]);
        xs.push_back(x);
        for (const auto& [key, value] : row->record->headline) {
          if (!inFigure(key)) continue;
          const size_t dot = key.find('.');
          const std::string panel = key.substr(0, dot);
          std::string name = dot == std::string::npos ? std::string() : key.substr(dot + 1);
          if (scenarios.size() > 1) name = name.empty() ? row->job[scenarioCol] : row->job[scenarioCol] + ": " + name;
          if (std::find(panelNames.begin(), panelNames.end(), panel) == panelNames.end()) panelNames.push_back(panel);
          auto& s = series[panel][name];
          if (s.x.empty()) {
            s.name = name;
            s.markers = true;
            seriesOrder[panel].push_back(name);
          }
          s.x.push_back(x);
          s.y.push_back(value);
        }
      }
      if (panelNames.size() > 4) panelNames.resize(4);
      plot::LineChart chart;
      chart.xLabel = parameters[varying.front()];
      chart.xScale = scaleFor(xs);
      for (const std::string& name : panelNames) {
        plot::Panel panel;
        panel.yLabel = axisLabel(name);
        std::vector<double> ys;
        for (const std::string& s : seriesOrder[name]) {
          plot::Series line = series[name][s];
          // Points in order of x, so the line goes left to right whatever the job order.
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
        chart.panels.push_back(std::move(panel));
      }
      plot::Figure figure;
      figure.title = fmt::format("{} against {}", std::filesystem::absolute(dir).lexically_normal().filename().string(),
                                 parameters[varying.front()]);
      figure.heightPx = int(std::max<size_t>(1, chart.panels.size())) * 300 + 140;
      figure.chart = std::move(chart);
      figurePath = plotPath;
      plot::writeFigure(figure, figurePath);
    }
  }
  if (!o.quiet) {
    fmt::print("{}: {} jobs: {} ok, {} failed, {} not run{} → {}\n", o.outDir, rows.size(), ok, failed,
               notRun - unreadable, unreadable ? fmt::format(", {} with unreadable records", unreadable) : "",
               csvPath.string());
    fmt::print("{}\n", figurePath.empty() ? figureNote : "figure: " + figurePath.string());
  }
  return kOk;
}

const CommandDescriptor<GatherOptions> kGatherCommand = {
    .name = "gather",
    .summary = "Collect a sweep's results: one CSV row per job, and a figure",
    .addOptions = addGatherOptions,
    .run = gatherCommand,
};

}  // namespace particles::app
