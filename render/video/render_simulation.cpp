#include "render/video/render_simulation.hpp"

#include <chrono>
#include <deque>
#include <optional>
#include <vector>
#include <stdexcept>
#include <string>

#include "core/solver.hpp"
#include "plot/frame_annotations.hpp"
#include "render/frame_memory.hpp"
#include "render/video/frame_pipeline.hpp"
#include "render/renderer.hpp"
#include "render/styled_run.hpp"

namespace particles::render {

namespace {

// The job's GL request, with the job's threads for llvmpipe.
GlRequest rasterRequestOf(const RenderJob& job) {
  GlRequest gl = job.gl;
  if (job.threads > 0) gl.threads = job.threads;
  return gl;
}

// A frame ready to draw: the state as geometry, where the camera is, and the style resolved.
struct FrameToDraw {
  Drawing drawing;
  Camera camera;
  FrameLook look;
  std::optional<plot::FrameAnnotations> notes;  // the text and bars over it, if the style has any
};

// The renderer's frame for a drawing, with the style's text over it and then the decorate hook's.
class FramePainter {
 public:
  // oneFrame: the output is one frame, its own pass (StyledRun::fitTo).
  FramePainter(const RenderJob& job, StyledRun& styled, const RenderHooks& hooks, bool oneFrame)
      : renderer_(styled.look(), rasterRequestOf(job)),
        styled_(styled),
        decorate_(hooks.decorate),
        oneFrame_(oneFrame) {
    if (hooks.glReady) hooks.glReady(renderer_.gl());
    // The copy drawn over, allocated with the frame (render/frame_memory.hpp) and reused.
    if (decorate_ || styled.annotates()) {
      buffers_.annotated = allocateImage(job.look.width, job.look.height, "the frame's decorated copy");
    }
  }
  // The system's state now (at time t), as `frame` (filled here) shows it: its shapes built on the
  // system's threads (Renderer::render), which are idle while it is drawn.
  void prepare(System& system, FrameToDraw& frame) {
    styled_.drawFrame(system, frame.drawing, SpringDetail::topology);  // every raster path draws springs by index
    if (oneFrame_) styled_.fitTo(frame.drawing);
    frame.camera = styled_.camera(system.time());
    styled_.resolve(frame.drawing, frame.camera, frame.look);
    if (styled_.annotates()) frame.notes = styled_.annotations(frame.drawing, frame.camera);
  }
  const Image& paint(System& system) {
    const Image& image = drawStyledFrame(system, styled_, renderer_, buffers_, oneFrame_, system.pool());
    if (!decorate_) return image;
    if (&image != &buffers_.annotated) buffers_.annotated = image;  // the renderer's image is reused
    decorate_(buffers_.annotated, system);
    return buffers_.annotated;
  }
  // A frame prepared earlier, without the decorate hook (which needs the system at the frame's
  // time), in two steps (Renderer::submit, collect).
  void submit(const FrameToDraw& frame, WorkerPool* pool) {
    renderer_.submit(frame.drawing, frame.camera, pool, lookOf(frame));
  }
  const Image& collect() { return renderer_.collect(); }
  // The image with `notes` drawn over a copy of it (the renderer's image is reused for the next frame).
  const Image& annotate(const Image& image, const std::optional<plot::FrameAnnotations>& notes) {
    if (!notes) return image;
    buffers_.annotated = image;
    plot::drawFrameAnnotations(buffers_.annotated.rgba.data(), buffers_.annotated.width, buffers_.annotated.height,
                               *notes);
    return buffers_.annotated;
  }
  bool readsAhead() const { return renderer_.readsAhead(); }
  void releaseFromThread() { renderer_.releaseFromThread(); }

 private:
  static const FrameLook* lookOf(const FrameToDraw& frame) { return frame.look.empty() ? nullptr : &frame.look; }

