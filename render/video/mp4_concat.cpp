#include "render/video/mp4_concat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "output/pending_output.hpp"
#include "render/video/libav_util.hpp"

namespace particles::render {

namespace {

using libav::check;

// Bad input: the segment `path` and what is wrong with it.
[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& why) {
  throw std::invalid_argument(fmt::format("{}: {}", path.string(), why));
}

// One segment, open: its file, its one video stream and a decoder for it. Only one is open at a
// time, so memory does not grow with the number of segments (8000 open at once took 1.3 GB).
struct Segment {
  std::filesystem::path path;
  libav::InputFormatPtr format;
  AVStream* video = nullptr;
  libav::CodecContextPtr decoder;
};

// Opens a segment, finds its one video stream and opens a decoder for it; anything else is bad
// input naming the file.
Segment openSegment(const std::filesystem::path& path) {
  Segment s;
  s.path = path;
  AVFormatContext* fmt = nullptr;
  const std::string url = "file:" + path.string();
  if (const int err = libav::ffmpeg().avformat_open_input(&fmt, url.c_str(), nullptr, nullptr); err < 0) {
    throw std::invalid_argument(libav::describe("cannot open " + path.string(), err));
  }
  s.format.reset(fmt);
  if (const int err = libav::ffmpeg().avformat_find_stream_info(fmt, nullptr); err < 0) {
    refuse(path, libav::describe("not a video (truncated, or not an MP4?)", err));
  }
  int videos = 0;
  for (unsigned i = 0; i < fmt->nb_streams; ++i) {
    if (fmt->streams[i]->codecpar->codec_type == AVMEDIA_TYPE_VIDEO) {
      ++videos;
      s.video = fmt->streams[i];
    }
  }
  if (videos != 1) refuse(path, fmt::format("{} video streams, not one", videos));
  // libavformat leaves the pixel format unknown when it could decode no picture of the stream: a
  // 2000-byte head of a segment has its index but none of its frames.
  const AVCodecParameters* par = s.video->codecpar;
  if (par->width <= 0 || par->height <= 0 || par->format == AV_PIX_FMT_NONE) {
    refuse(path, "truncated or damaged: none of its pictures decodes");
  }
  const AVCodec* codec = libav::ffmpeg().avcodec_find_decoder(par->codec_id);
  if (!codec)
    refuse(path, fmt::format("no decoder for its codec {} in this libavcodec",
                             libav::ffmpeg().avcodec_get_name(par->codec_id)));
  s.decoder.reset(libav::ffmpeg().avcodec_alloc_context3(codec));
  if (!s.decoder) throw OutputError("avcodec_alloc_context3: out of memory");
  check(libav::ffmpeg().avcodec_parameters_to_context(s.decoder.get(), par), "avcodec_parameters_to_context");
  // A damaged packet is an error, not a picture concealed from its neighbours.
  s.decoder->err_recognition |= AV_EF_EXPLODE;
  if (const int err = libav::ffmpeg().avcodec_open2(s.decoder.get(), codec, nullptr); err < 0) {
    refuse(path, libav::describe(std::string("avcodec_open2(") + codec->name + ")", err));
  }
  return s;
}

// What every segment must share with the first for the copy to be one stream.
struct StreamShape {
  std::filesystem::path path;  // the first segment
  libav::CodecParametersPtr par{libav::ffmpeg().avcodec_parameters_alloc()};
  AVRational frameRate{0, 1}, timeBase{0, 1};
};

StreamShape shapeOf(const Segment& s) {
  StreamShape shape;
  shape.path = s.path;
  if (!shape.par) throw OutputError("avcodec_parameters_alloc: out of memory");
  check(libav::ffmpeg().avcodec_parameters_copy(shape.par.get(), s.video->codecpar), "avcodec_parameters_copy");
  shape.frameRate = s.video->avg_frame_rate;
  shape.timeBase = s.video->time_base;
  return shape;
}

std::string rational(AVRational r) {
  return fmt::format("{}/{}", r.num, r.den);
}

// Empty when `s` can follow the first segment by stream copy; else what differs.
std::string difference(const StreamShape& first, const Segment& s) {
  const AVCodecParameters* a = first.par.get();
  const AVCodecParameters* b = s.video->codecpar;
  if (a->codec_id != b->codec_id) {
    return fmt::format("codec {}, not {}", libav::ffmpeg().avcodec_get_name(b->codec_id),
                       libav::ffmpeg().avcodec_get_name(a->codec_id));
  }
  if (a->width != b->width || a->height != b->height) {
    return fmt::format("{}×{}, not {}×{}", b->width, b->height, a->width, a->height);
  }
  if (a->format != b->format) return "another pixel format";
  if (av_cmp_q(first.frameRate, s.video->avg_frame_rate) != 0) {
    return fmt::format("{} frames/s, not {}", rational(s.video->avg_frame_rate), rational(first.frameRate));
  }
  if (av_cmp_q(first.timeBase, s.video->time_base) != 0) {
    return fmt::format("time base {}, not {}", rational(s.video->time_base), rational(first.timeBase));
  }
  if (a->extradata_size != b->extradata_size ||
      (a->extradata_size > 0 && std::memcmp(a->extradata, b->extradata, size_t(a->extradata_size)) != 0)) {
    return "another codec header (encoded with other settings)";
  }
  return {};
}

// The joined video being written: its muxer and where the next segment starts.
class JoinedVideo {
 public:
  JoinedVideo(const std::filesystem::path& output, const StreamShape& shape) : output_(output), out_(output) {
    const std::string temp = "file:" + out_.reopenablePath().string();
    AVFormatContext* raw = nullptr;
    check(libav::ffmpeg().avformat_alloc_output_context2(&raw, nullptr, "mp4", temp.c_str()),
          "avformat_alloc_output_context2(mp4)");
    format_.reset(raw);
    stream_ = libav::ffmpeg().avformat_new_stream(raw, nullptr);
    if (!stream_) throw OutputError("avformat_new_stream: out of memory");
    check(libav::ffmpeg().avcodec_parameters_copy(stream_->codecpar, shape.par.get()), "avcodec_parameters_copy");
    stream_->codecpar->codec_tag = 0;  // the muxer picks the tag for its container
    stream_->time_base = shape.timeBase;
    stream_->avg_frame_rate = shape.frameRate;

    AVDictionary* fileOptions = nullptr;
    check(libav::ffmpeg().av_dict_set(&fileOptions, "truncate", "0", 0), "av_dict_set(truncate)");
    const int openResult = libav::ffmpeg().avio_open2(&raw->pb, temp.c_str(), AVIO_FLAG_WRITE, nullptr, &fileOptions);
    libav::ffmpeg().av_dict_free(&fileOptions);
    check(openResult, "avio_open2(" + output.string() + ")");
    AVDictionary* muxOptions = nullptr;
    check(libav::ffmpeg().av_dict_set(&muxOptions, "movflags", "+faststart", 0), "av_dict_set(movflags)");
    const int headerResult = libav::ffmpeg().avformat_write_header(raw, &muxOptions);
    libav::ffmpeg().av_dict_free(&muxOptions);
    check(headerResult, "avformat_write_header(" + output.string() + ")");
  }

