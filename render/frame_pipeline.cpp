#include "render/frame_pipeline.hpp"

#include <algorithm>

namespace particles::render {

FramePipeline::FramePipeline(size_t capacity, Consumer consume)
    : capacity_(std::max<size_t>(1, capacity)), consume_(std::move(consume)), worker_([this] { run(); }) {}

FramePipeline::~FramePipeline() {
  cancel();
}

void FramePipeline::rethrowIfFailed() {
  if (error_) std::rethrow_exception(error_);
}

void FramePipeline::push(const Image& frame) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < capacity_ || error_ || cancelled_; });
  rethrowIfFailed();
  if (cancelled_ || closing_) throw std::logic_error("FramePipeline::push after close or cancel");
  Image buffer;
  if (!spare_.empty()) {
    buffer = std::move(spare_.back());
    spare_.pop_back();
  }
  lock.unlock();
  // Copy outside the lock; assign() reuses the spare buffer's memory when the size matches.
  buffer.width = frame.width;
  buffer.height = frame.height;
  buffer.rgba.assign(frame.rgba.begin(), frame.rgba.end());
  lock.lock();
  queue_.push_back(std::move(buffer));
  changed_.notify_all();
}

void FramePipeline::close() {
  {
    std::unique_lock lock(mutex_);
    closing_ = true;
    changed_.notify_all();
  }
  if (worker_.joinable()) worker_.join();
  std::unique_lock lock(mutex_);
  rethrowIfFailed();
}

void FramePipeline::cancel() noexcept {
  {
    std::unique_lock lock(mutex_);
    cancelled_ = true;
    queue_.clear();
    changed_.notify_all();
  }
  if (worker_.joinable()) worker_.join();
}

void FramePipeline::run() {
  long index = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return !queue_.empty() || closing_ || cancelled_; });
    if (cancelled_ || queue_.empty()) return;  // cancelled, or closing with nothing left
    Image frame = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();  // room for the producer
    lock.unlock();
    try {
      consume_(frame, index++);
    } catch (...) {
      lock.lock();
      error_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
      return;
    }
    lock.lock();
    spare_.push_back(std::move(frame));
  }
}

}  // namespace particles::render
