// particles::VideoWriter: see include/particles/video_writer.hpp. The render command's writers
// (render/video/frame_writer.hpp), opened at the first frame with its size.
#include <particles/video_writer.hpp>

#include <fmt/format.h>

#include <atomic>
#include <mutex>
#include <string_view>
#include <cmath>

#include "api/checked_image.hpp"
#include "api/exclusive_use.hpp"
#include "api/guarded_call.hpp"
#include "core/worker_pool.hpp"
#include "input/printable_text.hpp"
#include "render/video/frame_writer.hpp"
#include "render/video/output_formats.hpp"

namespace particles {

struct VideoWriter::Impl {
  std::string path;
  render::FrameWriterOptions options;  // the size is the first frame's
  std::unique_ptr<render::FrameWriter> writer;
  bool finished = false;
  std::atomic<bool> busy{false};  // a write() or finish() is under way (ExclusiveUse)
  // Held by write() and finish() for their whole call, and by abort(), which another thread may
  // call meanwhile: it waits for the call to end instead of freeing the encoder under it.
  std::mutex calls;
  bool aborted = false;  // under `calls`
  // forkCount() when the writer was made: its encoder thread, once started, and its temporary file
  // belong to that process. A fork()ed child's write() and finish() are refused, and its abort()
  // and destructor leave them alone (freeing the writer would wait for a thread that is not here).
  unsigned madeAtFork = forkCount();

  bool inherited() const { return madeAtFork != forkCount(); }
  void requireOwnProcess(std::string_view call) const {
    if (inherited()) {
      throw Error(
          fmt::format("VideoWriter::{}: this writer was made before this process was forked; its encoder and "
                      "{}'s temporary file are the parent's: write from there, or make a writer here",
                      call, input::quotedValue(path)));
    }
  }
  ~Impl() {
    if (inherited()) (void)writer.release();
  }

