#include "core/worker_pool.hpp"

#include <chrono>
#include <stdexcept>
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

using detail::InsideTask;

// The pools whose tasks this thread is running, innermost first, through the threads that handed
// those tasks out: a task that calls run on one of them must not wait for that pool's threads (it
// holds one of them, or its caller waits for this very task in that pool's job).
thread_local const InsideTask* insideTasks = nullptr;

class EnterTask {
 public:
  EnterTask(const WorkerPool* pool, const InsideTask* outer) : here_{pool, outer}, saved_(insideTasks) {
    insideTasks = &here_;
  }
  ~EnterTask() { insideTasks = saved_; }
  EnterTask(const EnterTask&) = delete;
  EnterTask& operator=(const EnterTask&) = delete;

 private:
  InsideTask here_;
  const InsideTask* saved_;
};

}  // namespace

WorkerPool::WorkerPool(int threads) : threads_(std::max(threads, 1)) {}

WorkerPool::~WorkerPool() {
  if (startedPending_) {
    // Its handle is still alive, or was leaked: either way the task must end before the threads.
    startedPending_ = false;
    try {
      finishJob();
    } catch (...) {
    }
  }
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

bool WorkerPool::runningOwnTask() const {
  for (const InsideTask* t = insideTasks; t != nullptr; t = t->outer) {
    if (t->pool == this) return true;
  }
  return false;
}

bool WorkerPool::threadsFree() const {
  // startedPending_ is the owning thread's: a task of this pool stops at the first test.
  return !runningOwnTask() && !startedPending_;
}

void WorkerPool::takeChunks(const Job& job) {
  const EnterTask entered(this, job.outer);
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

void WorkerPool::startWorkers() {
  if (!workers_.empty()) return;
  workers_.reserve(size_t(threads_ - 1));
  // A thread the system refuses to start (std::system_error) leaves fewer to share the chunks,
  // which changes the time taken, never the result.
  try {
    for (int i = 1; i < threads_; ++i) workers_.emplace_back([this] { workerLoop(); });
  } catch (const std::system_error&) {
  }
}

void WorkerPool::publish(const Job& job) {
  {
    std::unique_lock lock(mutex_);
    // A worker that joined the last job late may still be taking (empty) chunks: next_ is its
    // until it leaves.
    done_.wait(lock, [&] { return inside_ == 0; });
    job_ = job;
    next_.store(0, std::memory_order_relaxed);
    finished_.store(0, std::memory_order_relaxed);
    error_ = nullptr;
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
}

void WorkerPool::finishJob() {
  // job_ is this thread's to read: only it publishes, and not before this job is finished.
  takeChunks(job_);
  const auto allDone = [&] { return finished_.load(std::memory_order_acquire) == job_.count; };
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

void WorkerPool::dispatch(size_t count, void* context, Trampoline call) {
  startWorkers();
  publish(Job{context, call, count, insideTasks});
  finishJob();
}

WorkerPool::Started WorkerPool::start(std::function<void()> task) {
  if (runningOwnTask()) throw std::logic_error("WorkerPool::start: called from one of the pool's own tasks");
  if (startedPending_) throw std::logic_error("WorkerPool::start: the task started before was not waited for");
  if (threads_ == 1) throw std::invalid_argument("WorkerPool::start: a pool of one thread has none to start a task on");
  startWorkers();
  if (workers_.empty()) {
    throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again),
                            "WorkerPool::start: no thread could be started");
  }
  started_ = std::move(task);
  startedPending_ = true;
  // Outside any other pool's task: the caller goes on and may leave the tasks it is inside of.
  publish(Job{&started_, [](void* context, size_t) { (*static_cast<std::function<void()>*>(context))(); }, 1, nullptr});
  return Started(this);
}

void WorkerPool::Started::wait() {
  WorkerPool* pool = std::exchange(pool_, nullptr);
  if (pool == nullptr || !pool->startedPending_) return;
  pool->startedPending_ = false;
  pool->finishJob();
}

WorkerPool::Started::~Started() {
  try {
    wait();
  } catch (...) {  // the documented behaviour: wait() is where the exception is seen
  }
}

}  // namespace particles
