#pragma once
// The program's one table from errors to exit codes and messages. Commands throw; main() runs
// them through runReportingErrors, the one place that prints an error and picks its code:
//   1  the simulation failed    SimulationError, SimulationFailure   "SCENARIO: error: …"
//   2  bad input or usage       scenario::ScenarioError              its own "FILE:LINE:COL: error: …"
//                               InputError, plot::CsvError,
//                               output::SameFileError,
//                               output::OutsideFolderError           "error: …"
//   3  an output failed         output::OutputError, render::RenderError,
//                               plot::FigureError                    "error: …"
//      memory ran out           std::bad_alloc (render::OutOfMemory says for what)
//                                                                    "error: out of memory: …"
//   1  anything else: a bug     "particles: internal error: …"
// A command returns the code of an outcome that is not an error: kOk, compare's differing frames
// (1), an interrupted render (128 + signal). What is printed has its control characters escaped
// (output/printable_text.hpp): a message may quote a name from a file.

#include <functional>
#include <stdexcept>
#include <string>

namespace particles::app {

enum ExitCode { kOk = 0, kSimulationFailed = 1, kBadInput = 2, kOutputFailed = 3 };

// Bad input a command finds itself: an option out of range, options that do not go together, a
// name the scenario does not have, an input it cannot read. Exit 2, printed "error: " + what().
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The simulation failed where the core does not say so with a SimulationError (the stability
// study's reference run), or the command adds to what it says (the frame a render reached).
// Exit 1, printed like a SimulationError.
class SimulationFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What the messages name.
struct ErrorContext {
  std::string scenario;            // the scenario file as given; empty for commands without one
  std::string* printed = nullptr;  // when set, receives the error message printed (a job record keeps it)
};

// Runs the command and returns its exit code; an exception from it is printed on stderr and
// mapped to its code by the table above.
int runReportingErrors(const ErrorContext& context, const std::function<int()>& command);

}  // namespace particles::app