  // Writes a packet of `s`, its timestamps moved on by the segments before.
  void write(const Segment& s, AVPacket* packet) {
    libav::ffmpeg().av_packet_rescale_ts(packet, s.video->time_base, stream_->time_base);
    if (packet->pts != AV_NOPTS_VALUE) {
      packet->pts += offset_;
      segmentEnd_ = std::max(segmentEnd_, packet->pts + packet->duration);
    }
    if (packet->dts != AV_NOPTS_VALUE) {
      packet->dts += offset_;
      // Alike segments have the same reorder delay, so decoding times stay increasing.
      if (packet->dts <= lastDts_) refuse(s.path, "its decoding times overlap the segment before");
      lastDts_ = packet->dts;
    }
    packet->stream_index = stream_->index;
    packet->pos = -1;
    check(libav::ffmpeg().av_interleaved_write_frame(format_.get(), packet),
          "av_interleaved_write_frame(" + output_.string() + ")");
  }

  // The next segment starts where this one's last frame ends.
  void endSegment() { offset_ = segmentEnd_; }

  // Writes the index and publishes the file; returns the video's duration in seconds.
  double finish() {
    check(libav::ffmpeg().av_write_trailer(format_.get()), "av_write_trailer(" + output_.string() + ")");
    check(libav::ffmpeg().avio_closep(&format_->pb), "avio_closep(" + output_.string() + ")");
    out_.commit();
    return double(offset_) * av_q2d(stream_->time_base);
  }