  Renderer renderer_;
  StyledRun& styled_;
  StyledFrameBuffers buffers_;  // the frame's, its storage reused from frame to frame
  const std::function<void(Image&, const System&)>& decorate_;
  bool oneFrame_;
};

// The frame loop overlapped: while this thread steps the simulation to frame k + 1's
// time, another draws frame k (its shapes built on a pool of its own, GL, the read-back) and hands
// it to the writer, whose own thread encodes frame k − 1. Where the renderer reads ahead (EGL:
// two pixel-pack buffers), the drawing thread starts frame k's read-back and hands the writer
// frame k − 1's instead, so that GL copies frame k out while the CPU converts frame k − 1 and
// builds frame k + 1; finish() collects the last. What passes between the two is the
// frame's Drawing, a snapshot of the state in plain geometry (core/drawing.hpp), with its camera and
// resolved style, in one of three reused slots (FramePipeline::slotCount(1): one being drawn, one
// waiting, one being filled), so memory stays bounded. Frames are drawn in order, each from its own
// state: the same images as the plain loop, byte for byte. Not for a decorated frame, whose hook
// reads the system itself.
class OverlappedFrames {
 public:
  OverlappedFrames(FramePainter& painter, FrameWriter& writer, int threads)
      : painter_(painter),
        writer_(writer),
        pool_(threads),
        pipeline_(1, nullptr, [this](std::size_t slot, long) {
          // The GL context is this thread's for the frame: taken in Renderer::render, given back
          // after, so that the owning thread can release it at the end.
          struct Release {
            FramePainter& painter;
            ~Release() { painter.releaseFromThread(); }
          } release{painter_};
          painter_.submit(frames_[slot], &pool_);
          notes_.push_back(frames_[slot].notes);
          if (held_ || !painter_.readsAhead()) writeCollected();
          held_ = painter_.readsAhead();  // this frame waits in its buffer for the next one
        }) {}

  void push(System& system) {
    pipeline_.pushWith([&](std::size_t slot) { painter_.prepare(system, frames_[slot]); });
  }
  // Rethrows a failed frame's error; else writes the frame still being read back, on this thread
  // (the drawing thread has given the GL context back).
  void finish() {
    pipeline_.close();
    if (!held_) return;
    held_ = false;
    writeCollected();
    painter_.releaseFromThread();
  }
  void cancel() noexcept { pipeline_.cancel(); }

 private:
  // The oldest frame submitted, with its notes, to the writer.
  void writeCollected() {
    const Image& image = painter_.collect();
    writer_.write(painter_.annotate(image, notes_.front()));
    notes_.pop_front();
  }

