#pragma once
/// @file
/// The exceptions of particles: one hierarchy, thrown by the library itself (the scenario loader
/// throws ScenarioError, the solver SimulationError, the writers OutputError), so that what a
/// program catches is what the command line reports.
///
/// @code
/// particles::Error            anything the library refuses or cannot do; what() says why
/// ├── ScenarioError           a scenario (file, text or set()) that cannot be used: file, line, column, key
/// ├── SimulationError         a simulation that blew up: step, time, integrator, dt
/// ├── OutputError             a file that could not be written (nothing is left half-written)
/// └── ArgumentError           a bad argument to an API call: an index out of range, step(-1), …
/// @endcode

#include <stdexcept>
#include <string>
#include <utility>

#include <particles/choices.hpp>
#include <particles/export.hpp>

namespace particles {

/// Anything the library refuses or cannot do; what() says why. Every exception the library throws
/// is one of these (std::bad_alloc aside).
class PARTICLES_API Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A scenario that cannot be used, with where and why. what() reads
/// `FILE:LINE:COLUMN: error: KEY: MESSAGE`, as the command line prints it.
class PARTICLES_API ScenarioError : public Error {
 public:
  /// line, column: 1-based; 0 when the error has no position (an unreadable file, a set() value).
  /// origin: where the offending value came from (a command-line option, a set() call), or empty.
  ScenarioError(std::string file, int line, int column, std::string keyPath, std::string message,
                std::string origin = {})
      : Error(describe(file, line, column, keyPath, message, origin)),
        file_(std::move(file)),
        line_(line),
        column_(column),
        keyPath_(std::move(keyPath)),
        message_(std::move(message)),
        origin_(std::move(origin)) {}
  const std::string& file() const { return file_; }        ///< the file's path, or the text's label
  int line() const { return line_; }                        ///< 1-based; 0: no position
  int column() const { return column_; }                    ///< 1-based; 0: no position
  const std::string& keyPath() const { return keyPath_; }  ///< `forces[2].ks`, or empty
  const std::string& message() const { return message_; }  ///< why, without the place
  const std::string& origin() const { return origin_; }    ///< `--set`, `set()`, …, or empty

 private:
  static std::string describe(const std::string& file, int line, int column, const std::string& keyPath,
                              const std::string& message, const std::string& origin) {
    // Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, wrongly) on `"(" + origin + ")"`.
    std::string out = file;
    if (line > 0) out.append(":").append(std::to_string(line)).append(":").append(std::to_string(column));
    out.append(": error: ");
    if (!keyPath.empty() || !origin.empty()) {
      out.append(keyPath);
      if (!origin.empty()) out.append(keyPath.empty() ? "(" : " (from ").append(origin).append(")");
      out.append(": ");
    }
    return out.append(message);
  }

  std::string file_;
  int line_, column_;
  std::string keyPath_, message_, origin_;
};

/// A simulation that blew up: a non-finite state or runaway kinetic energy. what() names the step,
/// time, integrator and dt and suggests what to change. The simulation is left at its last good
/// state.
class PARTICLES_API SimulationError : public Error {
 public:
  /// `what` is the whole message; the rest are its parts.
  SimulationError(const std::string& what, std::string reason, long step, double time, Integrator integrator, double dt)
      : Error(what), reason_(std::move(reason)), step_(step), time_(time), integrator_(integrator), dt_(dt) {}
  const std::string& reason() const { return reason_; }  ///< what went wrong: a non-finite state, the energy
  long step() const { return step_; }                    ///< the step that failed, counted from 1
  double time() const { return time_; }                  ///< s, the time that step would have reached
  Integrator integrator() const { return integrator_; }  ///< name() spells it: rk4, backward_euler…
  double dt() const { return dt_; }                      ///< s

 private:
  std::string reason_;
  long step_;
  double time_;
  Integrator integrator_;
  double dt_;
};

/// A file that could not be opened, written or renamed into place; what() names the path and the
/// system's words.
class PARTICLES_API OutputError : public Error {
 public:
  using Error::Error;
};

/// A bad argument to an API call (an index out of range, an unknown name, step(-1), advance(NaN)):
/// what() names the call and the value.
class PARTICLES_API ArgumentError : public Error {
 public:
  using Error::Error;
};

}  // namespace particles
