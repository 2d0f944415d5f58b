#include "render/mp4_concat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "output/pending_output.hpp"
#include "render/libav_util.hpp"

namespace particles::render {

namespace {

using libav::check;

struct Segment {
  std::filesystem::path path;
  libav::InputFormatPtr format;
  AVStream* video = nullptr;
};

// Opens a segment and finds its one video stream; anything else is bad input naming the file.
Segment openSegment(const std::filesystem::path& path) {
  Segment s;
  s.path = path;
  AVFormatContext* fmt = nullptr;
  const std::string url = "file:" + path.string();
  if (const int err = avformat_open_input(&fmt, url.c_str(), nullptr, nullptr); err < 0) {
    throw std::invalid_argument(libav::describe("cannot open " + path.string(), err));
  }
  s.format.reset(fmt);
  if (const int err = avformat_find_stream_info(fmt, nullptr); err < 0) {
    throw std::invalid_argument(libav::describe(path.string() + ": not a video", err));
  }
  int videos = 0;
  for (unsigned i = 0; i < fmt->nb_streams; ++i) {
    if (fmt->streams[i]->codecpar->codec_type == AVMEDIA_TYPE_VIDEO) {
      ++videos;
      s.video = fmt->streams[i];
    }
  }
  if (videos != 1) {
    throw std::invalid_argument(fmt::format("{}: {} video streams, not one", path.string(), videos));
  }
  return s;
}

std::string rational(AVRational r) { return fmt::format("{}/{}", r.num, r.den); }

// Empty when `s` can follow `first` by stream copy; else what differs.
std::string difference(const Segment& first, const Segment& s) {
  const AVCodecParameters* a = first.video->codecpar;
  const AVCodecParameters* b = s.video->codecpar;
  if (a->codec_id != b->codec_id) {
    return fmt::format("codec {}, not {}", avcodec_get_name(b->codec_id), avcodec_get_name(a->codec_id));
  }
  if (a->width != b->width || a->height != b->height) {
    return fmt::format("{}×{}, not {}×{}", b->width, b->height, a->width, a->height);
  }
  if (a->format != b->format) return "another pixel format";
  if (av_cmp_q(first.video->avg_frame_rate, s.video->avg_frame_rate) != 0) {
    return fmt::format("{} frames/s, not {}", rational(s.video->avg_frame_rate), rational(first.video->avg_frame_rate));
  }
  if (av_cmp_q(first.video->time_base, s.video->time_base) != 0) {
    return fmt::format("time base {}, not {}", rational(s.video->time_base), rational(first.video->time_base));
  }
  if (a->extradata_size != b->extradata_size ||
      (a->extradata_size > 0 && std::memcmp(a->extradata, b->extradata, size_t(a->extradata_size)) != 0)) {
    return "another codec header (encoded with other settings)";
  }
  return {};
}

}  // namespace

ConcatSummary concatMp4(const std::vector<std::filesystem::path>& paths, const std::filesystem::path& output) {
  if (paths.empty()) throw std::invalid_argument("no segments to join");
  std::vector<Segment> segments;
  for (const auto& path : paths) {
    segments.push_back(openSegment(path));
    const std::string why = difference(segments.front(), segments.back());
    if (!why.empty()) {
      throw std::invalid_argument(
          fmt::format("{} cannot follow {}: {}", path.string(), segments.front().path.string(), why));
    }
  }

  output::PendingOutput out(output);
  const std::string temp = "file:" + out.reopenablePath().string();
  AVFormatContext* raw = nullptr;
  check(avformat_alloc_output_context2(&raw, nullptr, "mp4", temp.c_str()), "avformat_alloc_output_context2(mp4)");
  const libav::OutputFormatPtr fmt(raw);
  AVStream* stream = avformat_new_stream(raw, nullptr);
  if (!stream) throw OutputError("avformat_new_stream: out of memory");
  const AVStream* in = segments.front().video;
  check(avcodec_parameters_copy(stream->codecpar, in->codecpar), "avcodec_parameters_copy");
  stream->codecpar->codec_tag = 0;  // the muxer picks the tag for its container
  stream->time_base = in->time_base;
  stream->avg_frame_rate = in->avg_frame_rate;

  AVDictionary* fileOptions = nullptr;
  check(av_dict_set(&fileOptions, "truncate", "0", 0), "av_dict_set(truncate)");
  const int openResult = avio_open2(&raw->pb, temp.c_str(), AVIO_FLAG_WRITE, nullptr, &fileOptions);
  av_dict_free(&fileOptions);
  check(openResult, "avio_open2(" + output.string() + ")");
  AVDictionary* muxOptions = nullptr;
  check(av_dict_set(&muxOptions, "movflags", "+faststart", 0), "av_dict_set(movflags)");
  const int headerResult = avformat_write_header(raw, &muxOptions);
  av_dict_free(&muxOptions);
  check(headerResult, "avformat_write_header(" + output.string() + ")");

  const libav::PacketPtr packet(av_packet_alloc());
  if (!packet) throw OutputError("av_packet_alloc: out of memory");
  ConcatSummary summary;
  int64_t offset = 0;  // in the output stream's time base: where the current segment starts
  int64_t lastDts = INT64_MIN;
  for (Segment& s : segments) {
    int64_t end = offset;
    while (true) {
      const int err = av_read_frame(s.format.get(), packet.get());
      if (err == AVERROR_EOF) break;
      if (err < 0) throw std::invalid_argument(libav::describe(s.path.string() + ": av_read_frame", err));
      if (packet->stream_index != s.video->index) {
        av_packet_unref(packet.get());
        continue;
      }
      av_packet_rescale_ts(packet.get(), s.video->time_base, stream->time_base);
      if (packet->pts != AV_NOPTS_VALUE) {
        packet->pts += offset;
        end = std::max(end, packet->pts + packet->duration);
      }
      if (packet->dts != AV_NOPTS_VALUE) {
        packet->dts += offset;
        // Alike segments have the same reorder delay, so decoding times stay increasing.
        if (packet->dts <= lastDts) {
          throw std::invalid_argument(fmt::format("{}: its decoding times overlap the segment before", s.path.string()));
        }
        lastDts = packet->dts;
      }
      packet->stream_index = stream->index;
      packet->pos = -1;
      check(av_interleaved_write_frame(raw, packet.get()), "av_interleaved_write_frame(" + output.string() + ")");
      ++summary.frames;
    }
    offset = end;
  }
  check(av_write_trailer(raw), "av_write_trailer(" + output.string() + ")");
  check(avio_closep(&raw->pb), "avio_closep(" + output.string() + ")");
  out.commit();
  summary.seconds = double(offset) * av_q2d(stream->time_base);
  return summary;
}

}  // namespace particles::render
