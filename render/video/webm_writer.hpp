#pragma once
// WebM output: VP9 through libavcodec's libvpx-vp9 encoder, muxed by libavformat's webm muxer,
// encoded in-process frame by frame as the MP4 is (render/video/yuv_video_writer.hpp: RGBA → yuv420p,
// BT.709 limited range, frame i at i / fps, an even size). With FrameWriterOptions::alpha the
// frames are yuva420p: libvpx encodes the alpha plane as a second VP9 stream that the muxer stores
// beside each frame (Matroska BlockAdditions) and flags on the track (AlphaMode 1); browsers show
// it over the page. Decoders that ignore it (libavcodec's own vp9) see the colour alone.
//
// Constant quality (crf, bit rate 0, as libvpx's VP9 guide recommends for files rather than
// streams), keyframes at most VideoOptions::keyintSeconds apart like the MP4, and deadline "good"
// with cpu-used kVp9CpuUsed. The muxer writes no random track ids (bitexact): the same frames give
// the same file.

#include "render/video/frame_writer.hpp"
#include "render/video/yuv_video_writer.hpp"

namespace particles::render {

class WebmWriter final : public YuvVideoWriter {
 public:
  // Opens the encoder and the temporary file and writes the header. Throws std::invalid_argument
  // for bad options, OutputError naming the failing libav call and its message.
  WebmWriter(const std::filesystem::path& path, const FrameWriterOptions& options);
};

}  // namespace particles::render
