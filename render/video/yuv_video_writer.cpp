#include "render/video/yuv_video_writer.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "render/video/frame_pipeline.hpp"
#include "render/video/output_formats.hpp"
#include "render/video/video_encoder.hpp"
#include "render/video/yuv420.hpp"

namespace particles::render {

using libav::check;

// Touched by the pipeline's worker while it runs (encode) and by the calling thread before it
// starts and after it has stopped (open, finish): never by both at once. `fill` runs on the
// calling thread but touches only a slot the worker is not using.
struct YuvVideoWriter::Encoder {
  std::unique_ptr<VideoEncoder> video;
  std::vector<libav::FramePtr> frames;  // the pipeline's slots
  bool alpha = false;

  // On the rendering thread: the frame straight into a slot's picture. If libav still holds a
  // reference to the slot's buffer, make_writable gives the slot a fresh one.
  void fill(const Image& image, size_t slot) {
    AVFrame* f = frames[slot].get();
    check(libav::ffmpeg().av_frame_make_writable(f), "av_frame_make_writable");
    const Yuv420Planes planes{f->data[0], f->data[1], f->data[2], f->linesize[0], f->linesize[1], f->linesize[2]};
    if (alpha) {
      rgbaToYuva420(image, planes, f->data[3], f->linesize[3]);
    } else {
      rgbaToYuv420(image, planes);
    }
  }

  // On the pipeline's worker: frame `index` of the video.
  void encode(size_t slot, long index) {
    AVFrame* f = frames[slot].get();
    f->pts = index;
    video->send(f);
  }
};

void validateYuvVideo(const OutputFormat& format, const FrameWriterOptions& o) {
  checkFrameSize(format, o.width, o.height, o.alpha);
  if (o.video.fps < kMinFps || o.video.fps > kMaxFps) {
    throw std::invalid_argument(fmt::format("fps {} is out of range ({} to {})", o.video.fps, kMinFps, kMaxFps));
  }
  if (!(o.video.keyintSeconds > 0.0 && o.video.keyintSeconds <= kMaxKeyintSeconds)) {  // NaN fails too
    throw std::invalid_argument(fmt::format("keyframe interval {} s is out of range (above 0, at most {})",
                                            std::to_string(o.video.keyintSeconds), kMaxKeyintSeconds));
  }
}

YuvVideoWriter::YuvVideoWriter(const std::filesystem::path& path, const FrameWriterOptions& options)
    : SingleFileWriter(path, options.width, options.height, "the video"), options_(options) {}

YuvVideoWriter::~YuvVideoWriter() {
  if (!finished_) abort();
}

std::unique_ptr<VideoEncoder> YuvVideoWriter::makeEncoder(const char* muxer, const char* encoder, bool alpha) const {
  // libav opens its output by name, and with +faststart the mp4 muxer opens it again by that name
  // (the context's url) to read it back while moving the index to the front. The name is that of
  // the file PendingOutput holds open ("/proc/self/fd/N" for an anonymous one). "file:" keeps a
  // colon in a named temporary from being read as a protocol ("out:1.mp4.partial-…").
  auto video = std::make_unique<VideoEncoder>(muxer, encoder, "file:" + out_.reopenablePath().string(),
                                              out_.destination().string());
  AVCodecContext* c = video->codec();
  c->width = options_.width;
  c->height = options_.height;
  c->time_base = AVRational{1, options_.video.fps};
  c->framerate = AVRational{options_.video.fps, 1};
  c->pix_fmt = alpha ? AV_PIX_FMT_YUVA420P : AV_PIX_FMT_YUV420P;
  c->colorspace = AVCOL_SPC_BT709;
  c->color_primaries = AVCOL_PRI_BT709;
  c->color_trc = AVCOL_TRC_BT709;
  c->color_range = AVCOL_RANGE_MPEG;
  return video;
}

void YuvVideoWriter::start(std::unique_ptr<VideoEncoder> video,
                           const std::vector<std::pair<std::string, std::string>>& muxerOptions) {
  auto enc = std::make_unique<Encoder>();
  enc->alpha = video->codec()->pix_fmt == AV_PIX_FMT_YUVA420P;
  video->open(muxerOptions);
  enc->frames.resize(FramePipeline::slotCount(options_.queueFrames));
  for (libav::FramePtr& frame : enc->frames) frame = video->newFrame();
  enc->video = std::move(video);

  encoder_ = std::move(enc);
  Encoder* e = encoder_.get();
  pipeline_ = std::make_unique<FramePipeline>(
      options_.queueFrames, [e](const Image& image, size_t slot) { e->fill(image, slot); },
      [e](size_t slot, long index) { e->encode(slot, index); });
}

void YuvVideoWriter::complete() {
  encoder_->video->finish();
}

void YuvVideoWriter::release() noexcept {
  encoder_.reset();  // closes the file
}

}  // namespace particles::render
