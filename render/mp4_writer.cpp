#include "render/mp4_writer.hpp"

#include <string>
#include <vector>

#include "render/errors.hpp"
#include "render/libav_util.hpp"
#include "render/yuv420.hpp"

extern "C" {
#include <libavutil/opt.h>
}

namespace particles::render {

using libav::check;

// Everything libav. Touched by the pipeline's worker while it runs (encodeFrame) and by the
// calling thread before it starts and after it has stopped (open, flush): never by both at once.
struct Mp4Writer::Encoder {
  libav::OutputFormatPtr format;
  libav::CodecContextPtr codec;
  std::vector<libav::FramePtr> frames;  // the pipeline's slots: yuv420p pictures
  libav::PacketPtr packet;
  AVStream* stream = nullptr;  // owned by format
  std::string path;            // for messages

  // Sends one frame (nullptr: the end, flushing the encoder) and writes every packet it yields.
  void send(const AVFrame* f) {
    check(avcodec_send_frame(codec.get(), f), f ? "avcodec_send_frame" : "avcodec_send_frame(flush)");
    for (;;) {
      const int ret = avcodec_receive_packet(codec.get(), packet.get());
      if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
      check(ret, "avcodec_receive_packet");
      av_packet_rescale_ts(packet.get(), codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      // Takes the packet's reference (the packet is left blank), also on failure.
      check(av_interleaved_write_frame(format.get(), packet.get()), "av_interleaved_write_frame(" + path + ")");
    }
  }

  // On the rendering thread: the frame straight into a slot's picture. If libav still holds a
  // reference to the slot's buffer, make_writable gives the slot a fresh one.
  void fill(const Image& image, size_t slot) {
    AVFrame* f = frames[slot].get();
    check(av_frame_make_writable(f), "av_frame_make_writable");
    rgbaToYuv420(image, {f->data[0], f->data[1], f->data[2], f->linesize[0], f->linesize[1], f->linesize[2]});
  }

  // On the pipeline's worker: frame `index` of the video.
  void encode(size_t slot, long index) {
    AVFrame* f = frames[slot].get();
    f->pts = index;
    send(f);
  }
};

namespace {

std::string evenHint(int w, int h) {
  return std::to_string(w + (w & 1)) + "x" + std::to_string(h + (h & 1));
}

void validate(const FrameWriterOptions& o) {
  if (o.width < 2 || o.height < 2 || (o.width & 1) || (o.height & 1)) {
    throw std::invalid_argument("MP4 (H.264, yuv420p) needs an even width and height; " + std::to_string(o.width) +
                                "x" + std::to_string(o.height) + " is not (try " + evenHint(o.width, o.height) +
                                ", or write PNG frames)");
  }
  if (o.video.fps < 1 || o.video.fps > 1000) {
    throw std::invalid_argument("fps " + std::to_string(o.video.fps) + " is out of range (1 to 1000)");
  }
  if (!(o.video.keyintSeconds > 0.0 && o.video.keyintSeconds <= kMaxKeyintSeconds)) {  // NaN fails too
    throw std::invalid_argument("keyframe interval " + std::to_string(o.video.keyintSeconds) +
                                " s is out of range (above 0, at most 3600)");
  }
  if (o.video.crf < 0 || o.video.crf > 51) {
    throw std::invalid_argument("crf " + std::to_string(o.video.crf) + " is out of range (0 to 51)");
  }
  if (!isX264Preset(o.video.preset)) {
    throw std::invalid_argument("unknown x264 preset '" + o.video.preset +
                                "' (ultrafast, superfast, veryfast, faster, fast, medium, slow, slower, veryslow, "
                                "placebo)");
  }
  static const char* const tunes[] = {"",     "film", "animation",  "grain",      "stillimage",
                                      "psnr", "ssim", "fastdecode", "zerolatency"};
  bool tuneOk = false;
  for (const char* t : tunes) tuneOk = tuneOk || o.video.tune == t;
  if (!tuneOk) throw std::invalid_argument("unknown x264 tune '" + o.video.tune + "'");
}

// The options are checked before the output is opened: opening a FIFO waits for its reader, and
// bad options would then be reported only once one came.
const std::filesystem::path& validated(const std::filesystem::path& path, const FrameWriterOptions& options) {
  validate(options);
  return path;
}

}  // namespace

Mp4Writer::Mp4Writer(const std::filesystem::path& path, const FrameWriterOptions& options)
    : PipelinedFrameWriter(options.width, options.height, "the video"), out_(validated(path, options)) {
  auto enc = std::make_unique<Encoder>();
  enc->path = path.string();
  // libav opens its output by name, and with +faststart the mp4 muxer opens it again by that name
  // (the context's url) to read it back while moving the index to the front. The name is that of
  // the file PendingOutput holds open ("/proc/self/fd/N" for an anonymous one). "file:" keeps a
  // colon in a named temporary from being read as a protocol ("out:1.mp4.partial-…").
  const std::string temp = "file:" + out_.reopenablePath().string();

  // The name does not end in .mp4, so the muxer is named, not guessed.
  AVFormatContext* fmt = nullptr;
  check(avformat_alloc_output_context2(&fmt, nullptr, "mp4", temp.c_str()), "avformat_alloc_output_context2(mp4)");
  enc->format.reset(fmt);

  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec) throw OutputError("avcodec_find_encoder_by_name(libx264): this libavcodec was built without libx264");
  enc->stream = avformat_new_stream(fmt, nullptr);
  if (!enc->stream) throw OutputError("avformat_new_stream: out of memory");
  enc->codec.reset(avcodec_alloc_context3(codec));
  if (!enc->codec) throw OutputError("avcodec_alloc_context3(libx264): out of memory");

