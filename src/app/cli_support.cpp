#include "app/cli_support.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "input/printable_text.hpp"
#include "app/thread_count.hpp"
#include "core/system.hpp"
#include "plot/errors.hpp"
#include "plot/figure.hpp"

namespace particles::app {

std::vector<scenario::Override> overridesOf(const CommonOptions& o) {
  std::vector<scenario::Override> out;
  for (const std::string& s : o.sets) out.push_back(scenario::parseOverride(s));
  // In scenario::kSimulationShorthands' order: the options that stand for those keys.
  const std::optional<std::string>* values[] = {&o.integrator, &o.dt, &o.duration, &o.implicitSolver};
  static_assert(std::size(values) == scenario::kSimulationShorthands.size());
  for (size_t i = 0; i < std::size(values); ++i) {
    const std::optional<std::string>* value = values[i];
    const std::string_view key = scenario::kSimulationShorthands[i];
    if (!*value) continue;
    std::string option = fmt::format("--{}", key);
    std::replace(option.begin(), option.end(), '_', '-');
    if ((*value)->empty()) throw InputError(fmt::format("{}: expected a value, got an empty one", option));
    out.push_back({fmt::format("simulation.{}", key), **value, fmt::format("{} {}", option, **value)});
  }
  return out;
}

scenario::SceneLimits sceneLimitsOf(const CommonOptions& o) {
  scenario::SceneLimits limits;
  for (const std::string& l : o.limits) scenario::applyLimitOption(limits, l);
  return limits;
}

scenario::Scenario loadScenario(const CommonOptions& o) {
  const int threads = threadCountOf(o.threads);  // a bad PARTICLES_THREADS before any work
  const auto overrides = overridesOf(o);
  std::optional<scenario::StyleFile> style;
  if (!o.style.empty()) style = scenario::readStyleFile(o.style, o.maxInputMiB);
  scenario::Scenario s =
      scenario::loadScenarioFile(o.scenario, overrides, o.maxInputMiB, sceneLimitsOf(o), style ? &*style : nullptr);
  s.system.setThreads(threads);
  return s;
}

void addCommonOptions(CLI::App& command, CommonOptions& o) {
  command.add_option("scenario", o.scenario, "Scenario file (YAML, see docs/scenarios.md)")->required();
  command.add_option("--integrator", o.integrator,
                     fmt::format("Override simulation.integrator: {}", fmt::join(integratorNames(), " | ")));
  command.add_option("--dt", o.dt, "Override simulation.dt, the time step in seconds");
  command.add_option("--duration", o.duration, "Override simulation.duration, in simulated seconds");
  command.add_option(
      "--implicit-solver", o.implicitSolver,
      "Override simulation.implicit_solver, backward_euler's and bdf2's linear solve: auto | direct | cg");
  command.add_option("--set", o.sets, "Override any key before validation: --set path.to.key=value (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  command.add_flag("-q,--quiet", o.quiet, "No progress and no summary; errors are still printed");
  command
      .add_option("--threads", o.threads,
                  fmt::format("Threads the command may keep busy: the simulation's and, in render, llvmpipe's and "
                              "the encoder's (default: {}, else one per CPU this process may use); the results "
                              "are the same bits for every count, but for an MP4 above 3 (x264's pictures depend "
                              "on its thread count there: docs/cli.md, Threads)",
                              kThreadsEnvironmentVariable))
      ->check(CLI::Range(1, kMaxThreads));
  addMaxInputOption(command, o.maxInputMiB, "a scenario file");
  command
      .add_option("--limit", o.limits,
                  "Raise (or lower) a scene limit, counted before anything is built: particles, springs, "
                  "constraints, endpoints or entries (repeatable; defaults in docs/scenarios.md, Limits)")
      ->type_name("NAME=N")
      ->allow_extra_args(false);
}

void addStyleOption(CLI::App& command, CommonOptions& o) {
  command
      .add_option("--style", o.style,
                  "A style file (YAML: the keys of a scenario's style section), merged over the scenario's style "
                  "key by key before --set and validation (docs/scenarios.md, Style files)")
      ->type_name("FILE");
}

void addMaxInputOption(CLI::App& command, std::uintmax_t& mebibytes, const std::string& what) {
  command.add_option("--max-input", mebibytes, fmt::format("Refuse {} larger than this, MiB", what))
      ->check(CLI::Range(std::uintmax_t(1), std::uintmax_t(1) << 20))
      ->capture_default_str();
}

void requireFigurePath(const std::string& option, const std::string& path) {
  try {
    plot::formatForPath(path);
  } catch (const plot::FigureError&) {
    throw InputError(fmt::format("{} {}: a figure is .svg, .png or .pdf, not {}", option, path,
                                 input::quotedValue(std::filesystem::path(path).extension().string())));
  }
}

Progress::Progress(bool enabled, std::string unit)
    : enabled_(enabled && ::isatty(STDERR_FILENO)), unit_(std::move(unit)), start_(std::chrono::steady_clock::now()) {}

void Progress::update(long done, long total, std::string_view detail) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (shown_ && now - last_ < std::chrono::milliseconds(100) && done != total) return;
  last_ = now;
  shown_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0.0 ? double(done) / elapsed : 0.0;
  const double eta = rate > 0.0 ? double(total - done) / rate : 0.0;
  fmt::print(stderr, "\r\033[K  {}/{} {} ({:.0f}%)  {:.1f} {}/s  ETA {:.0f} s  {}", done, total, unit_,
             total > 0 ? 100.0 * double(done) / double(total) : 100.0, rate, unit_, eta, detail);
  std::fflush(stderr);
}

void Progress::finish() {
  if (shown_) fmt::print(stderr, "\r\033[K");
  shown_ = false;
}

}  // namespace particles::app
