#pragma once
// What every writer shares: frames are size-checked and queued to a FramePipeline whose worker
// encodes them; a failure while queueing aborts the writer. finish() waits for the worker and then
// publishes the output; abort(), or a failure in either, stops the worker and discards it.

#include <memory>
#include <string>

#include "render/video/frame_pipeline.hpp"
#include "render/video/frame_writer.hpp"

namespace particles::render {

class PipelinedFrameWriter : public FrameWriter {
 public:
  void write(const Image& frame) final;
  void finish() final;
  void abort() noexcept final;
  long framesWritten() const final { return frames_; }

 protected:
  // `what` names the output in messages ("the video", "the sequence").
  PipelinedFrameWriter(int width, int height, std::string what)
      : width_(width), height_(height), what_(std::move(what)) {}

  // Called by finish() once the pipeline's worker has stopped: completes the output and moves it
  // into place. Throws OutputError.
  virtual void publish() = 0;
  // Removes whatever the writer wrote, the worker stopped. Never throws. abort() calls it, so a
  // derived destructor calls abort() (unless finished): a base destructor cannot.
  virtual void discard() noexcept = 0;

  std::unique_ptr<FramePipeline> pipeline_;  // set by the derived constructor
  int width_, height_;
  long frames_ = 0;
  bool finished_ = false, aborted_ = false;

 private:
  std::string what_;
};

}  // namespace particles::render