  FramePainter& painter_;
  FrameWriter& writer_;
  std::vector<FrameToDraw> frames_ = std::vector<FrameToDraw>(FramePipeline::slotCount(1));
  std::deque<std::optional<plot::FrameAnnotations>> notes_;  // of the frames submitted, not yet written
  WorkerPool pool_;  // the drawing thread's: the system's belongs to the stepping thread
  bool held_ = false;  // a frame read ahead and not yet written (the drawing thread's, then finish's)
  FramePipeline pipeline_;  // last: its worker uses the members above
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The times of the frames the output shows, all of them (a split render's too: its style and
// camera are the whole render's): the one frame's, or frame k's at k / fps.
std::vector<double> frameTimesOf(const RenderJob& job, const OutputFormat& format, long total) {
  if (format.oneFrameAt) return {*job.at};
  std::vector<double> times(static_cast<size_t>(total));
  for (long k = 0; k < total; ++k) times[size_t(k)] = double(k) / job.fps;
  return times;
}

// The frames of a video or sequence, first … end − 1, through `writer`.
void renderFrames(System& system, const RenderJob& job, const RenderHooks& hooks, FramePainter& painter,
                  const std::function<void(double)>& reached, long first, long end, RenderSummary& summary) {
  FrameWriterOptions out;
  out.width = job.look.width;
  out.height = job.look.height;
  out.video = job.video;
  out.video.fps = job.fps;
  out.png = job.png;
  out.alpha = job.look.transparentBackground;
  out.firstIndex = first;
  out.wholeSequence = !job.frames;
  if (job.threads > 0) out.video.encoderThreads = job.threads;
  if (job.threads == 1) out.queueFrames = 0;  // no encoder thread
  const long frames = end - first;
  // Removes everything it wrote if an exception leaves this function before finish().
  const std::unique_ptr<FrameWriter> writer = openFrameWriter(job.output, out);
  // Declared after the writer and the painter, which it uses: stopped (cancel) before they go.
  std::optional<OverlappedFrames> overlapped;
  if (job.threads != 1 && !hooks.decorate) {
    painter.releaseFromThread();  // the drawing thread takes the GL context from here on
    overlapped.emplace(painter, *writer, job.threads > 0 ? job.threads : system.threads());
  }
  for (long i = 0; i < frames; ++i) {
    if (hooks.shouldStop && hooks.shouldStop()) {
      if (overlapped) overlapped->cancel();
      writer->abort();
      summary.frames = i;
      summary.stopped = true;
      return;
    }
    // The same stepper reaches frame k's time by the same steps whether or not the frames before
    // it were drawn: the state is the whole render's.
    reached(double(first + i) / job.fps);
    if (overlapped) {
      overlapped->push(system);
    } else {
      writer->write(painter.paint(system));
    }
    if (hooks.progress) hooks.progress(i + 1, frames, system);
  }
  if (overlapped) overlapped->finish();
  writer->finish();
  summary.frames = frames;
}

}  // namespace

RenderSummary renderSimulation(System& system, Integrator integrator, double dt, const RenderJob& job,
                               const RenderHooks& hooks) {
  if (!(dt > 0.0)) throw std::invalid_argument("time step must be positive");
  const OutputFormat& format = outputFormatOf(job.output);
  checkFormatOptions(format, job.output,
                     {.transparentBackground = job.look.transparentBackground,
                      .crf = job.video.crf,
                      .fps = job.fps,
                      .at = job.at,
                      .frames = job.frames.has_value()});
  const long total = format.oneFrameAt ? 1 : frameCount(job.duration, job.fps);
  const long first = job.frames ? job.frames->first : 0;
  const long end = job.frames ? job.frames->second : total;
  if (!(0 <= first && first < end && end <= total)) {
    throw std::invalid_argument("frames " + std::to_string(first) + ":" + std::to_string(end) +
                                " are not a range of the video's " + std::to_string(total) +
                                " frames (0:" + std::to_string(total) + ")");
  }
  const std::vector<double> times = frameTimesOf(job, format, total);
  const double lastTime = std::max(times.empty() ? 0.0 : times.back() - system.time(), 0.0);
  StyledRun styled(job.style, job.view, job.camera, job.look, dt, long(std::ceil(lastTime / dt)) + 1);
  FramePainter painter(job, styled, hooks, format.oneFrameAt);
  const auto start = std::chrono::steady_clock::now();
  // A video's or sequence's pass; a one-frame output is fitted to its frame (FramePainter::prepare).
  if (styled.needsPass() && !format.oneFrameAt) styled.runPass(system, integrator, dt, times);
  styled.start(system);
  Stepper stepper(system, integrator, dt);
  auto reached = [&](double t) {
    // A time not after the system's own (or NaN) draws the state as it is, without stepping.
    styled.advanceTo(stepper, system, t);
    if (hooks.onFrame) hooks.onFrame(system);
  };
  RenderSummary summary;
  if (format.oneFrameAt) {
    reached(*job.at);
    PngOptions png = job.png;
    png.alpha = png.alpha || job.look.transparentBackground;
    writePng(job.output, painter.paint(system), png);
    summary.frames = 1;
  } else {
    renderFrames(system, job, hooks, painter, reached, first, end, summary);
  }
  summary.steps = stepper.steps();
  summary.wallSeconds = secondsSince(start);
  return summary;
}

}  // namespace particles::render
