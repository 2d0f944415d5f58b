// `particles plot`: the figure of a --stats CSV (energy and constraint error over time).
#include <fmt/format.h>

#include "app/commands.hpp"
#include "plot/stats_figure.hpp"

namespace particles::app {

int plotCommand(const PlotOptions& options) {
  const plot::StatsTable table = plot::readStatsCsv(options.input, options.maxInputMiB);  // throws CsvError (exit 2)
  plot::Figure figure = plot::statsFigure(table);
  if (!options.title.empty()) figure.title = options.title;
  if (options.width > 0) figure.widthPx = options.width;
  if (options.height > 0) figure.heightPx = options.height;
  plot::writeFigure(figure, options.output);  // throws FigureError (exit 3)
  if (!options.quiet) fmt::print("{}\n", options.output);
  return kOk;
}

}  // namespace particles::app
