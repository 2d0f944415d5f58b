// `particles render`: see render_command.hpp. The work is render::renderSimulation
// (render/video/render_simulation.hpp); this file reads the options, adds what only the program has (the
// --stats/--trace CSVs, the --hud text, progress, stopping on SIGINT/SIGTERM: stop_signal.hpp) as
// its hooks and reports the outcome.
#include "app/render_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "input/printable_text.hpp"
#include "app/cli_support.hpp"
#include "app/csv_recorder.hpp"
#include "app/gl_options.hpp"
#include "app/job_record.hpp"
#include "app/stop_signal.hpp"
#include "app/thread_count.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "plot/errors.hpp"
#include "plot/text_overlay.hpp"
#include "render/errors.hpp"
#include "render/video/frame_writer.hpp"
#include "render/gl_backend.hpp"
#include "render/video/output_formats.hpp"
#include "render/render_options.hpp"
#include "render/video/render_simulation.hpp"
#include "scenario/runner.hpp"

namespace particles::app {

namespace {

// The shortest --keyint, s: a keyframe every millisecond is already every frame.
constexpr double kMinKeyintSeconds = 1e-3;
// The largest --png-level: zlib's best compression (render/png_io.hpp).
constexpr int kMaxPngLevel = 9;

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

// The look of the frames: the scenario's render block, then the command line, each option as its
// row of render::lookOptions() reads it. Throws InputError.
render::RenderOptions lookOf(const scenario::Scenario& s, const RenderCommandOptions& options) {
  render::RenderOptions look;
  look.width = s.render.width;
  look.height = s.render.height;
  auto given = [](const std::string& text) { return text.empty() ? std::nullopt : std::optional(text); };
  // In the order their mistakes are told; --raster and --msaa CLI11 checked already.
  const std::pair<std::string_view, std::optional<std::string>> words[] = {
      {"--size", given(options.size)},      {"--msaa", std::to_string(options.msaa)},
      {"--raster", options.raster},         {"--theme", options.theme},
      {"--background", options.background}, {"--particle-radius", given(options.particleRadius)}};
  for (const auto& [flag, text] : words) {
    const render::LookOption& option = render::lookOption(flag);
    if (text && !option.read(*text, look)) {
      throw InputError(fmt::format("{}: expected {}, not {}", flag, option.expected, input::quotedValue(*text)));
    }
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
  // A frame number, or -1 for what is not one. (Not std::optional: GCC 12 at -O3 takes the
  // optionals' values for maybe-uninitialized, a false positive.)
  auto number = [&](const std::string& part) -> long {
    if (part.empty() || part.size() > 12 || part.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stol(part);
  };
  const long first = colon == std::string::npos ? -1 : number(text.substr(0, colon));
  const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  const long end = rest.empty() ? total : number(rest);
  if (first < 0 || end < 0) {
    throw InputError(
        fmt::format("--frames: expected A:B (frames A … B−1) or A: (A to the end), not {}", input::quotedValue(text)));
  }
  if (!(first < end && end <= total)) {
    throw InputError(fmt::format("--frames {}: not a range of the video's {} frames (0:{})", text, total, total));
  }
  return {first, end};
}

// --fps, --keyint and --at as numbers, before the output says what they mean for it.
void checkNumbers(const RenderCommandOptions& options) {
  if (options.fps && !(*options.fps >= render::kMinFps && *options.fps <= render::kMaxFps)) {  // NaN fails both
    throw InputError(fmt::format("--fps: expected a whole number of frames per second from {} to {}, not {}",
                                 render::kMinFps, render::kMaxFps, *options.fps));
  }
  if (!(options.keyint >= kMinKeyintSeconds && options.keyint <= render::kMaxKeyintSeconds)) {  // NaN fails both
    throw InputError(fmt::format("--keyint: expected seconds from {} to {} between keyframes, not {}",
                                 kMinKeyintSeconds, render::kMaxKeyintSeconds, options.keyint));
  }
  if (options.at && !std::isfinite(*options.at)) {
    throw InputError(fmt::format("--at: expected a simulated time in seconds, not {}", *options.at));
  }
}

// The row of render/video/output_formats.hpp that -o names.
const render::OutputFormat& outputFormatOf(const RenderCommandOptions& options) {
  try {
    return render::outputFormatOf(options.output);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("-o {}: {}", options.output, e.what()));
  }
}

// The frame rate: --fps, else the scenario's (capped where the format caps it, render::defaultFps).
int framesPerSecondOf(const scenario::Scenario& s, const RenderCommandOptions& options,
                      const render::OutputFormat& format) {
  const double fpsValue = options.fps.value_or(render::defaultFps(format, s.render.fps));
  const int fps = int(std::lround(fpsValue));
  if (std::abs(fpsValue - fps) > 1e-9 || fps <= 0) {
    throw InputError(fmt::format("render needs a whole, positive number of frames per second, not {}", fpsValue));
  }
  return fps;
}

// The options whose meaning depends on the output's format (alpha, --crf, the frame rate's cap,
// --at, --frames, --hud over a transparent background), by its row.
void checkFormatOptions(const RenderCommandOptions& options, const render::RenderOptions& look,
                        const render::OutputFormat& format, int fps) {
  refusedOptionsAreInputErrors([&] {
    render::checkFormatOptions(format, options.output,
                               {.transparentBackground = look.transparentBackground,
                                .hud = options.hud,
                                .crf = options.crf,
                                .fps = fps,
                                .at = options.at,
                                .frames = !options.frames.empty()});
  });
}

// --at inside the simulation (whether the format takes it is checkFormatOptions's).
void checkAtTime(const scenario::Scenario& s, const RenderCommandOptions& options) {
  if (options.at && (*options.at < 0 || *options.at > s.simulation.duration + 1e-9)) {
    throw InputError(fmt::format("--at {}: outside the simulation, 0 … {} s", *options.at, s.simulation.duration));
  }
}

// --frames against the video's `totalFrames`; none: every frame.
std::optional<std::pair<long, long>> frameRangeOf(const RenderCommandOptions& options, long totalFrames) {
  if (options.frames.empty()) return std::nullopt;
  return parseFrameRange(options.frames, totalFrames);
}

void checkPngLevel(const RenderCommandOptions& options) {
  if (options.pngLevel < 0 || options.pngLevel > kMaxPngLevel) {
    throw InputError(fmt::format("--png-level: 0 (fastest) to {} (smallest), not {}", kMaxPngLevel, options.pngLevel));
  }
}

// Adds --stats/--trace, --verbose's GL and raster lines and --hud to the render's hooks.
void addProgramHooks(render::RenderHooks& hooks, const scenario::Scenario& s, const RenderCommandOptions& options,
                     const render::RenderOptions& look, CsvRecorder& recorder, long& framesReached) {
  if (options.verbose) {
    const render::Raster taken = render::rasterTaken(look.raster, options.gpu);
    hooks.glReady = [taken, asked = look.raster](const render::GlInfo& info) {
      fmt::print(stderr, "GL: {}\n", render::describe(info));
      fmt::print(stderr, "raster: {}{}\n", render::rasterNameOf(taken),
                 taken == render::Raster::cpu ? " (the program's threads, not GL)"
                 : asked == render::Raster::automatic ? " (auto)" : "");
    };
  }
  hooks.onFrame = [&](const System& system) {
    recorder.record(system);
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
}

int renderCommand(const RenderCommandOptions& options) {
  const CommonOptions& common = options.common;
  scenario::Scenario s = loadScenario(common);
  const render::RenderOptions look = lookOf(s, options);
  checkNumbers(options);
  const render::OutputFormat& format = outputFormatOf(options);
  const int fps = framesPerSecondOf(s, options, format);
  checkFormatOptions(options, look, format, fps);
  checkAtTime(s, options);
  const long totalFrames = render::frameCount(s.simulation.duration, fps);
  const std::optional<std::pair<long, long>> frameRange = frameRangeOf(options, totalFrames);
  checkPngLevel(options);
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
  job.style = s.style;
  job.view = s.render.view;
  job.gl = gl;
  // --threads (or PARTICLES_THREADS) is the whole command's cap: the simulation's (loadScenario),
  // llvmpipe's and the encoder's. Without one, the simulation takes the CPUs and llvmpipe and x264
  // choose their own counts (x264 about 1.5 threads per CPU, its frame threads overlapping), which
  // encode faster than x264 held to one thread per CPU (bench/README.md).
  job.threads = threadCountGiven(common.threads) ? threadCountOf(common.threads) : 0;
  job.video.crf = options.crf;
  job.video.keyintSeconds = options.keyint;
  job.video.preset = options.preset;
  job.png.compressionLevel = options.pngLevel;
  long framesReached = 0;  // frames whose time the simulation reached
  render::RenderHooks hooks;
  addProgramHooks(hooks, s, options, look, *recorder, framesReached);
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
  StopSignals signals(StopMode::pollWithGrace);
  hooks.shouldStop = [] { return stopSignal() != 0; };
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
    return 128 + stopSignal();
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

void addRenderOptions(CLI::App& command, RenderCommandOptions& render) {
  CLI::App* renderCmd = &command;
  addCommonOptions(*renderCmd, render.common);
  addStyleOption(*renderCmd, render.common);
  renderCmd->add_option("-o,--output", render.output, render::outputHelp())->required();
  renderCmd->add_option("--at", render.at, render::atHelp());
  renderCmd->add_option("--frames", render.frames, render::framesHelp());
  renderCmd->add_option("--size", render.size, "Frame size WxH in px (default: the scenario's render.size)");
  renderCmd->add_option("--fps", render.fps, render::fpsHelp());
  renderCmd->add_option("--msaa", render.msaa, "Anti-aliasing samples per pixel: " + render::sampleCountsText())
      ->check(CLI::IsMember(render::kSampleCounts))
      ->capture_default_str();
  renderCmd
      ->add_option("--raster", render.raster,
                   fmt::format("How shapes become pixels: cpu (sorted into screen tiles and composited by "
                               "particles' own threads, no GL), triangles (one GL primitive each), tiles (the same "
                               "tiles drawn by one GL pass), resident (springs and particles kept in GL's buffers, "
                               "only positions sent each frame; the GPU's path) or auto (with --gpu resident, and "
                               "tiles from {} shapes where its buffers cannot hold the scene; else cpu)",
                               render::kTilesFromShapes))
      ->check(CLI::IsMember(render::rasterNames()))
      ->capture_default_str();
  renderCmd->add_option("--theme", render.theme, "dark (screens) or light (printed reports)")->capture_default_str();
  renderCmd->add_option("--background", render.background, render::backgroundHelp())->capture_default_str();
  renderCmd->add_option("--particle-radius", render.particleRadius,
                        "Particle disc radius: 4px (pixels) or 0.02m (world)");
  renderCmd->add_option("--crf", render.crf, render::crfHelp());
  renderCmd
      ->add_option("--keyint", render.keyint,
                   "Longest time between keyframes, s (MP4, WebM): players seek to a keyframe, so shorter seeks "
                   "faster")
      ->check(CLI::Range(kMinKeyintSeconds, render::kMaxKeyintSeconds))
      ->capture_default_str();
  // The presets' range as x264 lists it, fastest to veryslow (kX264Presets: not placebo, the last).
  renderCmd
      ->add_option("--preset", render.preset,
                   fmt::format("x264 preset (MP4): {} … {}", render::kX264Presets.front(),
                               render::kX264Presets[render::kX264Presets.size() - 2]))
      ->capture_default_str();
  renderCmd->add_option("--png-level", render.pngLevel, fmt::format("PNG compression level 0 … {}", kMaxPngLevel))
      ->capture_default_str();
  renderCmd->add_flag("--verbose", render.verbose, "Name the GL backend and renderer; show libav/x264's own log");
  renderCmd
      ->add_option("--gl", render.gl,
                   fmt::format("GL backend of the GL raster paths (the cpu path uses none): auto (EGL, else OSMesa), "
                               "egl or osmesa (default: ${}, else auto)",
                               kGlEnvironmentVariable))
      ->check(CLI::IsMember(render::glBackendNames()));
  renderCmd->add_flag("--gpu", render.gpu,
                      "Draw on a GPU through EGL instead of llvmpipe on the CPU (frames may differ from the goldens)");
  renderCmd->add_flag("--hud", render.hud,
                      "Draw time, integrator, dt and energy in the top-left corner of every frame");
  renderCmd->add_option("--stats", render.stats,
                        "Write t,kinetic,potential,total,constraint_error,penetration per frame");
  auto* renderTrace = renderCmd->add_option("--trace", render.trace, "Write t,name,x,y,vx,vy,angle,omega per frame");
  renderCmd->add_option("--trace-only", render.traceOnly, "Trace only these objects (comma-separated names)")
      ->delimiter(',')
      ->needs(renderTrace);
  const render::FpsCap& gifCap = *render::outputFormat(render::OutputKind::gif).fpsCap;
  renderCmd->footer(fmt::format(
      "Frame i shows t = i / fps; a video has round(duration · fps) frames.\n"
      "{}\n"
      "A GIF has one palette made for the whole video, at most {} fps ({} unless --fps says), delays\n"
      "rounded to whole centiseconds.\n"
      "Which formats take --background transparent, --frames, --crf and --at: their help above.\n"
      "Outputs appear only when complete.\n"
      "Frames are drawn by Mesa's llvmpipe on the CPU, the same bytes through EGL or OSMesa (with\n"
      "Mesa 25, but for samples lying exactly on an edge);\n"
      "'particles --version' names the backend and renderer.\n"
      "Examples:\n"
      "  particles render scenarios/cloth.yaml -o cloth.mp4\n"
      "  particles render scenarios/soft_body.yaml -o frames/ --size 640x360 --fps 30\n"
      "  particles render scenarios/cloth.yaml -o fig.png --at 2.5 --theme light --size 1600x1200\n"
      "  particles render scenarios/soft_body.yaml -o man.mp4 --hud   # time, integrator, dt, energy on every frame\n"
      "  particles render scenarios/rigid_chain.yaml -o chain.mp4 --crf 23 --preset veryfast --quiet\n"
      "  particles render scenarios/cloth.yaml -o cloth.gif --size 480x270   # 30 fps, a palette for the video\n"
      "  particles render scenarios/cloth.yaml -o cloth.webm --background transparent   # VP9 with alpha\n"
      "  PARTICLES_GL=osmesa particles render scenarios/cloth.yaml -o cloth.mp4   # where EGL will not start\n",
      render::frameSizeHelp(), gifCap.most, gifCap.byDefault));
  addJobOptions(*renderCmd, render.job);
}

CommandFiles renderFiles(const RenderCommandOptions& render) {
  return {{{"-o", render.output}, {"--stats", render.stats}, {"--trace", render.trace}},
          {{"the scenario", render.common.scenario}, {"--style", render.common.style}}};
}

}  // namespace

const CommandDescriptor<RenderCommandOptions> kRenderCommand = {
    .name = "render",
    .summary = "Simulate and draw the scenario off-screen to a video, PNG frames or one PNG (formats: render --help)",
    .addOptions = addRenderOptions,
    .run = renderCommand,
    .files = renderFiles,
    .common = &RenderCommandOptions::common,
    .job = &RenderCommandOptions::job,
};

}  // namespace particles::app
