#pragma once
// H.264 MP4 output (docs/physics.md §9) through libavcodec (libx264) and libavformat, encoded
// in-process frame by frame: RGBA → yuv420p (BT.709, limited range, tagged as such; converted by
// render/yuv420.hpp as the frame is queued, no other copy of it is made), the
// send-frame / receive-packet loop of FFmpeg's encode_video.c, muxed as in mux.c with
// "+faststart" (the index moves to the front at the end so players can start before the whole
// file has arrived). Frame i has pts i in a 1/fps time base: the video has exactly as many frames
// as were written and lasts frames / fps.
//
// Odd sizes are an error, not padded: yuv420p stores colour at half resolution, so x264 needs an
// even width and height. Padding would silently change the size the user asked for (and the
// camera's framing); an error names the nearest even size instead.

#include "render/frame_pipeline.hpp"
#include "render/frame_writer.hpp"
#include "render/pipelined_frame_writer.hpp"
#include "output/pending_output.hpp"

namespace particles::render {

class Mp4Writer final : public PipelinedFrameWriter {
 public:
  // Opens the encoder and the temporary file and writes the header. Throws std::invalid_argument
  // for bad options, OutputError naming the failing libav call and its message.
  Mp4Writer(const std::filesystem::path& path, const FrameWriterOptions& options);
  ~Mp4Writer() override;  // abort() unless finished

  void finish() override;
  void abort() noexcept override;
  const std::filesystem::path& destination() const override { return out_.destination(); }

 private:
  struct Encoder;
  output::PendingOutput out_;  // first: the output is discarded after the encoder has closed its own descriptor
  std::unique_ptr<Encoder> encoder_;
};

}  // namespace particles::render
