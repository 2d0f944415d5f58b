#pragma once
// What the subcommands share: the options of those that read a scenario, loading it with the
// command line's overrides, and the progress line on stderr.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/exit_codes.hpp"
#include "core/integrators.hpp"
#include "input/text_file.hpp"
#include "scenario/scenario.hpp"
#include "scenario/summary.hpp"

namespace particles::app {

// The names of every integrator the core has, in its order ("euler", "midpoint", "rk4").
inline std::vector<std::string> integratorNames() {
  std::vector<std::string> names;
  for (Integrator i : allIntegrators()) names.emplace_back(integratorName(i));
  return names;
}

// Options every scenario-reading subcommand takes.
struct CommonOptions {
  std::string scenario;
  std::optional<std::string> integrator, dt, duration, implicitSolver;  // shorthands for --set simulation.*=…
  std::vector<std::string> sets;                               // --set path=value, in order
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;     // --max-input
  std::vector<std::string> limits;                             // --limit NAME=N, in order
  std::string style;  // --style FILE (render, check): a style merged over the scenario's; empty: none
  int threads = 0;                                             // --threads N; 0: app/thread_count.hpp's default
  bool quiet = false;
};

// Adds the options of CommonOptions to a command that reads a scenario.
void addCommonOptions(CLI::App& command, CommonOptions& options);
// Adds --style FILE (CommonOptions::style), for the commands that draw a scenario or check it.
void addStyleOption(CLI::App& command, CommonOptions& options);

// The overrides of the command line: --set first, in order, then the shorthands, which win.
std::vector<scenario::Override> overridesOf(const CommonOptions& o);
// The scene limits: the defaults with each --limit NAME=N applied, in order.
scenario::SceneLimits sceneLimitsOf(const CommonOptions& o);

// Loads the scenario with --style's file and the overrides, its System set to run on --threads'
// threads (or PARTICLES_THREADS', or one per CPU this process may use). Throws
// scenario::ScenarioError for bad input, InputError for a bad PARTICLES_THREADS.
scenario::Scenario loadScenario(const CommonOptions& o);

// Refuses (InputError, exit 2) a figure path that plot/ cannot write (.svg, .png or .pdf), so that
// a typo is found before the work whose result the figure shows, not after.
void requireFigurePath(const std::string& option, const std::string& path);

using scenario::plural;    // "3 jobs" (scenario/summary.hpp)
using scenario::contents;  // "625 particles, 0 rigid bodies, …" for messages

// --max-input MIB, from 1 MiB to 1 TiB, its default shown: every command that reads files takes it.
void addMaxInputOption(CLI::App& command, std::uintmax_t& mebibytes, const std::string& what);

// Progress on stderr — done/total, rate and ETA — only for a person watching a terminal (never
// when stderr is a file or a pipe, as in CI), at most ten times a second.
class Progress {
 public:
  Progress(bool enabled, std::string unit);
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void update(long done, long total, std::string_view detail = {});
  void finish();

 private:
  bool enabled_;
  std::string unit_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace particles::app
