#include "core/worker_pool.hpp"

#include <pthread.h>

#include <chrono>
#include <new>
#include <stdexcept>
#include <system_error>
#include <thread>

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

// Polls `done` for up to kSpinTime; true when it turned true. After the first few polls it yields
// between them: where every CPU has work (a render's stepping, drawing and encoding threads all at
// once), the polling thread gives its CPU to one that has some, which a pause never does; on an
// idle CPU, yield returns at once (bench/README.md, "Polling that yields").
template <typename Done>
bool spinUntil(Done&& done) {
  const auto until = std::chrono::steady_clock::now() + kSpinTime;
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    if (i < 64) {
      cpuRelax();
    } else {
      std::this_thread::yield();
    }
    if (i % 64 == 0 && std::chrono::steady_clock::now() > until) return false;
  }
}

std::atomic<unsigned> forksSoFar{0};

}  // namespace

unsigned forkCount() {
  static const bool registered = ::pthread_atfork(nullptr, nullptr, [] { forksSoFar.fetch_add(1); }) == 0;
  (void)registered;
  return forksSoFar.load(std::memory_order_relaxed);
}

namespace {

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

WorkerPool::WorkerPool(int threads) : threads_(std::max(threads, 1)), workersFork_(forkCount()) {}

bool WorkerPool::inheritedWorkers() const {
  return !workers_.empty() && workersFork_ != forkCount();
}

void WorkerPool::dropInheritedWorkers() {
  if (!inheritedWorkers()) return;
  // No such thread here: neither joined nor detached (pthread_detach refuses the parent's handle,
  // and std::thread then throws), the handles are kept, unused, for the life of the process.
  new std::vector<std::thread>(std::move(workers_));
  workers_.clear();
  // A worker of the parent may have been inside the lock or a wait at the fork: the copies of the
  // mutex and the condition variables are left as they are (never destroyed, never used) and new
  // ones made in their place, with no sleeper and no started task (its thread is not here).
  new (&mutex_) std::mutex;
  new (&wake_) std::condition_variable;
  new (&done_) std::condition_variable;
  sleepers_.store(0);
  ownerWaiting_.store(false);
  error_ = nullptr;
  failed_.store(false);
  startedPending_ = false;
  workersFork_ = forkCount();
}

WorkerPool::~WorkerPool() {
  dropInheritedWorkers();
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
    stopping_.store(true);
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

WorkerPool::Job WorkerPool::readSlot(uint32_t generation) const {
  // Acquire: if a field shows a later job's value (the owner has moved on by two generations), the
  // owner's move of the ticket past `generation` happened before, so the worker's compare-and-swap
  // in takeChunks fails and the mixed copy is never called.
  const JobSlot& slot = slots_[generation & 1u];
  return Job{slot.context.load(std::memory_order_acquire), slot.call.load(std::memory_order_acquire),
             slot.count.load(std::memory_order_acquire), slot.outer.load(std::memory_order_acquire)};
}

void WorkerPool::takeChunks(const Job& job, uint32_t generation) {
  const EnterTask entered(this, job.outer);
  for (;;) {
    uint64_t ticket = ticket_.load(std::memory_order_relaxed);
    do {
      if (generationOf(ticket) != generation || chunkOf(ticket) >= job.count) return;
    } while (!ticket_.compare_exchange_weak(ticket, ticket + 1, std::memory_order_acquire, std::memory_order_relaxed));
    try {
      job.call(job.context, chunkOf(ticket));
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);  // published by the increment below
    }
    // The task's writes happen before the owner sees the count complete (seq_cst: see ownerWaiting_
    // in finishJob).
    if (finished_.fetch_add(1) + 1 == job.count && ownerWaiting_.load()) {
      std::lock_guard lock(mutex_);
      done_.notify_one();
    }
  }
}

void WorkerPool::workerLoop() {
  uint32_t seen = 0;
  for (;;) {
    uint64_t ticket = 0;
    const auto jobOrStop = [&] {
      ticket = ticket_.load();
      return generationOf(ticket) != seen || stopping_.load(std::memory_order_relaxed);
    };
    if (!spinUntil(jobOrStop)) {
      std::unique_lock lock(mutex_);
      // seq_cst, with publish's store of the ticket and load of sleepers_: either the owner sees
      // this worker asleep (and takes the lock before it notifies), or jobOrStop sees the job.
      sleepers_.fetch_add(1);
      wake_.wait(lock, jobOrStop);
      sleepers_.fetch_sub(1);
    }
    if (stopping_.load()) return;
    seen = generationOf(ticket);
    takeChunks(readSlot(seen), seen);
  }
}

void WorkerPool::startWorkers() {
  dropInheritedWorkers();
  if (!workers_.empty()) return;
  workersFork_ = forkCount();
  workers_.reserve(size_t(threads_ - 1));
  // A thread the system refuses to start (std::system_error) leaves fewer to share the chunks,
  // which changes the time taken, never the result.
  try {
    for (int i = 1; i < threads_; ++i) workers_.emplace_back([this] { workerLoop(); });
  } catch (const std::system_error&) {
  }
}

void WorkerPool::publish(const Job& job) {
  // The job before this one has ended (finishJob), so no worker holds a chunk of it and none can
  // take one: the counters and the slot of this generation's parity are the owner's to set.
  const uint32_t generation = generationOf(ticket_.load(std::memory_order_relaxed)) + 1;
  JobSlot& slot = slots_[generation & 1u];
  slot.context.store(job.context, std::memory_order_release);
  slot.call.store(job.call, std::memory_order_release);
  slot.count.store(job.count, std::memory_order_release);
  slot.outer.store(job.outer, std::memory_order_release);
  finished_.store(0, std::memory_order_relaxed);
  ticket_.store(uint64_t(generation) << kGenerationShift);
  if (sleepers_.load() > 0) {
    { std::lock_guard lock(mutex_); }
    wake_.notify_all();
  }
}

void WorkerPool::finishJob() {
  // The job in its slot: only this thread publishes, and not before this job is finished.
  const uint32_t generation = generationOf(ticket_.load(std::memory_order_relaxed));
  const Job job = readSlot(generation);
  takeChunks(job, generation);
  const auto allDone = [&] { return finished_.load() == job.count; };
  if (!spinUntil(allDone)) {
    std::unique_lock lock(mutex_);
    // seq_cst, with the last worker's increment and load of ownerWaiting_ (takeChunks).
    ownerWaiting_.store(true);
    done_.wait(lock, allDone);
    ownerWaiting_.store(false, std::memory_order_relaxed);
  }
  // Every task has returned, so error_ is this thread's to take (and to clear for the next job).
  if (!failed_.load(std::memory_order_relaxed)) return;
  failed_.store(false, std::memory_order_relaxed);
  std::exception_ptr error;
  {
    std::lock_guard lock(mutex_);
    error = std::exchange(error_, nullptr);
  }
  std::rethrow_exception(error);
}

void WorkerPool::dispatch(size_t count, void* context, Trampoline call) {
  startWorkers();
  publish(Job{context, call, count, insideTasks});
  finishJob();
}

WorkerPool::Started WorkerPool::start(std::function<void()> task) {
  dropInheritedWorkers();
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
