#pragma once
// Internal to render/: what the MP4 (H.264) and WebM (VP9) writers share. Their pipeline's slots
// are yuv420p pictures (yuva420p with alpha), filled by render/video/yuv420.hpp straight from the
// renderer's image as each frame is queued (no other copy of it is made) and encoded by a
// VideoEncoder on the worker; frame i has pts i in a 1/fps time base, so the video has exactly as
// many frames as were written and lasts frames / fps. A derived writer only configures the encoder.
//
// Odd sizes are an error, not padded: yuv420p stores colour at half resolution. Padding would
// silently change the size the user asked for (and the camera's framing); an error names the
// nearest even size instead.

#include <memory>
#include <vector>

#include "render/video/frame_writer.hpp"
#include "render/video/single_file_writer.hpp"

namespace particles::render {

class VideoEncoder;

class YuvVideoWriter : public SingleFileWriter {
 public:
  ~YuvVideoWriter() override;  // abort() unless finished

 protected:
  // Opens the temporary output; the derived constructor then configures an encoder and start()s.
  YuvVideoWriter(const std::filesystem::path& path, const FrameWriterOptions& options);
  // A VideoEncoder for `muxer` and `encoder` writing to this writer's temporary, with the size,
  // time base (1/fps), pixel format (yuva420p with `alpha`, else yuv420p) and BT.709 limited-range
  // colour tags of the frames set.
  std::unique_ptr<VideoEncoder> makeEncoder(const char* muxer, const char* encoder, bool alpha) const;
  // Opens the configured encoder (writing the header with `muxerOptions`), makes the slots and
  // starts the pipeline.
  void start(std::unique_ptr<VideoEncoder> encoder,
             const std::vector<std::pair<std::string, std::string>>& muxerOptions);

 private:
  void complete() override;
  void release() noexcept override;

  struct Encoder;
  std::unique_ptr<Encoder> encoder_;
  FrameWriterOptions options_;
};

// Throws std::invalid_argument unless the format's row takes the size (checkFrameSize: even sides,
// at least 2 × 2), fps is kMinFps … kMaxFps and the keyframe interval in range.
void validateYuvVideo(const OutputFormat& format, const FrameWriterOptions& options);

}  // namespace particles::render
