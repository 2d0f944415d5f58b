#pragma once
// The figure of a `--stats` CSV (docs/physics.md §12): energy over time above, constraint error and
// penetration over time below.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

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
StatsTable readStatsCsv(const std::filesystem::path& file, std::uintmax_t maxInputMiB = 64);
// The same rules on text in memory; `file` only labels messages.
StatsTable parseStatsCsv(std::string_view text, const std::filesystem::path& file);

// Top panel "energy [J]": kinetic, potential, total against t [s]. Bottom panel "error [m]":
// constraint error and penetration, on a log axis when their positive values span at least two
// decades (zeros, for "no contact", are then left out of the line), else linear.
// Throws FigureError if the columns differ in length.
Figure statsFigure(const StatsTable& table);

}  // namespace particles::plot
