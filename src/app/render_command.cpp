// `particles render SCENARIO -o OUT` (docs/physics.md §9, §12): simulate and draw frames off-screen,
// frames i = 0 … round(duration·fps) − 1 at t = i / fps, or the one frame at --at T, in OUT's
// format (render/output_formats.hpp, which checks the options that depend on it).
// The work is render::renderSimulation (render/render_simulation.hpp); this file reads the options,
// adds what only the program has (the --stats/--trace CSVs, the --hud text, progress, stopping on
// SIGINT/SIGTERM) as its hooks and reports the outcome. Outputs appear only when complete, and a
// signal or any failure removes them (exit 128 + signal, or the codes of exit_codes.hpp).
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <optional>
#include <string>
#include <utility>

#include "app/cli_support.hpp"
#include "app/csv_recorder.hpp"
#include "app/gl_options.hpp"
#include "app/job_record.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "plot/errors.hpp"
#include "plot/text_overlay.hpp"
#include "render/errors.hpp"
#include "render/frame_writer.hpp"
#include "render/output_formats.hpp"
#include "render/render_options.hpp"
#include "render/render_simulation.hpp"
#include "scenario/runner.hpp"

namespace particles::app {

namespace {

// SIGINT and SIGTERM stop a video render between frames: the handler sets a flag the frame loop
// polls (render/frame_writer.hpp), and the render removes what it wrote. A render can also be
// stuck where no loop polls: writing to a pipe or FIFO whose reader has stopped reading (a write
// restarts after the handler returns), or a filesystem that hangs. So the first signal also starts
// a grace period; a render that has not stopped by its end exits at once from the alarm's handler
// with the same code. Its output is an anonymous temporary that vanishes with the process (a named
// one, or a PNG sequence's staging folder, is left for the next run to remove, as after SIGKILL).
constexpr unsigned kStopGraceSeconds = 3;  // several frames of the largest renders we make; in the message

volatile std::sig_atomic_t stopSignal = 0;
extern "C" void onStopSignal(int signal) {
  if (stopSignal == 0) ::alarm(kStopGraceSeconds);
  stopSignal = signal;
}
extern "C" void onStopGraceOver(int) {
  static const char message[] =
      "particles: not stopped within 3 s of the signal (blocked writing an output?); ended at once\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(128 + stopSignal);
}

std::optional<render::Length> parseRadius(const std::string& text) {
  // "4px" (pixels, also a bare number) or "0.02m" (world units).
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    const std::string unit = text.substr(used);
    if (!(value > 0)) return std::nullopt;
    if (unit.empty() || unit == "px") return render::Length{value, render::Length::Unit::pixels};
    if (unit == "m") return render::Length{value, render::Length::Unit::world};
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// The --hud text: time, integrator, dt and energy, in the top-left corner of every frame.
auto hudOverlay(const scenario::Scenario& s, const render::RenderOptions& look) {
  plot::OverlayStyle style;
  style.darkBackground = look.themeName == render::ThemeName::dark;
  style.sizePx = std::clamp(look.height / 40.0, 10.0, 28.0);
  return [&sim = s.simulation, style](render::Image& frame, const System& system) {
    const EnergyReport e = system.energy();
    plot::drawTextOverlay(
        frame.rgba.data(), frame.width, frame.height,
        {fmt::format("t = {:.3f} s", system.time()),
         fmt::format("{}, dt = {} s", integratorName(sim.integrator), sim.dt),
         fmt::format("E = {:.4g} J (kinetic {:.3g}, potential {:.3g})", e.total(), e.kinetic, e.potential)},
        style);
  };
}

struct SignalGuard {
  SignalGuard() {
    stopSignal = 0;
    previousAlarm = std::signal(SIGALRM, onStopGraceOver);
    previousInt = std::signal(SIGINT, onStopSignal);
    previousTerm = std::signal(SIGTERM, onStopSignal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    // Once stopping, the grace period keeps running: it bounds what the command still does on its
    // way out too, such as closing a --trace FIFO whose last buffered lines wait for a reader.
    if (stopSignal != 0) return;
    ::alarm(0);
    std::signal(SIGALRM, previousAlarm);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;
  void (*previousInt)(int);
  void (*previousTerm)(int);
  void (*previousAlarm)(int);
};

// The look of the frames: the scenario's render block, then the command line. Throws InputError.
render::RenderOptions lookOf(const scenario::Scenario& s, const RenderCommandOptions& options) {
  render::RenderOptions look;
  look.width = s.render.width;
  look.height = s.render.height;
  if (!options.size.empty()) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(options.size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 ||
        h <= 0) {
      throw InputError(fmt::format("--size: expected WIDTHxHEIGHT in pixels, e.g. 1280x720, not '{}'", options.size));
    }
    look.width = w;
    look.height = h;
  }
  look.msaa = options.msaa;
  look.raster = options.raster == "tiles"       ? render::Raster::tiles
                : options.raster == "triangles" ? render::Raster::triangles
                                                : render::Raster::automatic;
  if (options.theme == "dark") {
    look.themeName = render::ThemeName::dark;
  } else if (options.theme == "light") {
    look.themeName = render::ThemeName::light;
  } else {
    throw InputError(fmt::format("--theme: expected dark or light, not '{}'", options.theme));
  }
  if (options.background == "transparent") {
    look.transparentBackground = true;
  } else if (options.background != "theme") {
    throw InputError(fmt::format("--background: expected theme or transparent, not '{}'", options.background));
  }
  if (!options.particleRadius.empty()) {
    const auto radius = parseRadius(options.particleRadius);
    if (!radius) {
      throw InputError(fmt::format("--particle-radius: expected a positive length like 4px or 0.02m, not '{}'",
                                   options.particleRadius));
    }
    look.particleRadius = *radius;
  }
  return look;
}

// Options the renderer or the writer refuse (a size out of range, an odd size for MP4, an unknown
// preset) are bad input.
template <class F>
auto refusedOptionsAreInputErrors(F&& f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

// --frames A:B (or A: for A to the end) against the video's `total` frames. Throws InputError.
std::pair<long, long> parseFrameRange(const std::string& text, long total) {
  const size_t colon = text.find(':');
  auto number = [&](const std::string& part) -> std::optional<long> {
    if (part.empty() || part.size() > 12 || part.find_first_not_of("0123456789") != std::string::npos) return {};
    return std::stol(part);
  };
  const auto first = colon == std::string::npos ? std::nullopt : number(text.substr(0, colon));
  const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  const auto end = rest.empty() ? std::optional<long>(total) : number(rest);
  if (!first || !end) {
    throw InputError(fmt::format("--frames: expected A:B (frames A … B−1) or A: (A to the end), not '{}'", text));
  }
  if (!(*first < *end && *end <= total)) {
    throw InputError(fmt::format("--frames {}: not a range of the video's {} frames (0:{})", text, total, total));
  }
  return {*first, *end};
}

}  // namespace

int renderCommand(const CommonOptions& common, const RenderCommandOptions& options) {
  scenario::Scenario s = loadScenario(common);
  const render::RenderOptions look = lookOf(s, options);
  if (options.fps && !(*options.fps >= 1 && *options.fps <= 1000)) {  // NaN fails both
    throw InputError(fmt::format("--fps: expected a whole number of frames per second from 1 to 1000, not {}",
                                 *options.fps));
  }
  if (!(options.keyint >= 1e-3 && options.keyint <= render::kMaxKeyintSeconds)) {  // NaN fails both
    throw InputError(fmt::format("--keyint: expected seconds from 0.001 to 3600 between keyframes, not {}",
                                 options.keyint));
  }
  if (options.at && !std::isfinite(*options.at)) {
    throw InputError(fmt::format("--at: expected a simulated time in seconds, not {}", *options.at));
  }
  const render::OutputFormat* outputFormat = nullptr;
  try {
    outputFormat = &render::outputFormatOf(options.output);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("-o {}: {}", options.output, e.what()));
  }
  const render::OutputFormat& format = *outputFormat;
  const double fpsValue = options.fps.value_or(render::defaultFps(format, s.render.fps));
  const int fps = int(std::lround(fpsValue));
  if (std::abs(fpsValue - fps) > 1e-9 || fps <= 0) {
    throw InputError(fmt::format("render needs a whole, positive number of frames per second, not {}", fpsValue));
  }
  refusedOptionsAreInputErrors([&] {
    render::checkFormatOptions(format, options.output,
                               {.transparentBackground = look.transparentBackground,
                                .hud = options.hud,
                                .crf = options.crf,
                                .fps = fps,
                                .at = options.at,
                                .frames = !options.frames.empty()});
  });
  if (look.transparentBackground && options.hud) {
    throw InputError("--hud draws an opaque panel over the frame: not with --background transparent");
  }
  if (options.at && (*options.at < 0 || *options.at > s.simulation.duration + 1e-9)) {
    throw InputError(fmt::format("--at {}: outside the simulation, 0 … {} s", *options.at, s.simulation.duration));
  }
  const long totalFrames = render::frameCount(s.simulation.duration, fps);
  std::optional<std::pair<long, long>> frameRange;
  if (!options.frames.empty()) frameRange = parseFrameRange(options.frames, totalFrames);
  if (options.pngLevel < 0 || options.pngLevel > 9) {
    throw InputError(fmt::format("--png-level: 0 (fastest) to 9 (smallest), not {}", options.pngLevel));
  }
  render::setLibavVerbose(options.verbose);
  refusedOptionsAreInputErrors([&] { render::validate(look); });
  const render::GlRequest gl = glRequestOf(options.gl, options.gpu);
  const auto recorder = CsvRecorder::open(s.system, fps, options.stats, options.trace, options.traceOnly);

  render::RenderJob job;
  job.output = options.output;
  job.at = options.at;
  job.duration = s.simulation.duration;
  job.fps = fps;
  job.frames = frameRange;
  job.camera = {s.render.viewCenter, s.render.viewHeight};
  job.look = look;
  job.gl = gl;
  job.video.crf = options.crf;
  job.video.keyintSeconds = options.keyint;
  job.video.preset = options.preset;
  job.png.compressionLevel = options.pngLevel;
  long framesReached = 0;  // frames whose time the simulation reached
  render::RenderHooks hooks;
  if (options.verbose) {
    hooks.glReady = [](const render::GlInfo& info) { fmt::print(stderr, "GL: {}\n", render::describe(info)); };
  }
  hooks.onFrame = [&](const System& system) {
    recorder->record(system);
    ++framesReached;
  };
  if (options.hud) {
    hooks.decorate = [hud = hudOverlay(s, look)](render::Image& frame, const System& system) {
      try {
        hud(frame, system);
      } catch (const plot::FigureError& e) {
        throw plot::FigureError(std::string("--hud: ") + e.what());
      }
    };
  }
  // A frame larger than the GL draws is bad input: the size's, named as it was given.
  const std::string sizeSource = options.size.empty()
                                     ? fmt::format("the scenario's render size {}x{}", look.width, look.height)
                                     : "--size " + options.size;
  const auto run = [&] {
    try {
      return render::renderSimulation(s.system, s.simulation.integrator, s.simulation.dt, job, hooks);
    } catch (const render::FrameSizeError& e) {
      throw InputError(fmt::format("{}: {}", sizeSource, e.what()));
    }
  };

  if (format.oneFrameAt) {
    refusedOptionsAreInputErrors(run);
    recorder->commit();
    if (!common.quiet) {
      fmt::print("{}: frame at t = {:.6g} s ({}×{}) → {}\n", s.name, s.system.time(), look.width, look.height,
                 options.output);
    }
    return kOk;
  }

  const long frames = frameRange ? frameRange->second - frameRange->first : totalFrames;
  Progress progress(!common.quiet, "frames");
  hooks.progress = [&](long done, long total, const System& system) {
    progress.update(done, total, fmt::format("t = {:.2f} s", system.time()));
  };
  SignalGuard signals;
  hooks.shouldStop = [] { return stopSignal != 0; };
  render::RenderSummary summary;
  try {
    summary = refusedOptionsAreInputErrors(run);
  } catch (const SimulationError& e) {
    throw SimulationFailure(fmt::format("{} (at frame {} of {}; no output written)", e.what(), framesReached, frames));
  }
  if (summary.stopped) {
    progress.finish();
    fmt::print(stderr, "{}: interrupted at frame {} of {}; no output written\n", common.scenario, summary.frames,
               frames);
    return 128 + int(stopSignal);
  }
  recorder->commit();
  progress.finish();
  reportHeadline("frames", double(frames));
  reportHeadline("wall_seconds", summary.wallSeconds);
  if (!common.quiet) {
    const double wall = summary.wallSeconds;
    fmt::print("{}: {} frames ({}×{}, {} fps, {:.6g} s) in {:.2f} s, {:.1f} frames/s, {} steps of {} s ({}) → {}\n",
               s.name, frames, look.width, look.height, fps, double(frames) / fps, wall, double(frames) / wall,
               summary.steps, s.simulation.dt, integratorName(s.simulation.integrator), options.output);
  }
  return kOk;
}

}  // namespace particles::app
