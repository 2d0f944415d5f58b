#pragma once
// What the frame and state checks of one run share (golden/frame_check.hpp,
// golden/state_check.hpp): the manifest, the report folder and the options; what they tell the
// run from any thread (a check done, a reference unusable, the GL that drew); how they read a
// reference and keep a file; and an entry's simulation, loaded and stepped the same way for both.
// Internal to the golden room.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

#include "core/solver.hpp"
#include "golden/check.hpp"
#include "render/gl_backend.hpp"
#include "scenario/golden_manifest.hpp"
#include "render/styled_run.hpp"
#include "scenario/scenario.hpp"

namespace particles::golden {

class CheckContext {
 public:
  // `checks`: how many the run has, for progress.
  CheckContext(const scenario::GoldenManifest& manifest, std::filesystem::path folder, const CheckOptions& options,
               long checks);

  const scenario::GoldenManifest& manifest() const { return manifest_; }
  const std::filesystem::path& folder() const { return folder_; }
  const CheckOptions& options() const { return options_; }

  // A check has its outcome: progress.
  void done(const std::string& name);
  // The GL a frame was drawn with; the run reports the first.
  void noteGl(const render::GlInfo& info);
  // A reference that cannot be used (not a regular file, too large, not a PNG or state file): the
  // check's error, and bad input for the run's exit code.
  template <class Result>
  void unusableReference(Result& result, const std::exception& why) {
    result.outcome = Outcome::error;
    result.message = "the reference cannot be used: " + std::string(why.what());
    std::lock_guard lock(mutex_);
    badReference_ = true;
  }

  bool badReference() const { return badReference_; }  // once the checks have ended
  const std::string& gl() const { return gl_; }        // once the checks have ended

 private:
  const scenario::GoldenManifest& manifest_;
  const std::filesystem::path folder_;
  const CheckOptions& options_;
  const long checks_;
  std::mutex mutex_;
  long done_ = 0;
  bool badReference_ = false;
  std::string gl_;
};

// A path as the results and the commands that reproduce them write it: relative to where the
// check runs.
std::string shownPath(const std::filesystem::path& path);

// Seconds since `start`, for a result's wall time.
double secondsSince(std::chrono::steady_clock::time_point start);

// A reference read within the limits and never waited on: a regular file, or ReferenceError.
struct ReferenceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
std::string readReference(const std::filesystem::path& file, std::uintmax_t maxInputMiB);

// Whether nothing is at `file`, not even a broken link: a missing reference, not an unusable one.
bool referenceAbsent(const std::filesystem::path& file);

// Keeps `text` as `file` (under a temporary name until complete). Throws OutputError.
void writeText(const std::filesystem::path& file, const std::string& text);

// An entry's scenario, loaded with the entry's `set:` overrides (each named by its place in the
// manifest) and stepped to the entry's times, in increasing order, by the stepper
// `particles render --at` uses (core/solver.hpp): a frame or state at a time is the program's.
class EntrySimulation {
 public:
  // Throws what loading a scenario throws (ScenarioError, a file that cannot be read).
  EntrySimulation(const scenario::GoldenManifest& manifest, const scenario::GoldenEntry& entry,
                  std::uintmax_t maxInputMiB);
  EntrySimulation(const EntrySimulation&) = delete;
  EntrySimulation& operator=(const EntrySimulation&) = delete;

  const scenario::Scenario& scenario() const { return scenario_; }
  // Why the simulation cannot reach `time` (it is after the scenario's duration), or empty.
  std::string unreachable(const scenario::GoldenTime& time) const;
  // Steps to `time`. Throws std::invalid_argument with unreachable's message, SimulationError.
  // With a styled run, every step feeds its trails and camera (render/styled_run.hpp).
  void advanceTo(const scenario::GoldenTime& time, render::StyledRun* styled = nullptr);
  // The system, for drawing a styled frame (which may evaluate its accelerations).
  System& system() { return scenario_.system; }

 private:
  scenario::Scenario scenario_;
  Stepper stepper_;  // steps scenario_.system
};

}  // namespace particles::golden
