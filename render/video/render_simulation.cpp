#include "render/video/render_simulation.hpp"

#include <chrono>
#include <optional>
#include <vector>
#include <stdexcept>
#include <string>

#include "core/solver.hpp"
#include "render/frame_memory.hpp"
#include "render/video/frame_pipeline.hpp"
#include "render/renderer.hpp"

namespace particles::render {

namespace {

// The job's GL request, with the job's threads for llvmpipe.
GlRequest rasterRequestOf(const RenderJob& job) {
  GlRequest gl = job.gl;
  if (job.threads > 0) gl.threads = job.threads;
  return gl;
}

// The renderer's frame for a drawing, drawn over by the decorate hook if there is one.
class FramePainter {
 public:
  FramePainter(const RenderJob& job, const RenderHooks& hooks)
      : renderer_(job.look, rasterRequestOf(job)), camera_(job.camera), decorate_(hooks.decorate) {
    if (hooks.glReady) hooks.glReady(renderer_.gl());
    // The copy drawn over, allocated with the frame (render/frame_memory.hpp) and reused.
    if (decorate_) decorated_ = allocateImage(job.look.width, job.look.height, "the frame's decorated copy");
  }
  // The system's current state, its shapes built on the system's threads (Renderer::render),
  // which are idle while it is drawn.
  const Image& paint(System& system) {
    system.draw(drawing_, SpringDetail::topology);  // every raster path draws springs by index
    const Image& image = renderer_.render(drawing_, camera_, system.pool());
    if (!decorate_) return image;
    decorated_ = image;  // the renderer's image is reused for the next frame
    decorate_(decorated_, system);
    return decorated_;
  }
  // A drawing made earlier, without the decorate hook (which needs the system at the frame's time),
  // in two steps (Renderer::submit, collect).
  void submit(const Drawing& drawing, WorkerPool* pool) { renderer_.submit(drawing, camera_, pool); }
  const Image& collect() { return renderer_.collect(); }
  bool readsAhead() const { return renderer_.readsAhead(); }
  void releaseFromThread() { renderer_.releaseFromThread(); }

 private:
  Renderer renderer_;
  Camera camera_;
  Drawing drawing_;  // the frame's, its storage reused from frame to frame
  const std::function<void(Image&, const System&)>& decorate_;
  Image decorated_;
};

// The frame loop overlapped: while this thread steps the simulation to frame k + 1's
// time, another draws frame k (its shapes built on a pool of its own, GL, the read-back) and hands
// it to the writer, whose own thread encodes frame k − 1. Where the renderer reads ahead (EGL:
// two pixel-pack buffers), the drawing thread starts frame k's read-back and hands the writer
// frame k − 1's instead, so that GL copies frame k out while the CPU converts frame k − 1 and
// builds frame k + 1; finish() collects the last. What passes between the two is the
// frame's Drawing, a snapshot of the state in plain geometry (core/drawing.hpp), in one of three
// reused slots (FramePipeline::slotCount(1): one being drawn, one waiting, one being filled), so
// memory stays bounded. Frames are drawn in order, each from its own state: the same images as
// the plain loop, byte for byte. Not for a decorated frame, whose hook reads the system itself.
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
          painter_.submit(drawings_[slot], &pool_);
          if (held_ || !painter_.readsAhead()) writer_.write(painter_.collect());
          held_ = painter_.readsAhead();  // this frame waits in its buffer for the next one
        }) {}

  void push(const System& system) {
    pipeline_.pushWith([&](std::size_t slot) { system.draw(drawings_[slot], SpringDetail::topology); });
  }
  // Rethrows a failed frame's error; else writes the frame still being read back, on this thread
  // (the drawing thread has given the GL context back).
  void finish() {
    pipeline_.close();
    if (!held_) return;
    held_ = false;
    writer_.write(painter_.collect());
    painter_.releaseFromThread();
  }
  void cancel() noexcept { pipeline_.cancel(); }

 private:
  FramePainter& painter_;
  FrameWriter& writer_;
  std::vector<Drawing> drawings_ = std::vector<Drawing>(FramePipeline::slotCount(1));
  WorkerPool pool_;  // the drawing thread's: the system's belongs to the stepping thread
  bool held_ = false;  // a frame read ahead and not yet written (the drawing thread's, then finish's)
  FramePipeline pipeline_;  // last: its worker uses the members above
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
                                " are not a range of the video's " + std::to_string(total) + " frames (0:" +
                                std::to_string(total) + ")");
  }
  const bool alpha = job.look.transparentBackground;

  FramePainter painter(job, hooks);
  Stepper stepper(system, integrator, dt);
  auto reached = [&](double t) {
    // A time not after the system's own (or NaN) draws the state as it is, without stepping.
    if (t > system.time()) stepper.advanceTo(t);
    if (hooks.onFrame) hooks.onFrame(system);
  };
  const auto start = std::chrono::steady_clock::now();
  RenderSummary summary;

  if (format.oneFrameAt) {
    reached(*job.at);
    PngOptions png = job.png;
    png.alpha = png.alpha || alpha;
    writePng(job.output, painter.paint(system), png);
    summary.frames = 1;
    summary.steps = stepper.steps();
    summary.wallSeconds = secondsSince(start);
    return summary;
  }

  FrameWriterOptions out;
  out.width = job.look.width;
  out.height = job.look.height;
  out.video = job.video;
  out.video.fps = job.fps;
  out.png = job.png;
  out.alpha = alpha;
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
      break;
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
  if (!summary.stopped) {
    if (overlapped) overlapped->finish();
    writer->finish();
    summary.frames = frames;
  }
  summary.steps = stepper.steps();
  summary.wallSeconds = secondsSince(start);
  return summary;
}

}  // namespace particles::render
