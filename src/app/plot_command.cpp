// `particles plot`: the figure of a --stats CSV (energy and constraint error over time). Given the
// scenario that was run, the title names it, its integrator and dt, and the intervals when a
// scripted mouse holds a point are shaded (they explain the jumps in the total energy).
#include "app/plot_command.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "app/cli_support.hpp"
#include "core/forces/mouse_spring_force.hpp"
#include "core/integrators.hpp"
#include "plot/stats_figure.hpp"

namespace particles::app {

namespace {

plot::StatsFigureContext contextOf(const PlotOptions& options) {
  plot::StatsFigureContext context;
  context.source = std::filesystem::path(options.input).filename().string();
  if (options.scenario.empty()) return context;
  CommonOptions common;
  common.scenario = options.scenario;
  common.integrator = options.integrator;
  common.dt = options.dt;
  common.sets = options.sets;
  const scenario::Scenario s = loadScenario(common);  // throws ScenarioError (exit 2)
  context.scenario = s.name;
  context.integrator = std::string(integratorName(s.simulation.integrator));
  context.dt = s.simulation.dt;
  for (const auto& force : s.system.forces()) {
    const auto* mouse = dynamic_cast<const MouseSpringForce*>(force.get());
    if (!mouse) continue;
    const MouseScript& script = mouse->script();
    const int point = script.grab.point(s.system.model().layout);
    context.mouse.push_back({script.from, script.to, "mouse: " + scenario::pointName(s.system.model(), point)});
  }
  return context;
}

int plotCommand(const PlotOptions& options) {
  requireFigurePath("-o", options.output);
  const plot::StatsTable table = plot::readStatsCsv(options.input, options.maxInputMiB);  // throws CsvError (exit 2)
  plot::Figure figure = plot::statsFigure(table, contextOf(options));
  if (!options.title.empty()) figure.title = options.title;
  if (options.width > 0) figure.widthPx = options.width;
  if (options.height > 0) figure.heightPx = options.height;
  plot::writeFigure(figure, options.output);  // throws FigureError (exit 3)
  if (!options.quiet) fmt::print("{}\n", options.output);
  return kOk;
}

void addPlotOptions(CLI::App& command, PlotOptions& plot) {
  command.add_option("stats", plot.input, "A CSV written by run/render --stats")->required();
  command.add_option("-o,--output", plot.output, "The figure: .svg (vector), .pdf (vector, for LaTeX) or .png")
      ->required();
  command.add_option("--title", plot.title, "Title above the chart (default: scenario, integrator and dt)");
  auto* plotScenario = command.add_option(
      "--scenario", plot.scenario,
      "The scenario that was run: names it, its integrator and dt in the title and shades the mouse's intervals");
  command.add_option("--integrator", plot.integrator, "The run's --integrator, if it had one")->needs(plotScenario);
  command.add_option("--dt", plot.dt, "The run's --dt, if it had one")->needs(plotScenario);
  command.add_option("--set", plot.sets, "The run's --set overrides, if it had any (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false)
      ->needs(plotScenario);
  command.add_option("--width", plot.width, fmt::format("Width in px (default {})", plot::Figure{}.widthPx))
      ->check(CLI::Range(200, 10000));
  command.add_option("--height", plot.height, fmt::format("Height in px (default {})", plot::Figure{}.heightPx))
      ->check(CLI::Range(150, 10000));
  command.add_flag("-q,--quiet", plot.quiet, "Print nothing on success");
  addMaxInputOption(command, plot.maxInputMiB, "a CSV file");
  command.footer(
      "Examples:\n"
      "  particles run scenarios/cloth.yaml --stats cloth.csv && particles plot cloth.csv -o energy.svg\n"
      "  particles plot cloth.csv -o energy.png --title 'Cloth, RK4, dt = 0.01 s'\n"
      "  particles run scenarios/soft_body.yaml --stats man.csv --dt 0.1\n"
      "  particles plot man.csv --scenario scenarios/soft_body.yaml --dt 0.1 -o man.pdf   # mouse intervals shaded\n");
}

CommandFiles plotFiles(const PlotOptions& plot) {
  return {{{"-o", plot.output}}, {{"the CSV", plot.input}, {"--scenario", plot.scenario}}};
}

}  // namespace

const CommandDescriptor<PlotOptions> kPlotCommand = {
    .name = "plot",
    .summary = "Draw the figure of a --stats CSV: energy and constraint error over time",
    .addOptions = addPlotOptions,
    .run = plotCommand,
    .files = plotFiles,
};

}  // namespace particles::app
