// `particles render SCENARIO -o OUT` (DESIGN §9, §12): simulate and draw frames off-screen.
//   OUT.mp4   H.264 video, frames i = 0 … round(duration·fps) − 1 at t = i / fps
//   OUT/      the same frames as frame_000000.png …
//   OUT.png   one frame at --at T, for report figures
// A frame shows the state after the last time step at or before its time (to rounding), so with
// a dt that divides 1/fps every frame is exact. Encoding runs on the writer's own thread; outputs
// appear only when complete, and SIGINT/SIGTERM or any failure removes them (exit 128 + signal,
// or the codes of commands.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <optional>

#include "app/cli_support.hpp"
#include "plot/errors.hpp"
#include "plot/text_overlay.hpp"
#include "app/csv_recorder.hpp"
#include "render/errors.hpp"
#include "render/frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/renderer.hpp"
#include "core/drawing.hpp"
#include "core/system.hpp"
#include "scenario/runner.hpp"

namespace particles::app {

namespace {

volatile std::sig_atomic_t stopSignal = 0;
extern "C" void onStopSignal(int signal) { stopSignal = signal; }

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

// The frame for the current state, with the --hud text drawn over it when asked for.
class FramePainter {
 public:
  FramePainter(render::Renderer& renderer, const render::Camera& camera, const scenario::Scenario& s, bool hud,
               bool darkTheme)
      : renderer_(renderer), camera_(camera), scenario_(s), hud_(hud) {
    style_.darkBackground = darkTheme;
    style_.sizePx = std::clamp(renderer.options().height / 40.0, 10.0, 28.0);
  }
  const render::Image& paint(const System& system) {
    const render::Image& image = renderer_.render(system.draw(), camera_);
    if (!hud_) return image;
    framed_ = image;
    const EnergyReport e = system.energy();
    const auto& sim = scenario_.simulation;
    plot::drawTextOverlay(framed_.rgba.data(), framed_.width, framed_.height,
                          {fmt::format("t = {:.3f} s", system.time()),
                           fmt::format("{}, dt = {} s", integratorName(sim.integrator), sim.dt),
                           fmt::format("E = {:.4g} J (kinetic {:.3g}, potential {:.3g})", e.total(), e.kinetic,
                                       e.potential)},
                          style_);
    return framed_;
  }

 private:
  render::Renderer& renderer_;
  render::Camera camera_;
  const scenario::Scenario& scenario_;
  bool hud_;
  plot::OverlayStyle style_;
  render::Image framed_;
};

struct SignalGuard {
  SignalGuard() {
    stopSignal = 0;
    previousInt = std::signal(SIGINT, onStopSignal);
    previousTerm = std::signal(SIGTERM, onStopSignal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
  }
  void (*previousInt)(int);
  void (*previousTerm)(int);
};

}  // namespace

int renderCommand(const CommonOptions& common, const RenderCommandOptions& options) {
  auto s = loadScenario(common);
  if (!s) return kBadInput;

  // Settings: the scenario's render block, then the command line.
  render::RenderOptions look;
  look.width = s->render.width;
  look.height = s->render.height;
  if (!options.size.empty()) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(options.size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 ||
        h <= 0) {
      fmt::print(stderr, "error: --size: expected WIDTHxHEIGHT in pixels, e.g. 1280x720, not '{}'\n", options.size);
      return kBadInput;
    }
    look.width = w;
    look.height = h;
  }
  look.msaa = options.msaa;
  if (options.theme == "dark") {
    look.themeName = render::ThemeName::dark;
  } else if (options.theme == "light") {
    look.themeName = render::ThemeName::light;
  } else {
    fmt::print(stderr, "error: --theme: expected dark or light, not '{}'\n", options.theme);
    return kBadInput;
  }
  if (!options.particleRadius.empty()) {
    const auto radius = parseRadius(options.particleRadius);
    if (!radius) {
      fmt::print(stderr, "error: --particle-radius: expected a positive length like 4px or 0.02m, not '{}'\n",
                 options.particleRadius);
      return kBadInput;
    }
    look.particleRadius = *radius;
  }
  const double fpsValue = options.fps > 0 ? options.fps : s->render.fps;
  const int fps = int(std::lround(fpsValue));
  if (std::abs(fpsValue - fps) > 1e-9 || fps <= 0) {
    fmt::print(stderr, "error: render needs a whole, positive number of frames per second, not {}\n", fpsValue);
    return kBadInput;
  }
  const render::Camera camera{s->render.viewCenter, s->render.viewHeight};

