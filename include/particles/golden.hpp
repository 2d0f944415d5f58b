#pragma once
/// @file
/// Golden regression checks (golden/README.md): a manifest's frames and states against their
/// references, into a report folder, as `particles golden check` does: the same function runs both.
///
/// @code
/// particles::golden::Report r = particles::golden::check("golden/golden.yaml", {.output = "golden-report"});
/// if (!r.allPassed()) std::cerr << r.summary << "\n";   // open r.html in a browser
/// @endcode

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <particles/choices.hpp>
#include <particles/export.hpp>

namespace particles::golden {

/// What `particles golden check` takes besides the manifest; the names are its options'.
struct Options {
  std::string output = "golden-report";  ///< the report folder (-o): replaced whole when the check is done
  std::vector<std::string> only{};       ///< `--only`: these frames and states; empty: all
  std::optional<Shard> shard{};          ///< `--shard K/N`: the K-th of N near-equal parts; nothing: all
  GlBackend gl = GlBackend::automatic;   ///< `--gl`
  bool gpu = false;                      ///< `--gpu`: draw on a GPU through EGL (golden/README.md, "On a GPU")
  std::optional<Raster> raster{};        ///< `--raster` for entries without their own; nothing: the manifest's
  std::optional<int> threshold{};        ///< `--threshold` for entries without their own (0 … 255)
  std::optional<double> maxShare{};      ///< `--max-share` for entries without their own (0 … 1)
  int jobs = 0;                          ///< `--jobs`: entries checked at once; 0: half the CPUs, at least 1
  /// After each check (on the checking threads): how many are done of how many, and its name.
  std::function<void(long done, long total, const std::string& name)> progress{};
};

/// One frame's result (Outcome: include/particles/choices.hpp). Paths are relative to the report
/// folder; empty when not kept.
struct FrameCheck {
  std::string name;                    ///< the frame's name in the manifest
  std::string scenario;                ///< the scenario's path, as the manifest writes it
  std::string time;                    ///< the frame's time, as the manifest writes it
  bool control = false;                ///< `expect: differ`: passes when the frame differs
  Outcome outcome = Outcome::passed;   ///< passed, failed, missing or error
  std::string message;                 ///< one line, empty when passed
  long differing = 0;                  ///< pixels beyond the threshold
  long pixels = 0;                     ///< width × height
  int largest = 0;                     ///< the largest channel difference, 0 … 255
  std::string actual;                  ///< the frame drawn now (PNG)
  std::string expected;                ///< the reference (PNG)
  std::string diff;                    ///< the differing pixels marked (PNG)
  std::vector<std::string> reproduce;  ///< shell commands that reproduce the result
};

/// One state's result: the first value beyond its tolerance when it failed.
struct StateCheck {
  std::string name;                    ///< the state's name in the manifest
  std::string scenario;                ///< the scenario's path, as the manifest writes it
  std::vector<std::string> times;      ///< the times compared, as the manifest writes them
  Outcome outcome = Outcome::passed;   ///< passed, failed, missing or error
  std::string message;                 ///< one line, empty when passed
  long values = 0;                     ///< values compared
  std::string point;                   ///< the first beyond tolerance (or the largest): cloth[3][4]
  std::string quantity;                ///< its quantity: x, y, vx, vy, angle, omega
  double expected = 0.0;               ///< that value in the reference
  double actual = 0.0;                 ///< that value now
  double difference = 0.0;             ///< |actual − expected|
  double tolerance = 0.0;              ///< the largest difference that passes
  std::vector<std::string> reproduce;  ///< shell commands that reproduce the result
};

/// What a check found: every frame's and state's result, the counts, and the report's files.
struct Report {
  std::vector<FrameCheck> frames;  ///< in manifest order
  std::vector<StateCheck> states;  ///< in manifest order
  long passed = 0;                 ///< frames and states that passed
  long failed = 0;                 ///< frames and states that failed
  long missing = 0;                ///< frames and states with no reference yet
  long errors = 0;                 ///< frames and states that could not be checked
  bool badReference = false;       ///< a reference that is not a usable file (the command's exit 2)
  std::string html;                ///< report.html's path
  std::string summary;             ///< the line `particles golden check` prints last
  /// Whether the command would exit 0: nothing failed, missing or in error, no bad reference.
  bool allPassed() const { return failed == 0 && missing == 0 && errors == 0 && !badReference; }
};

/// Checks the manifest into options.output. Throws ScenarioError for a manifest that cannot be
/// used, ArgumentError for bad options or a report folder that may not be replaced (it holds
/// something other than an earlier report, or one of the check's inputs), OutputError when the
/// report cannot be written. A failing frame is a result, not an exception.
PARTICLES_API Report check(const std::string& manifest, const Options& options = {});

}  // namespace particles::golden
