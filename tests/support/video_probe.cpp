#include "support/video_probe.hpp"

#include "render/errors.hpp"
#include "render/video/libav_util.hpp"

extern "C" {
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <memory>

namespace particles::test {

using render::Image;
using render::OutputError;
using render::libav::check;
namespace libav = render::libav;

namespace {

struct SwsDeleter {
  void operator()(SwsContext* s) const { sws_freeContext(s); }
};

Image toRgba(const AVFrame* f) {
  Image image(f->width, f->height);
  std::unique_ptr<SwsContext, SwsDeleter> sws(
      sws_getContext(f->width, f->height, AVPixelFormat(f->format), f->width, f->height, AV_PIX_FMT_RGBA,
                     SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr, nullptr));
  if (!sws) throw OutputError("sws_getContext(→ RGBA): unsupported conversion");
  const int space = f->colorspace == AVCOL_SPC_BT709 ? SWS_CS_ITU709 : SWS_CS_DEFAULT;
  const int fullRange = f->color_range == AVCOL_RANGE_JPEG ? 1 : 0;
  if (sws_setColorspaceDetails(sws.get(), sws_getCoefficients(space), fullRange, sws_getCoefficients(space), 1, 0,
                               1 << 16, 1 << 16) < 0) {
    throw OutputError("sws_setColorspaceDetails: not supported");
  }
  uint8_t* dst[1] = {image.rgba.data()};
  const int dstStride[1] = {int(image.stride())};
  if (sws_scale(sws.get(), f->data, f->linesize, 0, f->height, dst, dstStride) != f->height) {
    throw OutputError("sws_scale(→ RGBA) failed");
  }
  return image;
}

}  // namespace

VideoInfo probeVideo(const std::filesystem::path& path, long sampleFrame, const std::string& decoderName) {
  const std::string name = path.string();
  AVFormatContext* raw = nullptr;
  check(avformat_open_input(&raw, name.c_str(), nullptr, nullptr), "avformat_open_input(" + name + ")");
  libav::InputFormatPtr format(raw);
  check(avformat_find_stream_info(raw, nullptr), "avformat_find_stream_info(" + name + ")");
  const AVCodec* decoder = nullptr;
  const int streamIndex = av_find_best_stream(raw, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  check(streamIndex, "av_find_best_stream(video, " + name + ")");
  const AVStream* stream = raw->streams[streamIndex];
  if (!decoderName.empty()) {
    decoder = avcodec_find_decoder_by_name(decoderName.c_str());
    if (!decoder) throw OutputError("avcodec_find_decoder_by_name(" + decoderName + "): not in this libavcodec");
  }

  VideoInfo info;
  info.codec = avcodec_get_name(stream->codecpar->codec_id);
  const char* pix = av_get_pix_fmt_name(AVPixelFormat(stream->codecpar->format));
  info.pixelFormat = pix ? pix : "none";
  info.width = stream->codecpar->width;
  info.height = stream->codecpar->height;
  info.fps = av_q2d(stream->avg_frame_rate);
  if (const AVDictionaryEntry* alpha = av_dict_get(stream->metadata, "alpha_mode", nullptr, 0)) {
    info.alphaMode = alpha->value;
  }
  info.durationSeconds = stream->duration != AV_NOPTS_VALUE ? double(stream->duration) * av_q2d(stream->time_base)
                                                            : double(raw->duration) / AV_TIME_BASE;

  libav::CodecContextPtr codec(avcodec_alloc_context3(decoder));
  if (!codec) throw OutputError("avcodec_alloc_context3: out of memory");
  check(avcodec_parameters_to_context(codec.get(), stream->codecpar), "avcodec_parameters_to_context");
  check(avcodec_open2(codec.get(), decoder, nullptr), std::string("avcodec_open2(") + decoder->name + ")");
  libav::PacketPtr packet(av_packet_alloc());
  libav::FramePtr frame(av_frame_alloc());
  if (!packet || !frame) throw OutputError("av_packet_alloc/av_frame_alloc: out of memory");

  auto receiveAll = [&] {
    for (;;) {
      const int ret = avcodec_receive_frame(codec.get(), frame.get());
      if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
      check(ret, "avcodec_receive_frame");
      if (info.frames == 0) {
        const char* decoded = av_get_pix_fmt_name(AVPixelFormat(frame->format));
        info.decodedPixelFormat = decoded ? decoded : "none";
      }
      if (info.frames == sampleFrame) info.sample = toRgba(frame.get());
      ++info.frames;
      av_frame_unref(frame.get());
    }
  };
  for (;;) {
    const int ret = av_read_frame(raw, packet.get());
    if (ret == AVERROR_EOF) break;
    check(ret, "av_read_frame(" + name + ")");
    if (packet->stream_index == streamIndex) {
      const int sent = avcodec_send_packet(codec.get(), packet.get());
      av_packet_unref(packet.get());
      check(sent, "avcodec_send_packet");
      receiveAll();
    } else {
      av_packet_unref(packet.get());
    }
  }
  check(avcodec_send_packet(codec.get(), nullptr), "avcodec_send_packet(flush)");
  receiveAll();
  return info;
}

}  // namespace particles::test