 private:
  std::filesystem::path output_;
  output::PendingOutput out_;
  libav::OutputFormatPtr format_;
  AVStream* stream_ = nullptr;
  int64_t offset_ = 0;      // in the output stream's time base: where the current segment starts
  int64_t segmentEnd_ = 0;  // the end of the current segment's last frame so far
  int64_t lastDts_ = INT64_MIN;
};

// Sends `packet` (null: the end), the segment's `frame`th, to its decoder and counts the pictures
// it gives back; a packet that does not decode is bad input naming the file.
void decode(const Segment& s, const AVPacket* packet, long frame, AVFrame* picture, long& pictures) {
  const auto fail = [&](int err) {
    refuse(s.path, libav::describe(fmt::format("truncated or damaged: frame {} does not decode", frame), err));
  };
  if (const int err = libav::ffmpeg().avcodec_send_packet(s.decoder.get(), packet); err < 0) fail(err);
  for (;;) {
    const int err = libav::ffmpeg().avcodec_receive_frame(s.decoder.get(), picture);
    if (err == AVERROR(EAGAIN) || err == AVERROR_EOF) return;
    if (err < 0) fail(err);
    ++pictures;
    libav::ffmpeg().av_frame_unref(picture);
  }
}

// Copies the packets of `s` into `joined`, decoding each on the way: what is joined is checked to
// decode whole, every packet without error and as many pictures as the segment's index lists.
// Returns the packets copied.
long copySegment(Segment& s, JoinedVideo& joined) {
  const libav::PacketPtr packet(libav::ffmpeg().av_packet_alloc());
  const libav::FramePtr picture(libav::ffmpeg().av_frame_alloc());
  if (!packet || !picture) throw OutputError("av_packet_alloc/av_frame_alloc: out of memory");
  long packets = 0, pictures = 0;
  for (;;) {
    const int err = libav::ffmpeg().av_read_frame(s.format.get(), packet.get());
    if (err == AVERROR_EOF) break;
    if (err < 0)
      refuse(s.path, libav::describe(fmt::format("truncated or damaged: reading frame {}", packets + 1), err));
    if (packet->stream_index != s.video->index) {
      libav::ffmpeg().av_packet_unref(packet.get());
      continue;
    }
    // libavformat marks a packet the file ends inside of.
    if (packet->flags & AV_PKT_FLAG_CORRUPT) {
      refuse(s.path, fmt::format("truncated or damaged: frame {} is cut short", packets + 1));
    }
    ++packets;
    decode(s, packet.get(), packets, picture.get(), pictures);
    joined.write(s, packet.get());  // unreferences the packet
  }
  decode(s, nullptr, packets, picture.get(), pictures);  // the pictures the decoder still holds
  const int64_t listed = s.video->nb_frames;             // the MP4 index's sample count; 0 if unknown
  if (pictures != packets || (listed > 0 && listed != packets)) {
    refuse(s.path, fmt::format("truncated or damaged: its index lists {} frames, {} were read and {} decode", listed,
                               packets, pictures));
  }
  joined.endSegment();
  return packets;
}

}  // namespace

ConcatSummary concatMp4(const std::vector<std::filesystem::path>& paths, const std::filesystem::path& output) {
  if (paths.empty()) throw std::invalid_argument("no segments to join");
  // One segment open at a time: the first fixes the joined stream's parameters, each of the others
  // is opened, compared with them, copied and closed before the next.
  Segment first = openSegment(paths.front());
  const StreamShape shape = shapeOf(first);
  JoinedVideo joined(output, shape);
  ConcatSummary summary;
  summary.frames = copySegment(first, joined);
  first = {};
  for (size_t i = 1; i < paths.size(); ++i) {
    Segment s = openSegment(paths[i]);
    if (const std::string why = difference(shape, s); !why.empty()) {
      throw std::invalid_argument(fmt::format("{} cannot follow {}: {}", s.path.string(), shape.path.string(), why));
    }
    summary.frames += copySegment(s, joined);
  }
  summary.seconds = joined.finish();
  return summary;
}

}  // namespace particles::render
