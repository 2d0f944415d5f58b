#pragma once
// `particles render SCENARIO -o OUT` (docs/physics.md §9, §12): simulate and draw frames off-screen,
// frames i = 0 … round(duration·fps) − 1 at t = i / fps, or the one frame at --at T, in OUT's
// format (render/video/output_formats.hpp, which checks the options that depend on it).
//
// Exit codes: 0 done; 1 the simulation failed; 2 bad input (options, the scenario, a frame larger
// than the GL draws); 3 an output failed; 128 + signal when stopped by SIGINT or SIGTERM. Outputs
// appear only when complete: a signal or any failure removes them.

#include <optional>
#include <string>
#include <vector>

#include "app/command.hpp"
#include "render/video/frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/render_options.hpp"

namespace particles::app {

struct RenderCommandOptions {
  CommonOptions common;
  std::string output;                // -o: a path of a format of render/video/output_formats.hpp
  std::optional<double> at;          // --at T, s
  std::string frames;                // --frames A:B, frames A … B−1 only; empty: all
  std::string size;                  // --size WxH; empty: the scenario's render.size
  std::optional<double> fps;         // --fps; none: the scenario's render.fps (render::defaultFps)
  int msaa = render::RenderOptions{}.msaa;  // anti-aliasing samples per pixel: one of render::kSampleCounts
  std::string raster = "auto";       // --raster auto | triangles | tiles | resident | cpu
  std::string theme = "dark";        // dark | light
  std::string background = "theme";  // --background theme | transparent (formats that keep alpha)
  std::string particleRadius;        // "4px" or "0.02m"; empty: the renderer's default
  std::optional<int> crf;            // encoder quality; none: the format's default (output_formats.hpp)
  double keyint = render::VideoOptions{}.keyintSeconds;  // --keyint: longest time between keyframes, s
  std::string preset = render::VideoOptions{}.preset;    // x264 preset
  int pngLevel = render::PngOptions{}.compressionLevel;  // zlib level for PNG output
  bool verbose = false;              // the GL backend on stderr, and libav/x264's log
  std::string gl;                    // --gl auto | egl | osmesa; empty: $PARTICLES_GL, else auto
  bool gpu = false;                  // --gpu: a hardware EGL device
  bool hud = false;                  // time, integrator, dt and energy drawn on each frame
  std::string stats, trace;          // CSVs, one row per frame
  std::vector<std::string> traceOnly;
  JobOptions job;
};

extern const CommandDescriptor<RenderCommandOptions> kRenderCommand;

}  // namespace particles::app
