#pragma once
// A golden manifest (`particles golden check MANIFEST`, golden/README.md): which frames and which
// states of which scenarios are compared with stored references, and how. Read and checked here
// with the positions every later error names; rendering, comparing and reporting are the golden
// room's (src/golden/), which also checks the render settings' names (theme, raster, background)
// against the renderer's, failing at the positions kept here.
//
//   references: .                # folder of the references, relative to the manifest (default: its own)
//   defaults:                    # for every entry that does not set its own
//     render: {size: 320x240, msaa: 4, theme: dark, background: theme, raster: auto}
//     tolerance: {threshold: 16, max_share: 0.0002}            # as `particles compare`'s
//     state_tolerance: {position: 1e-9, velocity: 1e-9, angle: 1e-9, omega: 1e-9}
//   frames:
//     - scenario: ../scenarios/cloth.yaml       # relative to the manifest
//       times: [0.5, 2.5, 10]                   # seconds of simulated time; one simulation renders all
//       name: "{scenario}_t{time}"              # the default: cloth_t0.5 → references/cloth_t0.5.png
//       set: {"grids[0].springs.structural.ks": [26.25, 1.05]}   # as --set, in order
//       render: {raster: tiles}                 # over the defaults, key by key
//       tolerance: {max_share: 0.0005}
//       expect: differ                          # a control: passes only when the frame differs
//       reference: cloth_t2.5                   # compare with that frame's reference, not its own
//   states:
//     - scenario: ../scenarios/soft_body.yaml
//       times: [9, 37.5]
//       name: "{scenario}"                      # the default: soft_body → references/soft_body.csv
//       state_tolerance: {position: 1e-6}

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace particles::scenario {

// Where something was written in the manifest: 1-based line and column (0: nowhere in the file)
// and its key path (`frames[1].times[2]`).
struct GoldenPosition {
  int line = 0, column = 0;
  std::string keyPath;
};

template <class T>
struct GoldenSetting {
  T value;
  GoldenPosition at;
};

// Render settings, each absent unless written; an entry's are laid over the defaults' key by key,
// and what neither sets is the program's default (`particles render`'s). Names are checked by the
// golden room against the renderer's.
struct GoldenRenderSettings {
  std::optional<GoldenSetting<std::pair<int, int>>> size;  // width, height in px, 1 … kMaxImageSide
  std::optional<GoldenSetting<int>> msaa;                  // samples per pixel
  std::optional<GoldenSetting<std::string>> theme;         // dark | light
  std::optional<GoldenSetting<std::string>> background;    // theme | transparent
  std::optional<GoldenSetting<std::string>> raster;        // auto | triangles | tiles
};

// A frame's tolerance, as `particles compare --threshold --max-share`.
struct GoldenFrameTolerance {
  std::optional<GoldenSetting<int>> threshold;    // 0 … 255
  std::optional<GoldenSetting<double>> maxShare;  // 0 … 1
};

// A state's absolute tolerances: positions (m), velocities (m/s), rigid bodies' angles (rad) and
// angular velocities (rad/s). A quantity differs when |actual − expected| > its tolerance.
struct GoldenStateTolerance {
  std::optional<GoldenSetting<double>> position, velocity, angle, omega;  // ≥ 0
};

// One time of an entry: the number, its text as written (for names and the state file's time
// column) and the name of the frame it makes (frames only).
struct GoldenTime {
  double seconds = 0.0;  // ≥ 0, finite
  std::string text;
  std::string frameName;
  GoldenPosition at;
};

struct GoldenEntry {
  std::string scenarioGiven;       // as the manifest writes it
  std::filesystem::path scenario;  // resolved against the manifest's folder
  GoldenPosition scenarioAt;
  std::vector<std::pair<std::string, std::string>> sets;  // --set path=value, in the order written
  std::vector<GoldenPosition> setsAt;
  std::vector<GoldenTime> times;  // as written: distinct, in increasing order
  std::string stateName;          // states: the name of its reference (NAME.csv)
  GoldenPosition nameAt;
  GoldenRenderSettings render;          // frames: the entry's own, not yet laid over the defaults
  GoldenFrameTolerance tolerance;       // frames: the entry's own
  GoldenStateTolerance stateTolerance;  // states: the entry's own
  bool expectDiffer = false;            // frames: `expect: differ`
  // frames: `reference: NAME`, compare with frame NAME's reference rather than a reference of its
  // own (a control or a rounding check: the same frame with a perturbation; NAME.png in the
  // references' folder, which may belong to another manifest). One time only; NAME a file name as
  // a frame's. `golden update` never writes it.
  std::optional<GoldenSetting<std::string>> reference;
  GoldenPosition at;  // the entry
};

struct GoldenManifest {
  std::string file;                  // as given, for messages
  std::filesystem::path references;  // the references' folder, resolved against the manifest's
  GoldenRenderSettings defaultRender;
  GoldenFrameTolerance defaultTolerance;
  GoldenStateTolerance defaultStateTolerance;
  std::vector<GoldenEntry> frames, states;
};

// One check of a manifest: a frame (a time of a frame entry) or a state (a state entry).
struct GoldenCheck {
  enum class Kind { frame, state };
  Kind kind = Kind::frame;
  std::size_t entry = 0;  // into the manifest's frames or states
  std::size_t time = 0;   // frames: into the entry's times
  std::string name;       // the frame's or state's name, its reference's file name
};

// Every check of the manifest, frames then states, in manifest order.
std::vector<GoldenCheck> goldenChecks(const GoldenManifest& manifest);

// An entry's settings, key by key: its own, over `commandLine`'s (a run's settings over the
// manifest's defaults: `golden check --raster --threshold --max-share`), over the manifest's
// defaults. What none of them sets stays absent: the program's default (`particles render`'s,
// `particles compare`'s).
GoldenRenderSettings renderSettingsOf(const GoldenManifest& manifest, const GoldenEntry& entry,
                                      const GoldenRenderSettings& commandLine = {});
GoldenFrameTolerance frameToleranceOf(const GoldenManifest& manifest, const GoldenEntry& entry,
                                      const GoldenFrameTolerance& commandLine = {});

// A state check's tolerances once laid: position (m), velocity (m/s), angle (rad), omega (rad/s).
struct GoldenStateToleranceValues {
  double position = 0.0, velocity = 0.0, angle = 0.0, omega = 0.0;
};
// What neither an entry nor the manifest's defaults set: golden/README.md, "States", tells how
// they were chosen.
inline constexpr GoldenStateToleranceValues kDefaultGoldenStateTolerance{1e-6, 1e-5, 1e-6, 1e-5};
// An entry's state tolerances: its own, over the manifest's defaults, over kDefaultGoldenStateTolerance.
GoldenStateToleranceValues stateToleranceOf(const GoldenManifest& manifest, const GoldenEntry& entry);

// The most frames and states one manifest may name in all (entries × times).
inline constexpr std::uintmax_t kMaxGoldenChecks = 100'000;
// The longest name (a file name, without .png or .csv).
inline constexpr std::size_t kMaxGoldenNameLength = 200;
// The samples per pixel `render.msaa` takes: `particles render --msaa`'s (render::kSampleCounts,
// which this room cannot include; tests/test_golden_manifest.cpp checks that they agree).
inline constexpr int kGoldenSampleCounts[] = {1, 2, 4, 8, 16};

// Reads and checks a manifest: unknown keys (with the closest known one), empty lists, times that
// are negative or repeated, names that are not file names ([A-Za-z0-9._+-], not starting with a
// dot) or that two checks share, a size or tolerance out of range. Throws ScenarioError naming
// file, line, column and key. Nothing is opened but the manifest (scenarios are the golden room's).
GoldenManifest loadGoldenManifestFile(const std::filesystem::path& file, std::uintmax_t maxInputMiB);
// The same from text; relative paths are resolved against `directory`.
GoldenManifest loadGoldenManifestText(std::string_view text, const std::string& file,
                                      const std::filesystem::path& directory);

// Throws ScenarioError in the manifest at `at`.
[[noreturn]] void failInManifest(const GoldenManifest& manifest, const GoldenPosition& at, const std::string& message);

// The JSON Schema (draft 7) of a manifest, for editors and CI checks (`particles schema --golden`).
std::string goldenManifestJsonSchema();

}  // namespace particles::scenario
