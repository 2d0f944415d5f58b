#include "render/video/video_encoder.hpp"

namespace particles::render {

using libav::check;

VideoEncoder::VideoEncoder(const char* muxer, const char* encoder, std::string url, std::string name)
    : url_(std::move(url)), name_(std::move(name)) {
  // The url need not end in the muxer's extension (a temporary's does not): the muxer is named.
  AVFormatContext* fmt = nullptr;
  check(libav::ffmpeg().avformat_alloc_output_context2(&fmt, nullptr, muxer, url_.c_str()),
        std::string("avformat_alloc_output_context2(") + muxer + ")");
  format_.reset(fmt);
  encoder_ = libav::ffmpeg().avcodec_find_encoder_by_name(encoder);
  if (!encoder_) {
    throw OutputError(std::string("avcodec_find_encoder_by_name(") + encoder + "): this libavcodec was built without " +
                      encoder);
  }
  stream_ = libav::ffmpeg().avformat_new_stream(fmt, nullptr);
  if (!stream_) throw OutputError("avformat_new_stream: out of memory");
  codec_.reset(libav::ffmpeg().avcodec_alloc_context3(encoder_));
  if (!codec_) throw OutputError(std::string("avcodec_alloc_context3(") + encoder + "): out of memory");
  packet_.reset(libav::ffmpeg().av_packet_alloc());
  if (!packet_) throw OutputError("av_packet_alloc: out of memory");
}

void VideoEncoder::setOption(const char* key, const std::string& value) {
  check(libav::ffmpeg().av_opt_set(codec_->priv_data, key, value.c_str(), 0),
        std::string("av_opt_set(") + key + "=" + value + ")");
}

void VideoEncoder::open(const Options& muxerOptions) {
  AVCodecContext* c = codec_.get();
  AVFormatContext* fmt = format_.get();
  if (fmt->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  check(libav::ffmpeg().avcodec_open2(c, encoder_, nullptr), std::string("avcodec_open2(") + encoder_->name + ")");
  check(libav::ffmpeg().avcodec_parameters_from_context(stream_->codecpar, c), "avcodec_parameters_from_context");
  stream_->time_base = c->time_base;  // a hint: the muxer may pick another in write_header
  stream_->avg_frame_rate = c->framerate;

  // truncate=0: the file protocol would open with O_TRUNC; what we opened is empty already, or a
  // device or FIFO written in place, which is not ours to truncate.
  AVDictionary* fileOptions = nullptr;
  check(libav::ffmpeg().av_dict_set(&fileOptions, "truncate", "0", 0), "av_dict_set(truncate)");
  const int openResult = libav::ffmpeg().avio_open2(&fmt->pb, url_.c_str(), AVIO_FLAG_WRITE, nullptr, &fileOptions);
  const bool truncateIgnored = libav::ffmpeg().av_dict_count(fileOptions) > 0;
  libav::ffmpeg().av_dict_free(&fileOptions);
  check(openResult, "avio_open2(" + name_ + ")");
  if (truncateIgnored) throw OutputError("avio_open2: the file protocol did not accept truncate=0");

  AVDictionary* options = nullptr;
  for (const auto& [key, value] : muxerOptions) {
    check(libav::ffmpeg().av_dict_set(&options, key.c_str(), value.c_str(), 0), "av_dict_set(" + key + ")");
  }
  const int headerResult = libav::ffmpeg().avformat_write_header(fmt, &options);
  // An entry left over was not recognised.
  const AVDictionaryEntry* ignored = libav::ffmpeg().av_dict_get(options, "", nullptr, AV_DICT_IGNORE_SUFFIX);
  const std::string ignoredKey = ignored ? ignored->key : "";
  libav::ffmpeg().av_dict_free(&options);
  check(headerResult, "avformat_write_header(" + name_ + ")");
  if (!ignoredKey.empty()) {
    throw OutputError(std::string("avformat_write_header: the ") + fmt->oformat->name + " muxer did not accept " +
                      ignoredKey);
  }
}

libav::FramePtr VideoEncoder::newFrame() const {
  const AVCodecContext* c = codec_.get();
  libav::FramePtr frame(libav::ffmpeg().av_frame_alloc());
  if (!frame) throw OutputError("av_frame_alloc: out of memory");
  frame->format = c->pix_fmt;
  frame->width = c->width;
  frame->height = c->height;
  frame->color_range = c->color_range;
  frame->colorspace = c->colorspace;
  frame->color_primaries = c->color_primaries;
  frame->color_trc = c->color_trc;
  check(libav::ffmpeg().av_frame_get_buffer(frame.get(), 0), "av_frame_get_buffer");
  return frame;
}

void VideoEncoder::send(const AVFrame* frame) {
  check(libav::ffmpeg().avcodec_send_frame(codec_.get(), frame),
        frame ? "avcodec_send_frame" : "avcodec_send_frame(flush)");
  for (;;) {
    const int ret = libav::ffmpeg().avcodec_receive_packet(codec_.get(), packet_.get());
    if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
    check(ret, "avcodec_receive_packet");
    libav::ffmpeg().av_packet_rescale_ts(packet_.get(), codec_->time_base, stream_->time_base);
    packet_->stream_index = stream_->index;
    // Takes the packet's reference (the packet is left blank), also on failure.
    check(libav::ffmpeg().av_interleaved_write_frame(format_.get(), packet_.get()),
          "av_interleaved_write_frame(" + name_ + ")");
  }
}

void VideoEncoder::finish() {
  send(nullptr);
  AVFormatContext* fmt = format_.get();
  check(libav::ffmpeg().av_write_trailer(fmt), "av_write_trailer(" + name_ + ")");
  check(libav::ffmpeg().avio_closep(&fmt->pb), "avio_closep(" + name_ + ")");
}

}  // namespace particles::render
