#pragma once
// Internal to render/: one video stream, encoded by a libavcodec encoder and muxed by libavformat
// into a file that libav opens by name. What the MP4, WebM and GIF writers share, in the order of
// FFmpeg's mux.c: the muxer's and the encoder's contexts (the caller sets the encoder's fields
// between construction and open()), the header, the send-frame / receive-packet loop of
// encode_video.c, and at the end the flush with a null frame and the trailer. Every call checked:
// failures are OutputError naming the call and libav's message.

extern "C" {
#include <libavutil/opt.h>
}

#include <string>
#include <utility>
#include <vector>

#include "render/video/libav_util.hpp"

namespace particles::render {

class VideoEncoder {
 public:
  using Options = std::vector<std::pair<std::string, std::string>>;

  // The output context of `muxer` ("mp4", "webm", "gif") for `url`, and a stream encoded by
  // `encoder` ("libx264", "libvpx-vp9", "gif"). `name` labels messages (the destination).
  VideoEncoder(const char* muxer, const char* encoder, std::string url, std::string name);

  // The encoder's context: set its size, time base, pixel format and colour tags before open().
  AVCodecContext* codec() { return codec_.get(); }
  // The muxer's context, for its flags (AVFMT_FLAG_BITEXACT), before open().
  AVFormatContext* format() { return format_.get(); }
  // One of the encoder's private options (x264's "crf", libvpx's "deadline"), before open().
  void setOption(const char* key, const std::string& value);

  // Opens the encoder and the file, and writes the header with the muxer's `muxerOptions`; an
  // option the muxer does not take is an error, not silently dropped.
  void open(const Options& muxerOptions = {});
  // A frame of the encoder's size, pixel format and colour tags, with its buffers.
  libav::FramePtr newFrame() const;
  // Encodes a frame (its pts in the codec's time base) and writes every packet the encoder yields.
  void send(const AVFrame* frame);
  // Flushes the encoder, writes the trailer and closes the file.
  void finish();

 private:
  std::string url_, name_;
  libav::OutputFormatPtr format_;
  libav::CodecContextPtr codec_;
  libav::PacketPtr packet_;
  const AVCodec* encoder_ = nullptr;
  AVStream* stream_ = nullptr;  // owned by format_
};

}  // namespace particles::render
