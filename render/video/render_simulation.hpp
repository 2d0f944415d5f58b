#pragma once
// `particles render` as a library call: steps a simulation, draws it at each frame's time and
// writes them in the output's format (render/video/output_formats.hpp): a run of frames
// i = 0 … frameCount(duration, fps) − 1 at t = i / fps through a writer (render/video/frame_writer.hpp),
// or a range of them (RenderJob::frames, for the formats that split), or the one frame at `at`
// seconds (render/png_io.hpp).
// A frame shows the state after the last time step at or before its time (to rounding), so with
// a dt that divides 1/fps every frame is exact.
//
// Nothing here prints, reads scenario files or knows the command line: the program passes hooks
// for what it adds (CSV rows per frame, a text overlay, progress, stopping on a signal). Outputs
// appear only when complete; a failure or a stop leaves nothing (an existing output is untouched).

#include <filesystem>
#include <functional>
#include <optional>
#include <utility>

#include "core/integrators.hpp"
#include "core/system.hpp"
#include "render/video/frame_writer.hpp"
#include "render/gl_backend.hpp"
#include "render/image.hpp"
#include "render/png_io.hpp"
#include "render/render_options.hpp"
#include "style/style.hpp"
#include "style/view.hpp"

namespace particles::render {

struct RenderJob {
  std::filesystem::path output;  // its format is a row of render/video/output_formats.hpp (outputFormatOf)
  std::optional<double> at;      // s: the time of the one frame of a one-frame format; only with one.
                                 // A time not after the system's (or NaN) draws its current state
  double duration = 0.0;         // s of simulated time a video or sequence covers, > 0
  int fps = 60;                  // frames per simulated second, ≥ 1
  // Only frames first … end − 1 of the video or sequence (a split render): the simulation still
  // starts from the system's state and steps through the earlier frames' times without drawing
  // them, so each frame is the same as in the whole render. A sequence names the frames by their
  // index in the whole (frame_000060.png …) and leaves other frames in the directory alone; an
  // MP4 holds end − first frames from t = 0 and starts with a keyframe (particles concat joins
  // segments). Only for the formats that split (OutputFormat::splits). Nothing: every frame.
  // 0 ≤ first < end ≤ frameCount(duration, fps).
  std::optional<std::pair<long, long>> frames;
  Camera camera;  // the fixed view (the scenario's render.view centre and height)
  RenderOptions look;
  // What the frames show beyond the geometry and how the camera moves (render/styled_run.hpp):
  // plain by default. An automatic colour range or a camera that fits the run costs one pass over
  // the whole render's frames before the first is drawn (a split render makes the same pass).
  style::Style style;
  style::ViewStyle view;
  GlRequest gl;        // which GL backend draws (render/gl_backend.hpp)
  // The threads the render may keep busy, the simulation's aside (System::setThreads): with 1,
  // llvmpipe rasterises and x264 encodes on the calling thread; with n > 1, llvmpipe starts n
  // rasteriser threads (GlRequest::threads), x264 n threads (VideoOptions::encoderThreads) and
  // the frames reach the encoder through a thread of their own; 0 leaves llvmpipe and x264 at
  // their defaults (one and 1.5 threads per CPU). With any value but 1, frames are drawn on a
  // thread of their own while the simulation steps to the next (docs/architecture.md, "The frame
  // loop"). The frames are the same for every value (an MP4's one difference is x264's note of
  // its thread count in the first frame).
  int threads = 0;
  VideoOptions video;  // the encoder's settings for file.mp4; its fps is set from `fps`
  PngOptions png;      // for file.png and dir/
};

// Every hook may be left empty.
struct RenderHooks {
  // Once, when the GL context is made, before the output is opened: what draws the frames.
  std::function<void(const GlInfo& gl)> glReady;
  // Once per frame, when the system has reached the frame's time and before it is drawn.
  std::function<void(const System& system)> onFrame;
  // Draws over each rendered frame before it is written.
  std::function<void(Image& frame, const System& system)> decorate;
  // After each frame of a video or sequence is handed to the writer: `done` of `total` frames.
  std::function<void(long done, long total, const System& system)> progress;
  // Asked before each frame of a video or sequence; true stops the render and removes what was
  // written. Called on this thread: a signal handler sets a flag, this reads it.
  std::function<bool()> shouldStop;
};

struct RenderSummary {
  long frames = 0;           // frames written; for a stopped render, those drawn before the stop
  long steps = 0;            // time steps taken
  double wallSeconds = 0.0;  // from opening the output to its being in place (or removed)
  bool stopped = false;      // shouldStop() asked for it: no output was written
};

// Renders `system`, stepped by `integrator` with time step `dt` from its current state, to
// `job.output`. Throws SimulationError (core/solver.hpp) when the simulation blows up,
// RenderError when the GL context cannot be made (before any output is opened) or draw,
// OutputError when the output cannot be written, std::invalid_argument for options out of range
// (render/render_options.hpp, render/gl_backend.hpp's validate, a video of odd size, an unknown
// preset, a frame range outside the video) or that the output's format does not take
// (checkFormatOptions, whose messages name the options as `particles render` spells them: --at
// for `at`, --frames, --background transparent for RenderOptions::transparentBackground), and
// whatever a hook throws.
RenderSummary renderSimulation(System& system, Integrator integrator, double dt, const RenderJob& job,
                               const RenderHooks& hooks = {});

}  // namespace particles::render
