#pragma once
// Internal to render/: a worker thread behind a bounded queue of frames, so that rendering frame
// n+1 overlaps encoding frame n. push() copies the frame into a recycled buffer and blocks while
// the queue is full; the worker calls `consume` for each frame in order. An exception thrown by
// `consume` stops the worker and is rethrown by the next push() or close().

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "render/image.hpp"

namespace particles::render {

class FramePipeline {
 public:
  using Consumer = std::function<void(const Image& frame, long index)>;

  FramePipeline(size_t capacity, Consumer consume);
  ~FramePipeline();  // cancel()
  FramePipeline(const FramePipeline&) = delete;
  FramePipeline& operator=(const FramePipeline&) = delete;

  void push(const Image& frame);
  // Waits until every queued frame is consumed and stops the worker; rethrows its error.
  void close();
  // Drops queued frames, waits for the frame in progress and stops the worker. Never throws.
  void cancel() noexcept;

 private:
  void run();
  void rethrowIfFailed();  // with the lock held

  const size_t capacity_;
  Consumer consume_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Image> queue_;
  std::vector<Image> spare_;  // consumed buffers, reused by push()
  bool closing_ = false, cancelled_ = false;
  std::exception_ptr error_;
  std::thread worker_;  // last: started after everything it uses exists
};

}  // namespace particles::render
