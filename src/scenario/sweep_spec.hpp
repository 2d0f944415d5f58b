#pragma once
// A sweep file (`particles sweep SPEC.yaml`, docs/sweeps.md): scenarios × one command × parameters
// to vary, read and checked here with the positions every later error names. Turning it into job
// command lines, running them or emitting them for GNU parallel and Slurm is the program's
// (src/app/sweep_*.cpp); this room owns the YAML.
//
//   name: cloth_stiffness                 # optional; the file's stem by default
//   scenarios: [../cloth.yaml]             # relative to the sweep file
//   command: stability                     # run | render | stability
//   options: {duration: 4, integrators: [euler, rk4]}   # the command's options, for every job
//   parameters:                            # crossed with each other
//     - {key: grids[0].springs.structural.ks, scale: true, values: [0.5, 1, 2], name: stiffness_scale}
//     - zip:                               # varied together, one value of each per job
//         - {key: integrator, values: [euler, rk4]}
//         - {key: dt, values: [0.001, 0.01]}
//   split: 2                               # render: each video in 2 segments, joined by concat
//   slurm: [--time=00:20:00]               # extra #SBATCH lines for --emit slurm

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace particles::scenario {

// Where something was written in the sweep file: 1-based line and column (0: nowhere in the
// file) and its key path (`parameters[1].values[2]`).
struct SweepPosition {
  int line = 0, column = 0;
  std::string keyPath;
};

// One value a parameter takes: its text as it goes on the command line (a scalar as written, a
// list in YAML flow form), and the number when it is one (for tables and figures).
struct SweepValue {
  std::string text;
  std::optional<double> number;
  SweepPosition at;
};

struct SweepParameter {
  // `integrator`, `dt` or `duration` (the command's shorthands), or a --set key path.
  std::string key;
  std::string name;         // the column in jobs.csv and results.csv; the key unless given
  bool scale = false;       // values are factors on the scenario's own value at `key`
  bool logSpacing = false;  // from a log `range` (a figure then takes a log axis)
  std::vector<SweepValue> values;
  SweepPosition at;
};

// Parameters varied together (a `zip` entry, all of one length) or one parameter alone. The
// groups of a sweep are crossed.
struct SweepGroup {
  std::vector<SweepParameter> parameters;
  bool zipped = false;
  SweepPosition at;
  size_t size() const { return parameters.front().values.size(); }
};

// One of the command's options as `--name value` (a list joined by commas), or a flag `--name`.
struct SweepOption {
  std::string name;  // without the dashes
  std::string value;
  bool flag = false;
  SweepPosition at;
};

struct SweepScenario {
  std::string given;           // as the sweep file writes it
  std::filesystem::path path;  // resolved against the sweep file's folder
  SweepPosition at;
};

struct SweepSpec {
  std::string file;  // as given, for messages
  std::string name;
  std::vector<SweepScenario> scenarios;
  std::string command;  // run | render | stability
  SweepPosition commandAt;
  std::vector<SweepOption> options;
  std::vector<std::pair<std::string, std::string>> sets;  // options.set: {path: value}, in order
  std::vector<SweepPosition> setsAt;
  std::vector<SweepGroup> groups;
  SweepPosition parametersAt;
  int split = 1;  // render: segments per video
  SweepPosition splitAt;
  std::vector<std::string> slurm;  // extra sbatch options, each one `#SBATCH` line

  // Jobs before splitting: scenarios × the product of the groups' sizes.
  std::uintmax_t combinations() const;
};

// The most jobs one sweep file may make (scenarios × combinations × split).
inline constexpr std::uintmax_t kMaxSweepJobs = 100'000;
// The most YAML nodes (values, keys, lists, maps) a sweep file may hold: three zipped parameters
// of kMaxSweepJobs values each, and room for the rest. Counted before any node is built.
inline constexpr std::uintmax_t kMaxSweepNodes = 3 * kMaxSweepJobs + 10'000;

// The columns jobs.csv and results.csv write around the parameters' own (docs/sweeps.md): a
// parameter named like one of them would make a second column of that name, which a reader
// takes for the first, so such names are refused.
inline constexpr std::string_view kReservedColumns[] = {"index",   "stage",  "scenario", "segment", "dir",
                                                        "command", "status", "exit",     "seconds", "message"};

// Reads and checks a sweep file: unknown keys, empty lists, zips of unlike lengths, a product over
// kMaxSweepJobs, options the sweep itself sets. Throws ScenarioError naming file, line and key.
SweepSpec loadSweepFile(const std::filesystem::path& file, std::uintmax_t maxInputMiB);
SweepSpec loadSweepText(std::string_view text, const std::string& file);

// Throws ScenarioError in the sweep file at `at`.
[[noreturn]] void failInSweep(const SweepSpec& spec, const SweepPosition& at, const std::string& message);

}  // namespace particles::scenario
