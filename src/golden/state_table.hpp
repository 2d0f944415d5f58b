#pragma once
// A state golden's file (golden/README.md, "States"): the state of every particle and rigid body at
// the manifest's times, one row each, in the columns of `run --trace` (docs/physics.md §12):
//
//   t,name,x,y,vx,vy,angle,omega
//   2.5,cloth[0][0],-1.2,0.9,0,0,0,0
//
// t is the time as the manifest writes it, names as the trace spells them (a name holding a comma,
// a quote or a line break is quoted as RFC 4180 says), numbers in shortest round-trip form, angle
// and omega 0 for particles. One small text file per entry, so that a review's diff shows which
// particle moved. Compared value by value with absolute tolerances.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/system.hpp"
#include "golden/results.hpp"

namespace particles::golden {

inline constexpr std::string_view kStateHeader = "t,name,x,y,vx,vy,angle,omega";
// The quantities of a row, in column order after t and name.
inline constexpr std::string_view kStateQuantities[6] = {"x", "y", "vx", "vy", "angle", "omega"};

struct StateRow {
  std::string time;  // as the manifest writes it
  std::string name;
  double values[6] = {};  // x, y, vx, vy, angle, omega
};

// The rows of `system`'s state now, at the manifest's time `timeText`.
std::vector<StateRow> stateRows(const System& system, const std::string& timeText);

// The file's text: the header, then a line per row.
std::string stateText(const std::vector<StateRow>& rows);

// Reads a state file; throws std::invalid_argument naming `file`, the line and what is wrong (a
// header that is not kStateHeader, text that is not CSV (input/csv_reader.hpp), a row without 8 fields, a
// value that is not a number, a NUL byte).
std::vector<StateRow> parseStateText(std::string_view text, const std::string& file);

// Absolute tolerances: position (x, y), velocity (vx, vy), angle, omega.
struct StateTolerance {
  double position = 0.0, velocity = 0.0, angle = 0.0, omega = 0.0;
  double of(size_t quantity) const;  // by index into kStateQuantities
};

struct StateComparison {
  bool passed = true;
  std::string mismatch;  // rows that do not pair up (another time or point): why; values are not compared then
  std::optional<StateDeviation> firstBeyond;  // the first value beyond its tolerance, in file order
  std::optional<StateDeviation> largest;      // the largest |difference| / tolerance (|difference| where it is 0)
  long values = 0;                            // values compared
};

// Compares row by row: the rows must name the same times and points in the same order. A value is
// beyond its tolerance when |actual − expected| > tolerance, or when exactly one of them is NaN.
StateComparison compareStates(const std::vector<StateRow>& expected, const std::vector<StateRow>& actual,
                              const StateTolerance& tolerance);

}  // namespace particles::golden
