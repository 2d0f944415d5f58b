// `particles plot`: the figure of a --stats CSV (energy and constraint error over time).
#include <fmt/format.h>

#include "app/commands.hpp"
#include "plot/errors.hpp"
#include "plot/stats_figure.hpp"

namespace particles::app {

int plotCommand(const PlotOptions& options) {
  try {
    const plot::StatsTable table = plot::readStatsCsv(options.input);
    plot::Figure figure = plot::statsFigure(table);
    if (!options.title.empty()) figure.title = options.title;
    if (options.width > 0) figure.widthPx = options.width;
    if (options.height > 0) figure.heightPx = options.height;
    plot::writeFigure(figure, options.output);
  } catch (const plot::CsvError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kBadInput;
  } catch (const plot::FigureError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kOutputFailed;
  }
  if (!options.quiet) fmt::print("{}\n", options.output);
  return kOk;
}

}  // namespace particles::app
