#pragma once
// What the MP4 and PNG-sequence writers share: frames are size-checked and queued to a
// FramePipeline whose worker encodes them; a failure while queueing aborts the writer.

#include <memory>
#include <string>

#include "render/frame_pipeline.hpp"
#include "render/frame_writer.hpp"

namespace particles::render {

class PipelinedFrameWriter : public FrameWriter {
 public:
  void write(const Image& frame) final;
  long framesWritten() const final { return frames_; }

 protected:
  // `what` names the output in messages ("the video", "the sequence").
  PipelinedFrameWriter(int width, int height, std::string what)
      : width_(width), height_(height), what_(std::move(what)) {}

  std::unique_ptr<FramePipeline> pipeline_;  // set by the derived constructor
  int width_, height_;
  long frames_ = 0;
  bool finished_ = false, aborted_ = false;

 private:
  std::string what_;
};

}  // namespace particles::render
