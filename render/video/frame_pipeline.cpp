#include "render/video/frame_pipeline.hpp"

#include <algorithm>
#include <stdexcept>

namespace particles::render {

std::size_t FramePipeline::slotCount(std::size_t capacity) {
  return capacity == 0 ? 1 : capacity + 2;
}

FramePipeline::FramePipeline(std::size_t capacity, Fill fill, Consumer consume)
    : capacity_(capacity), fill_(std::move(fill)), consume_(std::move(consume)) {
  for (std::size_t slot = slotCount(capacity); slot-- > 0;) free_.push_back(slot);  // slot 0 is used first
  if (capacity_ > 0) worker_.emplace(pool_.start([this] { run(); }));
}

FramePipeline::~FramePipeline() {
  cancel();
}

void FramePipeline::rethrowIfFailed() {
  if (error_) std::rethrow_exception(error_);
}

void FramePipeline::push(const Image& frame) {
  pushWith([&](std::size_t slot) { fill_(frame, slot); });
}

void FramePipeline::pushWith(const std::function<void(std::size_t slot)>& fill) {
  if (capacity_ == 0) {
    if (error_) std::rethrow_exception(error_);
    if (cancelled_ || closing_) throw std::logic_error("FramePipeline::push after close or cancel");
    fill(0);
    try {
      consume_(0, consumed_++);
    } catch (...) {
      error_ = std::current_exception();  // a failed encoder takes no more frames
      throw;
    }
    return;
  }
  std::unique_lock lock(mutex_);
  // Queue not full implies a free slot: capacity_ queued + 1 consumed leave one of slotCount.
  changed_.wait(lock, [&] { return queue_.size() < capacity_ || error_ || cancelled_; });
  rethrowIfFailed();
  if (cancelled_ || closing_) throw std::logic_error("FramePipeline::push after close or cancel");
  const std::size_t slot = free_.back();
  free_.pop_back();
  lock.unlock();
  try {
    fill(slot);  // outside the lock: the worker goes on consuming meanwhile
  } catch (...) {
    lock.lock();
    free_.push_back(slot);
    throw;
  }
  lock.lock();
  queue_.push_back(slot);
  changed_.notify_all();
}

void FramePipeline::close() {
  {
    std::unique_lock lock(mutex_);
    closing_ = true;
    changed_.notify_all();
  }
  if (worker_) worker_->wait();  // run() throws nothing: a consumer's exception is kept in error_
  worker_.reset();
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
  worker_.reset();  // waits for run()
}

void FramePipeline::run() {
  long index = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return !queue_.empty() || closing_ || cancelled_; });
    if (cancelled_ || queue_.empty()) return;  // cancelled, or closing with nothing left
    const std::size_t slot = queue_.front();
    queue_.pop_front();
    changed_.notify_all();  // room for the producer
    lock.unlock();
    try {
      consume_(slot, index++);
    } catch (...) {
      lock.lock();
      error_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
      return;
    }
    lock.lock();
    free_.push_back(slot);
  }
}

}  // namespace particles::render
