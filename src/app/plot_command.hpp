#pragma once
// `particles plot STATS.csv -o OUT` (docs/physics.md §12): the figure of a --stats CSV, energy and
// constraint error over time, as SVG, PDF or PNG.
//
// Exit codes: 0 written; 2 bad input (the CSV, the scenario, a figure path that is not .svg, .png
// or .pdf); 3 the figure could not be written.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/command.hpp"
#include "input/text_file.hpp"

namespace particles::app {

struct PlotOptions {
  std::string input;   // a --stats CSV
  std::string output;  // .svg | .png | .pdf
  std::string title;
  // The run's scenario and its overrides, for the title and the mouse's intervals; empty: none.
  std::string scenario;
  std::optional<std::string> integrator, dt;
  std::vector<std::string> sets;
  int width = 0, height = 0;        // px; 0: the figure's default
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;  // --max-input
  bool quiet = false;
};

extern const CommandDescriptor<PlotOptions> kPlotCommand;

}  // namespace particles::app
