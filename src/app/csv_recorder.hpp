#pragma once
// The --stats and --trace CSV files of `run` and `render` (docs/physics.md §12): one row (stats) or one row
// per traced object (trace) each time record() is called, numbers in shortest round-trip form.
// The time column is the state's time as a reader expects it: a tick i / fps exactly when the
// state is at one (0.45, not the 0.44999999999999996 that 3 × 0.15 computes), otherwise the time to
// 12 significant digits, which drops the rounding of k · dt (a dt given in decimals).
// Both files are written through output::OutputFile and appear only on commit().

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "output/output_file.hpp"
#include "core/system.hpp"

namespace particles::app {

class CsvRecorder {
 public:
  // Throws InputError for a --trace-only name nothing in the system has; OutputError when a file
  // cannot be created. That the two are not one file is the program's check, before the command
  // runs (Cli::dispatch, output/distinct_files.hpp).
  // fps: the rate of the ticks (the scenario's, or render --fps).
  static std::unique_ptr<CsvRecorder> open(const System& system, double fps, const std::string& statsPath,
                                         const std::string& tracePath, const std::vector<std::string>& traceOnly);

  void record(const System& system);
  // The time column's value for a state at time t (see the top of this file).
  static double nominalTime(double t, double fps);
  void commit();  // throws OutputError
  bool writesStats() const { return stats_.has_value(); }
  bool writesTrace() const { return trace_.has_value(); }

 private:
  CsvRecorder() = default;
  std::optional<output::OutputFile> stats_, trace_;
  std::vector<int> points_;
  std::vector<std::string> names_;
  double fps_ = 0;
};

}  // namespace particles::app
