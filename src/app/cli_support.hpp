#pragma once
// What the subcommands share: loading the scenario with the command line's overrides, and the
// progress line on stderr.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "app/commands.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

// The overrides of the command line: --set first, in order, then the shorthands, which win.
std::vector<scenario::Override> overridesOf(const CommonOptions& o);
// The scene limits: the defaults with each --limit NAME=N applied, in order.
scenario::SceneLimits sceneLimitsOf(const CommonOptions& o);

// Loads the scenario with the overrides. Throws scenario::ScenarioError for bad input.
scenario::Scenario loadScenario(const CommonOptions& o);

// Refuses (InputError, exit 2) a figure path that plot/ cannot write (.svg, .png or .pdf), so that
// a typo is found before the work whose result the figure shows, not after.
void requireFigurePath(const std::string& option, const std::string& path);

std::string plural(size_t n, const char* one, const char* many);

// --max-input MIB, from 1 MiB to 1 TiB, its default shown: every command that reads files takes it.
void addMaxInputOption(CLI::App& command, std::uintmax_t& mebibytes, const std::string& what);
// "625 particles, 0 rigid bodies, 1200 springs, …" for messages.
std::string contents(const scenario::Scenario& s);

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
