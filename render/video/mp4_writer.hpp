#pragma once
// H.264 MP4 output (docs/physics.md §9) through libavcodec (libx264) and libavformat, encoded
// in-process frame by frame: RGBA → yuv420p (BT.709, limited range, tagged as such), frame i at
// i / fps, an even size (render/video/yuv_video_writer.hpp), muxed with "+faststart" (the index moves to
// the front at the end so players can start before the whole file has arrived).

#include "render/video/frame_writer.hpp"
#include "render/video/yuv_video_writer.hpp"

namespace particles::render {

class Mp4Writer final : public YuvVideoWriter {
 public:
  // Opens the encoder and the temporary file and writes the header. Throws std::invalid_argument
  // for bad options, OutputError naming the failing libav call and its message.
  Mp4Writer(const std::filesystem::path& path, const FrameWriterOptions& options);
};

}  // namespace particles::render
