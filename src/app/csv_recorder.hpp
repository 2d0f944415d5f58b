#pragma once
// The --stats and --trace CSV files of `run` and `render` (docs/physics.md §12): one row (stats) or one row
// per traced object (trace) each time record() is called, numbers in shortest round-trip form.
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
  // Throws InputError when the options are inconsistent: the same file for both, or a
  // --trace-only name nothing in the system has; OutputError when a file cannot be created.
  static std::unique_ptr<CsvRecorder> open(const System& system, const std::string& statsPath,
                                         const std::string& tracePath, const std::vector<std::string>& traceOnly);

  void record(const System& system);
  void commit();  // throws OutputError
  bool writesStats() const { return stats_.has_value(); }
  bool writesTrace() const { return trace_.has_value(); }

 private:
  CsvRecorder() = default;
  std::optional<output::OutputFile> stats_, trace_;
  std::vector<int> points_;
  std::vector<std::string> names_;
};

}  // namespace particles::app
