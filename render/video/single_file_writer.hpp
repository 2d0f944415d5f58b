#pragma once
// What the MP4, WebM and GIF writers share: one output file (output::PendingOutput: an anonymous
// temporary until finish() moves it over the destination) encoded by the writer's pipeline.
// finish() stops the pipeline, lets the writer complete the file and publishes it; abort(), a
// failure in finish(), or destroying an unfinished writer removes it.

#include <filesystem>
#include <string>

#include "output/pending_output.hpp"
#include "render/video/pipelined_frame_writer.hpp"

namespace particles::render {

class SingleFileWriter : public PipelinedFrameWriter {
 public:
  const std::filesystem::path& destination() const final { return out_.destination(); }

 protected:
  // Opens the temporary output. `what` names the output in messages ("the video").
  SingleFileWriter(const std::filesystem::path& path, int width, int height, std::string what);

  // Called by finish() once the pipeline's worker has stopped: whatever completes the file
  // (flushing the encoder, the trailer, closing it). Throws OutputError.
  virtual void complete() = 0;
  // Frees the encoder, closing its own descriptors of the file: after complete(), or on abort.
  // Never throws.
  virtual void release() noexcept = 0;

  output::PendingOutput out_;  // a base member: discarded after the derived writer has released it

 private:
  void publish() final;
  void discard() noexcept final;
};

}  // namespace particles::render