  AVCodecContext* c = enc->codec.get();
  c->width = options.width;
  c->height = options.height;
  c->time_base = AVRational{1, options.video.fps};
  c->framerate = AVRational{options.video.fps, 1};
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->colorspace = AVCOL_SPC_BT709;
  c->color_primaries = AVCOL_PRI_BT709;
  c->color_trc = AVCOL_TRC_BT709;
  c->color_range = AVCOL_RANGE_MPEG;
  // x264's keyint: the longest run between keyframes. Its min-keyint (libav's keyint_min, default
  // 25) is clamped by x264 to half of it plus one.
  c->gop_size = options.video.keyframeInterval();
  if (fmt->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  check(av_opt_set(c->priv_data, "preset", options.video.preset.c_str(), 0), "av_opt_set(preset)");
  if (!options.video.tune.empty()) {
    check(av_opt_set(c->priv_data, "tune", options.video.tune.c_str(), 0), "av_opt_set(tune)");
  }
  check(av_opt_set_double(c->priv_data, "crf", options.video.crf, 0), "av_opt_set_double(crf)");
  check(avcodec_open2(c, codec, nullptr), "avcodec_open2(libx264)");

  check(avcodec_parameters_from_context(enc->stream->codecpar, c), "avcodec_parameters_from_context");
  enc->stream->time_base = c->time_base;  // a hint: the muxer may pick a finer one in write_header
  enc->stream->avg_frame_rate = c->framerate;

  // truncate=0: the file protocol would open with O_TRUNC; what we opened is empty already, or a
  // device or FIFO written in place, which is not ours to truncate.
  AVDictionary* fileOptions = nullptr;
  check(av_dict_set(&fileOptions, "truncate", "0", 0), "av_dict_set(truncate)");
  const int openResult = avio_open2(&fmt->pb, temp.c_str(), AVIO_FLAG_WRITE, nullptr, &fileOptions);
  const bool truncateIgnored = av_dict_count(fileOptions) > 0;
  av_dict_free(&fileOptions);
  check(openResult, "avio_open2(" + path.string() + ")");
  if (truncateIgnored) throw OutputError("avio_open2: the file protocol did not accept truncate=0");
  AVDictionary* muxOptions = nullptr;
  check(av_dict_set(&muxOptions, "movflags", "+faststart", 0), "av_dict_set(movflags)");
  const int headerResult = avformat_write_header(fmt, &muxOptions);
  const bool optionIgnored = av_dict_count(muxOptions) > 0;  // an entry left over was not recognised
  av_dict_free(&muxOptions);
  check(headerResult, "avformat_write_header(" + path.string() + ")");
  if (optionIgnored) throw OutputError("avformat_write_header: the mp4 muxer did not accept movflags=+faststart");

  enc->packet.reset(av_packet_alloc());
  if (!enc->packet) throw OutputError("av_packet_alloc: out of memory");
  // RGBA → yuv420p is ours (render/yuv420.hpp), done as each frame is queued.
  enc->frames.resize(FramePipeline::slotCount(options.queueFrames));
  for (libav::FramePtr& frame : enc->frames) {
    frame.reset(av_frame_alloc());
    if (!frame) throw OutputError("av_frame_alloc: out of memory");
    frame->format = c->pix_fmt;
    frame->width = c->width;
    frame->height = c->height;
    frame->color_range = c->color_range;
    frame->colorspace = c->colorspace;
    frame->color_primaries = c->color_primaries;
    frame->color_trc = c->color_trc;
    check(av_frame_get_buffer(frame.get(), 0), "av_frame_get_buffer");
  }

  encoder_ = std::move(enc);
  Encoder* e = encoder_.get();
  pipeline_ = std::make_unique<FramePipeline>(
      options.queueFrames, [e](const Image& image, size_t slot) { e->fill(image, slot); },
      [e](size_t slot, long index) { e->encode(slot, index); });
}

Mp4Writer::~Mp4Writer() {
  if (!finished_) abort();
}

void Mp4Writer::finish() {
  if (finished_ || aborted_) throw std::logic_error("Mp4Writer::finish called twice or after abort");
  try {
    pipeline_->close();  // the worker has stopped: libav is ours again
    encoder_->send(nullptr);
    AVFormatContext* fmt = encoder_->format.get();
    check(av_write_trailer(fmt), "av_write_trailer(" + out_.destination().string() + ")");
    check(avio_closep(&fmt->pb), "avio_closep(" + out_.destination().string() + ")");
    encoder_.reset();
    out_.commit();
  } catch (...) {
    abort();
    throw;
  }
  finished_ = true;
}

void Mp4Writer::abort() noexcept {
  if (aborted_ || finished_) return;
  aborted_ = true;
  if (pipeline_) pipeline_->cancel();
  encoder_.reset();  // closes the file
  out_.discard();
}

}  // namespace particles::render
