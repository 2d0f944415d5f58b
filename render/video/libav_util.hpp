#pragma once
// Internal to render/: ownership of libav* objects (one deleter each, as FFmpeg's examples free
// them) and libav error codes as text.

#include <memory>
#include <string>

#include "render/errors.hpp"
#include "render/video/libav_library.hpp"

namespace particles::render::libav {

// "avcodec_open2(libx264): Invalid argument" from a call name and a negative AVERROR code.
inline std::string describe(const std::string& call, int err) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  ffmpeg().av_strerror(err, buf, sizeof buf);
  return call + ": " + buf;
}

// Throws OutputError with describe()'s message when a libav call returned an error code.
inline void check(int err, const std::string& call) {
  if (err < 0) throw OutputError(describe(call, err));
}

struct CodecContextDeleter {
  void operator()(AVCodecContext* c) const { ffmpeg().avcodec_free_context(&c); }
};
struct FrameDeleter {
  void operator()(AVFrame* f) const { ffmpeg().av_frame_free(&f); }
};
struct PacketDeleter {
  void operator()(AVPacket* p) const { ffmpeg().av_packet_free(&p); }
};
struct FilterGraphDeleter {
  void operator()(AVFilterGraph* g) const { ffmpeg().avfilter_graph_free(&g); }
};
// An output context: closes its file (if one is open) and frees it.
struct OutputFormatDeleter {
  void operator()(AVFormatContext* s) const {
    if (s->pb && !(s->oformat->flags & AVFMT_NOFILE)) ffmpeg().avio_closep(&s->pb);
    ffmpeg().avformat_free_context(s);
  }
};
struct CodecParametersDeleter {
  void operator()(AVCodecParameters* p) const { ffmpeg().avcodec_parameters_free(&p); }
};
// An input context from avformat_open_input.
struct InputFormatDeleter {
  void operator()(AVFormatContext* s) const { ffmpeg().avformat_close_input(&s); }
};

using CodecContextPtr = std::unique_ptr<AVCodecContext, CodecContextDeleter>;
using FramePtr = std::unique_ptr<AVFrame, FrameDeleter>;
using PacketPtr = std::unique_ptr<AVPacket, PacketDeleter>;
using FilterGraphPtr = std::unique_ptr<AVFilterGraph, FilterGraphDeleter>;
using OutputFormatPtr = std::unique_ptr<AVFormatContext, OutputFormatDeleter>;
using InputFormatPtr = std::unique_ptr<AVFormatContext, InputFormatDeleter>;
using CodecParametersPtr = std::unique_ptr<AVCodecParameters, CodecParametersDeleter>;

}  // namespace particles::render::libav
