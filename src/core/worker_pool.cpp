#include "core/worker_pool.hpp"

#include <chrono>
#include <system_error>

namespace particles {

namespace {

// How long an idle thread keeps polling for the next job before it sleeps: a derivEval hands out
// several loops a few hundred microseconds apart, and waking a sleeping thread costs tens of
// microseconds; beyond this, polling would only take the CPU from other processes.
constexpr auto kSpinTime = std::chrono::microseconds(100);

void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Polls `done` for up to kSpinTime; true when it turned true.
template <typename Done>
bool spinUntil(Done&& done) {
  const auto until = std::chrono::steady_clock::now() + kSpinTime;
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    cpuRelax();
    if (i % 64 == 0 && std::chrono::steady_clock::now() > until) return false;
  }
}

}  // namespace

WorkerPool::WorkerPool(int threads) : threads_(std::max(threads, 1)) {}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void WorkerPool::takeChunks(const Job& job) {
  for (;;) {
    const size_t k = next_.fetch_add(1, std::memory_order_relaxed);
    if (k >= job.count) return;
    try {
      job.call(job.context, k);
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    // acq_rel: the task's writes happen before the caller sees the count complete.
    if (finished_.fetch_add(1, std::memory_order_acq_rel) + 1 == job.count) {
      std::lock_guard lock(mutex_);
      done_.notify_one();
    }
  }
}

void WorkerPool::workerLoop() {
  size_t seen = 0;
  for (;;) {
    spinUntil([&] { return generation_.load(std::memory_order_acquire) != seen; });
    Job job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || generation_.load(std::memory_order_relaxed) != seen; });
      if (stopping_) return;
      seen = generation_.load(std::memory_order_relaxed);
      job = job_;
      ++inside_;
    }
    takeChunks(job);
    {
      std::lock_guard lock(mutex_);
      --inside_;
    }
    done_.notify_one();
  }
}

void WorkerPool::dispatch(size_t count, void* context, Trampoline call) {
  if (workers_.empty()) {
    workers_.reserve(size_t(threads_ - 1));
    // A thread the system refuses to start (std::system_error) leaves fewer to share the chunks,
    // which changes the time taken, never the result.
    try {
      for (int i = 1; i < threads_; ++i) workers_.emplace_back([this] { workerLoop(); });
    } catch (const std::system_error&) {
    }
  }
  {
    std::unique_lock lock(mutex_);
    // A worker that joined the last job late may still be taking (empty) chunks: next_ is its
    // until it leaves.
    done_.wait(lock, [&] { return inside_ == 0; });
    job_ = Job{context, call, count};
    next_.store(0, std::memory_order_relaxed);
    finished_.store(0, std::memory_order_relaxed);
    error_ = nullptr;
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
  takeChunks(job_);
  const auto allDone = [&] { return finished_.load(std::memory_order_acquire) == count; };
  if (!spinUntil(allDone)) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, allDone);
  }
  std::exception_ptr error;
  {
    std::lock_guard lock(mutex_);
    error = std::exchange(error_, nullptr);
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace particles
