#pragma once
// The figure of a `--stats` CSV (docs/physics.md §12): energy over time above, constraint error and
// penetration over time below, the scripted mouse's intervals shaded.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "input/text_file.hpp"
#include "plot/figure.hpp"

namespace particles::plot {

// The columns of a stats CSV, one entry per row. All columns have the same length.
struct StatsTable {
  std::vector<double> t, kinetic, potential, total, constraintError, penetration;
  std::size_t rows() const { return t.size(); }
};

// The exact header line of a stats CSV.
inline constexpr const char* kStatsCsvHeader = "t,kinetic,potential,total,constraint_error,penetration";

// Reads a stats CSV strictly: the header exactly as kStatsCsvHeader, then rows of six finite
// numbers (no spaces, no quotes; "\r\n" line ends accepted; one final newline optional; no blank
// lines). Throws CsvError with the file, line and column of the first problem.
// Files past maxInputMiB are refused as they are read (an endless device such as /dev/zero too).
StatsTable readStatsCsv(const std::filesystem::path& file, std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB);
// The same rules on text in memory; `file` only labels messages.
StatsTable parseStatsCsv(std::string_view text, const std::filesystem::path& file);

// What the CSV does not say, for the figure's title and its shaded intervals (from the scenario).
struct StatsFigureContext {
  std::string scenario;    // its name; empty: unknown
  std::string integrator;  // empty: unknown
  double dt = 0;           // s; 0: unknown
  std::string source;      // the CSV's name, for the title when the scenario is unknown
  // When a scripted mouse holds a point: its spring's energy is part of the total, which jumps
  // where it grabs and lets go. Labelled with the point, e.g. "mouse: torso[2][1]".
  std::vector<Band> mouse;
};

// Panel "energy [J]": kinetic, potential, total against t [s], the mouse's intervals shaded.
// Then "constraint error [m]" on a log axis, and "penetration [m]" (log when its positive values
// span at least two decades, else linear), each on its own panel; a column that is 0 throughout
// gets no panel but a line in the caption saying so. The title names the scenario, integrator and
// dt when known. Throws FigureError if the columns differ in length.
Figure statsFigure(const StatsTable& table, const StatsFigureContext& context = {});

}  // namespace particles::plot
