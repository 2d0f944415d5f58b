#include "render/video/pipelined_frame_writer.hpp"

#include <stdexcept>

namespace particles::render {

void PipelinedFrameWriter::write(const Image& frame) {
  if (finished_ || aborted_) throw std::logic_error("write to " + what_ + " after finish or abort");
  if (frame.width != width_ || frame.height != height_) {
    throw std::invalid_argument("frame is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + ", " +
                                what_ + " " + std::to_string(width_) + "x" + std::to_string(height_));
  }
  try {
    pipeline_->push(frame);
  } catch (...) {
    abort();
    throw;
  }
  ++frames_;
}

void PipelinedFrameWriter::finish() {
  if (finished_ || aborted_) throw std::logic_error("finish of " + what_ + " called twice or after abort");
  try {
    pipeline_->close();  // the worker has stopped: what it used is this thread's again
    publish();
  } catch (...) {
    abort();
    throw;
  }
  finished_ = true;
}

void PipelinedFrameWriter::abort() noexcept {
  if (aborted_ || finished_) return;
  aborted_ = true;
  if (pipeline_) pipeline_->cancel();
  discard();
}

}  // namespace particles::render
