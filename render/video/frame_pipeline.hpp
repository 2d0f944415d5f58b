#pragma once
// Internal to render/: a consumer task behind a bounded queue of frames, so that rendering frame
// n+1 overlaps encoding frame n. The consumer is a task started on a WorkerPool of two threads, the
// caller's and one more (core/worker_pool.hpp: the program's one way onto threads, and its
// determinism contract); the queue is this class's, and a started task is one call on one thread,
// so frames are consumed in the order they were pushed. The frames live in slots the writer owns,
// in whatever form its encoder takes (an RGBA Image for PNG, a yuv420p AVFrame for H.264): push()
// hands a free slot and the renderer's image to `fill` on the calling thread (a copy or a
// conversion, straight into the slot, so the frame is never copied twice), queues it, and blocks
// while the queue is full; the consumer calls `consume` for each queued slot in order and then
// frees it. An exception thrown by `fill` propagates from push(); one thrown by `consume` stops the
// consumer and is rethrown by the next push() or close().
// A capacity of 0 starts no thread: push() fills and consumes each frame on the calling thread
// (a render held to one thread, `particles render --threads 1`).

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "core/worker_pool.hpp"
#include "render/image.hpp"

namespace particles::render {

class FramePipeline {
 public:
  // Slots are numbered 0 … slotCount(capacity) − 1; a slot is touched by one thread at a time.
  using Fill = std::function<void(const Image& frame, std::size_t slot)>;
  using Consumer = std::function<void(std::size_t slot, long index)>;

  // The slots a pipeline of `capacity` queued frames uses: those queued, the one being filled and
  // the one being consumed (one, without a worker).
  static std::size_t slotCount(std::size_t capacity);

  FramePipeline(std::size_t capacity, Fill fill, Consumer consume);
  ~FramePipeline();  // cancel()
  FramePipeline(const FramePipeline&) = delete;
  FramePipeline& operator=(const FramePipeline&) = delete;

  void push(const Image& frame);
  // The same with a slot filled by `fill` instead of the pipeline's Fill (a pipeline of other
  // things than images: render/video/render_simulation.cpp's drawings).
  void pushWith(const std::function<void(std::size_t slot)>& fill);
  // Waits until every queued frame is consumed and stops the worker; rethrows its error.
  void close();
  // Drops queued frames, waits for the frame in progress and stops the worker. Never throws.
  void cancel() noexcept;

 private:
  void run();
  void rethrowIfFailed();  // with the lock held

  const std::size_t capacity_;  // 0: no worker
  long consumed_ = 0;           // frames consumed without a worker
  Fill fill_;
  Consumer consume_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::size_t> queue_;  // filled slots, oldest first
  std::vector<std::size_t> free_;  // slots no thread is using
  bool closing_ = false, cancelled_ = false;
  std::exception_ptr error_;
  WorkerPool pool_{2};
  // run() on pool_, while it may be running; last: started after everything it uses exists.
  std::optional<WorkerPool::Started> worker_;
};

}  // namespace particles::render
