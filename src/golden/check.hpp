#pragma once
// Checking a golden manifest (golden/README.md): each entry's scenario is loaded once (with its
// --set overrides) and simulated once, through all of its times in increasing order, each frame
// drawn and compared with its reference PNG as `particles compare` does, each state compared with
// its reference CSV (golden/state_table.hpp). A frame is the same pixels as
// `particles render SCENARIO --at T` with the entry's render settings: the same stepper reaches
// each time by the same steps (core/solver.hpp).
//
// Nothing here prints, parses the command line or writes the report's pages: the program does
// (src/app/golden_command.cpp, golden/results.hpp). What this writes is the files kept for the
// report (actual, expected, diff) into the folder it is given.
//
// The pieces: check.cpp selects the checks and runs each entry's on the core's WorkerPool;
// golden/frame_check.hpp and golden/state_check.hpp check an entry's frames or state;
// golden/check_settings.hpp lays an entry's settings; golden/reproduce_commands.hpp writes the
// commands that reproduce a result.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "golden/results.hpp"
#include "input/text_file.hpp"
#include "render/gl_backend.hpp"
#include "render/image_compare.hpp"
#include "render/render_options.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

// Settings of the command line over the manifest's defaults (an entry that sets its own keeps it):
// another raster path or tolerance for a run whose pixels are expected to differ a little (the tile
// path, another backend).
struct CheckOverrides {
  std::optional<render::Raster> raster;
  std::optional<int> threshold;
  std::optional<double> maxShare;
  bool any() const { return raster || threshold || maxShare; }
  std::vector<std::string> args()
      const;                 // {"--raster", "tiles", "--max-share", "0.0005"}, as the command line has them
  std::string text() const;  // the same joined by spaces
};

// The most entries a check runs at once (--jobs): each has a GL context and a frame's buffers.
inline constexpr int kMaxJobs = 256;

struct CheckOptions {
  std::string manifestGiven;                 // the manifest as given on the command line, for commands
  std::optional<std::pair<int, int>> shard;  // K, N: the K-th of N near-equal blocks of the checks, 1 ≤ K ≤ N
  std::vector<std::string> only;             // names of frames and states; empty: all
  bool missingOnly = false;                  // only the checks whose reference is absent (update --missing)
  render::GlRequest gl;
  CheckOverrides overrides;
  int jobs = 1;  // entries simulated at once, each on a thread of a WorkerPool with its own GL context
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;  // scenarios, reference PNGs and state files
  // Keep the actual frame or state of every check, passing or not (update writes them as references).
  bool keepAll = false;
  std::string program = "particles";  // how the commands that reproduce a result spell the program
  // After each check: done of total.
  std::function<void(long done, long total, const std::string& name)> progress;
};

// What a run makes: results in manifest order (frames, then states), and whether a reference was
// unusable (not a regular file, past the size limit, not a PNG or state file): bad input, exit 2,
// though every check ran and is reported. A reference of another size than its frame is usable: the
// frame changed size, a failure.
struct CheckRun {
  GoldenResults results;
  bool badReference = false;
};

// The names of every check of the manifest, frames then states, in manifest order.
std::vector<std::string> checkNames(const scenario::GoldenManifest& manifest);

// The checks the options select, in manifest order: those --only names (all when it names none),
// only those whose reference is absent with missingOnly (never a frame that compares with another's
// reference), then the shard's contiguous block of them. Throws std::invalid_argument for --only
// names the manifest does not have (with the closest one) or a shard out of range.
std::vector<scenario::GoldenCheck> selectChecks(const scenario::GoldenManifest& manifest, const CheckOptions& options);

// Throws ScenarioError in the manifest for render settings the renderer does not know (a theme,
// a raster path, a background), for every entry, before anything runs.
void checkRenderSettings(const scenario::GoldenManifest& manifest);

// Runs the checks the options select into `folder` (which exists): kept files under frames/ and
// states/. Throws std::invalid_argument for --only names the manifest does not have (with the
// closest one) or a shard out of range; OutputError when a kept file cannot be written. A scenario
// that does not load, a simulation that blows up or a GL error is that entry's `error` result.
CheckRun runCheck(const scenario::GoldenManifest& manifest, const std::filesystem::path& folder,
                  const CheckOptions& options);

// A comparison's numbers as the results hold them.
FrameNumbers frameNumbersOf(const render::ImageComparison& comparison, const render::CompareTolerance& tolerance);

// The reference file of a frame (NAME.png) or state (NAME.csv).
std::filesystem::path frameReference(const scenario::GoldenManifest& manifest, const std::string& name);
std::filesystem::path stateReference(const scenario::GoldenManifest& manifest, const std::string& name);

}  // namespace particles::golden
