#pragma once
// The subcommands of the program (docs/physics.md §12). Each returns the process exit code of an outcome
// that is not an error (0 on success) and throws for one; main() runs them through
// runReportingErrors, which prints the error and maps it to its code (exit_codes.hpp).

#include <optional>
#include <string>
#include <vector>

#include "app/exit_codes.hpp"
#include "core/integrators.hpp"
#include "scenario/scenario.hpp"

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
  std::optional<std::string> integrator, dt, duration;  // shorthands for --set simulation.*=…
  std::vector<std::string> sets;         // --set path=value, in order
  std::uintmax_t maxInputMiB = scenario::kDefaultMaxInputMiB;  // --max-input
  std::vector<std::string> limits;       // --limit NAME=N, in order
  bool quiet = false;
};

struct RunOptions {
  std::string stats;                   // --stats CSV, empty: none
  std::string trace;                   // --trace CSV, empty: none
  std::vector<std::string> traceOnly;  // --trace-only names
};

// `stability`: defaults as in StabilityCriteria / StabilityOptions (src/core/stability.hpp).
struct StabilityOptionsCli {
  std::vector<std::string> integrators = integratorNames();  // every integrator the core has
  std::string csv;   // --csv, empty: none
  std::string plot;  // --plot .svg | .png | .pdf, empty: none
  std::vector<std::string> references;  // --reference NAME=DT or NAME=LO:HI, for the figure
  std::string referenceName = "reference";
  double energyTolerance = 0.1;
  double stretchFactor = 1.5;  // × the reference run's largest stretch
  double shakeThreshold = 0.1;
  double minDt = 0;  // 0: the scenario's dt / 1000
  double maxDt = 10.0;
  int threads = 0;
};

struct RenderCommandOptions {
  std::string output;                  // -o: a path of a format of render/output_formats.hpp
  std::optional<double> at;            // --at T, s
  std::string frames;                  // --frames A:B, frames A … B−1 only; empty: all
  std::string size;                    // --size WxH; empty: the scenario's render.size
  std::optional<double> fps;           // --fps; none: the scenario's render.fps (render::defaultFps)
  int msaa = 4;                        // anti-aliasing samples per pixel: 1 (off), 2, 4, 8, 16
  std::string raster = "auto";         // --raster auto | triangles | tiles
  std::string theme = "dark";          // dark | light
  std::string background = "theme";    // --background theme | transparent (PNG and WebM)
  std::string particleRadius;          // "4px" or "0.02m"; empty: the renderer's default
  std::optional<int> crf;              // encoder quality; none: the format's default (render/output_formats.hpp)
  double keyint = 2.0;                 // --keyint: longest time between keyframes, s
  std::string preset = "medium";       // x264 preset
  int pngLevel = 6;                    // zlib level for PNG output
  bool verbose = false;                // the GL backend on stderr, and libav/x264's log
  std::string gl;                      // --gl auto | egl | osmesa; empty: $PARTICLES_GL, else auto
  bool gpu = false;                    // --gpu: a hardware EGL device
  bool hud = false;                    // time, integrator, dt and energy drawn on each frame
  std::string stats, trace;            // CSVs, one row per frame
  std::vector<std::string> traceOnly;
};

struct PlotOptions {
  std::string input;   // a --stats CSV
  std::string output;  // .svg | .png | .pdf
  std::string title;
  // The run's scenario and its overrides, for the title and the mouse's intervals; empty: none.
  std::string scenario;
  std::optional<std::string> integrator, dt;
  std::vector<std::string> sets;
  int width = 0, height = 0;  // px; 0: the figure's default
  std::uintmax_t maxInputMiB = 64;  // --max-input
  bool quiet = false;
};

struct SchemaOptions {
  bool markdown = false;  // the docs' key tables instead of JSON Schema
};

int checkCommand(const CommonOptions& common);
int runCommand(const CommonOptions& common, const RunOptions& run);
int stabilityCommand(const CommonOptions& common, const StabilityOptionsCli& options);
int plotCommand(const PlotOptions& options);
int schemaCommand(const SchemaOptions& options);
int renderCommand(const CommonOptions& common, const RenderCommandOptions& options);

}  // namespace particles::app