  // write() and finish() refuse to go on after abort() (under `calls`).
  void requireNotAborted(std::string_view call) const {
    if (aborted)
      throw ArgumentError(fmt::format("VideoWriter::{}: the writer was aborted; {} is not written", call, path));
  }
};

namespace {

// The format's frame rate when none is asked for (0), as `particles render` takes it; checked.
int fpsFor(const render::OutputFormat& format, int fps) {
  if (fps == 0) return format.fpsCap ? format.fpsCap->byDefault : 60;
  const int most = format.fpsCap ? format.fpsCap->most : render::kMaxFps;
  if (fps < render::kMinFps || fps > most) {
    throw ArgumentError(fmt::format("VideoWriter: fps for {} must be {} to {} (or 0, the format's default){}, got {}",
                                    format.name, render::kMinFps, most,
                                    format.fpsCap ? fmt::format(": {}", format.fpsCap->why) : std::string(), fps));
  }
  return fps;
}

}  // namespace

VideoWriter::VideoWriter(const std::string& path, const VideoSettings& settings) {
  impl_ = api::guardedCall("VideoWriter", [&] {
    // A copy (views and numbers): GCC 14's -Wdangling-reference takes a reference returned by a
    // call given a temporary (the std::filesystem::path made from `path`) to be one into it.
    const render::OutputFormat format = render::outputFormatOf(path);
    if (format.oneFrameAt || format.kind == render::OutputKind::pngSequence) {
      throw ArgumentError(
          fmt::format("VideoWriter: {} is not a video: give a .mp4, .webm or .gif path "
                      "(one frame: Image::savePng)",
                      input::quotedValue(path)));
    }
    const int fps = fpsFor(format, settings.fps);
    if (!render::isX264Preset(settings.preset)) {
      throw ArgumentError(fmt::format("VideoWriter: preset must be one of {}, not {}",
                                      fmt::join(render::kX264Presets, ", "), input::quotedValue(settings.preset)));
    }
    if (!(settings.keyintSeconds > 0.0 && settings.keyintSeconds <= render::kMaxKeyintSeconds)) {
      throw ArgumentError(fmt::format("VideoWriter: keyintSeconds must be above 0 and at most {}, got {}",
                                      render::kMaxKeyintSeconds, settings.keyintSeconds));
    }
    if (settings.alpha && !format.keepsAlpha) {
      throw ArgumentError(fmt::format("VideoWriter: {} cannot keep alpha: {}", format.name, format.alphaNote));
    }
    if (settings.crf != -1) {
      if (!format.crf || settings.crf < format.crf->lowest || settings.crf > format.crf->highest) {
        throw ArgumentError(format.crf ? fmt::format("VideoWriter: crf for {} must be {} to {} (or −1, the default {}), "
                                                     "got {}",
                                                     format.name, format.crf->lowest, format.crf->highest,
                                                     format.crf->byDefault, settings.crf)
                                       : fmt::format("VideoWriter: {} has no quality setting: leave crf at −1",
                                                     format.name));
      }
    }
    render::setLibavVerbose(settings.verbose);
    auto impl = std::make_unique<Impl>();
    impl->path = path;
    impl->options.video.fps = fps;
    if (settings.crf != -1) impl->options.video.crf = settings.crf;
    impl->options.video.preset = settings.preset;
    impl->options.video.keyintSeconds = settings.keyintSeconds;
    impl->options.alpha = settings.alpha;
    return impl;
  });
}
VideoWriter::VideoWriter(VideoWriter&& other) noexcept = default;
VideoWriter& VideoWriter::operator=(VideoWriter&& other) noexcept = default;
VideoWriter::~VideoWriter() = default;  // an unfinished FrameWriter removes what it wrote

void VideoWriter::write(const Image& frame) {
  api::guardedCall("VideoWriter::write", [&] {
    if (!impl_) throw ArgumentError("VideoWriter::write: this VideoWriter was moved from");
    impl_->requireOwnProcess("write");
    ExclusiveUse use(impl_->busy, "VideoWriter::write", "VideoWriter");
    const std::lock_guard lock(impl_->calls);
    impl_->requireNotAborted("write");
    if (impl_->finished) throw ArgumentError("VideoWriter::write: the video is finished");
    const render::Image image = api::checkedImage(frame, "VideoWriter::write", "frame");
    if (!impl_->writer) {
      impl_->options.width = frame.width;
      impl_->options.height = frame.height;
      impl_->writer = render::openFrameWriter(impl_->path, impl_->options);
    } else if (frame.width != impl_->options.width || frame.height != impl_->options.height) {
      throw ArgumentError(fmt::format("VideoWriter::write: every frame must be {}x{} like the first, this one is {}x{}",
                                      impl_->options.width, impl_->options.height, frame.width, frame.height));
    }
    impl_->writer->write(image);
  });
}

void VideoWriter::finish() {
  api::guardedCall("VideoWriter::finish", [&] {
    if (!impl_) throw ArgumentError("VideoWriter::finish: this VideoWriter was moved from");
    impl_->requireOwnProcess("finish");
    ExclusiveUse use(impl_->busy, "VideoWriter::finish", "VideoWriter");
    const std::lock_guard lock(impl_->calls);
    impl_->requireNotAborted("finish");
    if (impl_->finished) return;
    if (!impl_->writer) {
      throw ArgumentError(
          fmt::format("VideoWriter::finish: no frame was written to {}", input::quotedValue(impl_->path)));
    }
    impl_->writer->finish();
    impl_->finished = true;
  });
}

void VideoWriter::abort() noexcept {
  if (!impl_ || impl_->inherited()) return;  // a fork()ed child's: the parent's to stop
  const std::lock_guard lock(impl_->calls);  // a write() or finish() on another thread ends first
  if (impl_->finished) return;
  impl_->aborted = true;
  if (impl_->writer) impl_->writer->abort();
}

long VideoWriter::frames() const { return impl_ && impl_->writer ? impl_->writer->framesWritten() : 0; }

}  // namespace particles