  render::OutputKind kind;
  try {
    kind = render::outputKind(options.output);
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "error: -o {}: {}\n", options.output, e.what());
    return kBadInput;
  }
  if (kind == render::OutputKind::png && !options.at) {
    fmt::print(stderr, "error: -o {}: a single PNG needs --at T, the simulated time to draw (or use -o DIR/ for "
                       "every frame)\n", options.output);
    return kBadInput;
  }
  if (kind != render::OutputKind::png && options.at) {
    fmt::print(stderr, "error: --at draws one frame: give -o FILE.png\n");
    return kBadInput;
  }
  if (options.at && (*options.at < 0 || *options.at > s->simulation.duration + 1e-9)) {
    fmt::print(stderr, "error: --at {}: outside the simulation, 0 … {} s\n", *options.at, s->simulation.duration);
    return kBadInput;
  }
  if (options.pngLevel < 0 || options.pngLevel > 9) {
    fmt::print(stderr, "error: --png-level: 0 (fastest) to 9 (smallest), not {}\n", options.pngLevel);
    return kBadInput;
  }
  render::setLibavVerbose(options.verbose);

  try {
    std::optional<render::Renderer> renderer;
    try {
      renderer.emplace(look);
    } catch (const std::invalid_argument& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return kBadInput;
    }
    auto recorder = CsvRecorder::open(s->system, options.stats, options.trace, options.traceOnly);
    if (!recorder) return kBadInput;
    Stepper stepper(s->system, s->simulation.integrator, s->simulation.dt);
    FramePainter painter(*renderer, camera, *s, options.hud, look.themeName == render::ThemeName::dark);
    const auto start = std::chrono::steady_clock::now();

    if (kind == render::OutputKind::png) {
      try {
        stepper.advanceTo(*options.at);
      } catch (const SimulationError& e) {
        fmt::print(stderr, "{}: error: {}\n", common.scenario, e.what());
        return kSimulationFailed;
      }
      recorder->record(s->system);
      render::writePng(options.output, painter.paint(s->system), render::PngOptions{options.pngLevel});
      recorder->commit();
      if (!common.quiet) {
        fmt::print("{}: frame at t = {:.6g} s ({}×{}) → {}\n", s->name, s->system.time(), look.width, look.height,
                   options.output);
      }
      return kOk;
    }

    render::FrameWriterOptions out;
    out.width = look.width;
    out.height = look.height;
    out.video.fps = fps;
    out.video.crf = options.crf;
    out.video.preset = options.preset;
    out.png.compressionLevel = options.pngLevel;
    std::unique_ptr<render::FrameWriter> writer;
    try {
      writer = render::openFrameWriter(options.output, out);
    } catch (const std::invalid_argument& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return kBadInput;
    }

    const long frames = render::frameCount(s->simulation.duration, fps);
    Progress progress(!common.quiet, "frames");
    SignalGuard signals;
    for (long i = 0; i < frames; ++i) {
      if (stopSignal != 0) {
        progress.finish();
        writer->abort();
        fmt::print(stderr, "{}: interrupted at frame {} of {}; no output written\n", common.scenario, i, frames);
        return 128 + int(stopSignal);
      }
      try {
        stepper.advanceTo(double(i) / fps);
      } catch (const SimulationError& e) {
        progress.finish();
        writer->abort();
        fmt::print(stderr, "{}: error: {} (at frame {} of {}; no output written)\n", common.scenario, e.what(), i,
                   frames);
        return kSimulationFailed;
      }
      recorder->record(s->system);
      writer->write(painter.paint(s->system));
      progress.update(i + 1, frames, fmt::format("t = {:.2f} s", s->system.time()));
    }
    writer->finish();
    recorder->commit();
    progress.finish();
    if (!common.quiet) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print("{}: {} frames ({}×{}, {} fps, {:.6g} s) in {:.2f} s, {:.1f} frames/s, {} steps of {} s ({}) → {}\n",
                 s->name, frames, look.width, look.height, fps, double(frames) / fps, wall, double(frames) / wall,
                 stepper.steps(), s->simulation.dt, integratorName(s->simulation.integrator), options.output);
    }
    return kOk;
  } catch (const render::RenderError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kOutputFailed;
  } catch (const output::OutputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kOutputFailed;
  } catch (const plot::FigureError& e) {
    fmt::print(stderr, "error: --hud: {}\n", e.what());
    return kOutputFailed;
  }
}

}  // namespace particles::app
