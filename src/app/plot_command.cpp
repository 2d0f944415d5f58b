// `particles plot`: the figure of a --stats CSV (energy and constraint error over time). Given the
// scenario that was run, the title names it, its integrator and dt, and the intervals when a
// scripted mouse holds a point are shaded (they explain the jumps in the total energy).
#include <fmt/format.h>

#include <filesystem>

#include "app/cli_support.hpp"
#include "app/commands.hpp"
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

}  // namespace

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

}  // namespace particles::app
