#pragma once
// The one way the program runs work on threads (docs/architecture.md, "Threads"). Every thread the
// program starts is a WorkerPool's: a System's pool runs the parallel loops of derivEval, the
// integrators and the solvers; the stability study's trials, golden check's entries and the
// renderer's encoder run on pools of their own. A pool has two ways in:
// - run(count, task): task(0) … task(count − 1), each once, on the pool's threads and the caller's,
//   returning when all have returned. The chunked loops below (forChunks, sumChunks, anyOf) are
//   built on it, and so are sets of coarse tasks, fewer or more than the threads: one search loop
//   per thread (src/core/stability.cpp), one golden entry per task.
// - start(task): one task on one of the pool's threads while the caller goes on, until the handle's
//   wait(). A producer/consumer pair is one started task, the consumer, behind a bounded queue its
//   user owns (render/video/frame_pipeline.hpp: encoding frame n while frame n + 1 is drawn).
//
// The determinism contract, stated here once (the rest of the program refers to it): the same
// bytes on 1 or 64 threads, because
// 1. Work is cut before any thread sees it. What task k does depends on k and the problem, never on
//    the thread count or on which thread runs it. A loop over n items is split into chunks of a
//    fixed `grain` (chunk k is [k·grain, (k+1)·grain)), so which items share a chunk depends on n
//    and the grain alone.
// 2. A task writes only what is its own: its chunk's items (elementwise loops, a gather by point),
//    its entry of a vector indexed by k. A sum is formed per chunk, and the chunk sums are added in
//    chunk order (sumChunks). Nothing adds into a shared double from two threads, and no atomic
//    touches a double.
// 3. Tasks run, and finish, in any order, on however many threads there are (a thread the system
//    refuses to start, or threads that are not free: the caller takes what is left). A user that
//    reacts to the order (the stability study starts trials on speculation as verdicts arrive) keeps
//    only results that do not depend on it (a verdict is the same whenever it is reached).
// 4. A started task is one call on one thread: what it does in order stays in that order (frames are
//    encoded in the order they were queued).
// tests/test_worker_pool.cpp checks the pool, the determinism tests (tests/test_determinism*.cpp,
// test_stability_threads.cpp, test_render*.cpp) their outputs for 1–8 threads, byte for byte, and
// the TSan build (-DPARTICLES_TSAN=ON) the pool's synchronisation.
//
// Nesting. Pools share nothing (no global state), so a task may own and use a pool of its own (a
// trial's System with a pool, inside the study's): each pool's threads are its own. A task that
// calls run on a pool it is already running a task of (directly, or through another pool's task)
// gets that loop on its own thread, in index order: the same results (point 3), no deadlock. One
// thread hands a pool its work, besides those nested calls: the thread that owns it.
//
// A loop of one chunk runs on the calling thread with no hand-over at all, so small scenes (the 25²
// cloth: 1,200 springs) cost what they did before the pool existed.
//
// fork(). A child process has the forking thread alone: its pools' workers are the parent's, not
// its own, and joining them would wait forever. A pool used in a child (a loop, start, or its
// destructor) leaves those copies alone (their handles kept, unused) and starts workers of its own.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace particles {

// The most threads a simulation may be given: the command line's --threads and PARTICLES_THREADS,
// the library's Simulation(…, threads) and setThreads.
inline constexpr int kMaxThreads = 1024;

class WorkerPool;

// How many fork()s separate this process from the one that first asked (a pthread_atfork handler
// counts them in each child, registered at the first call): a thread pool, or a GL context with
// threads of its own, that was made at another count was made in an ancestor, and its threads are
// not in this process. A relaxed load, where getpid() would be a system call.
unsigned forkCount();

namespace detail {
// The pools whose tasks a thread is running, innermost first (worker_pool.cpp).
struct InsideTask {
  const WorkerPool* pool;
  const InsideTask* outer;
};
}  // namespace detail

class WorkerPool {
 public:
  class Started;

  // `threads` counts the calling thread: 1 starts no thread. Values below 1 are taken as 1. The
  // threads start at the first job handed out (a run of more than one task, or a start), so a
  // scene whose loops are all one chunk long never starts any.
  explicit WorkerPool(int threads = 1);
  // Waits for a started task that was not waited for (dropping its exception), then ends the
  // threads. A pool never used, or idle, ends at once.
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return threads_; }

  // Calls task(k) once for every k in [0, count) and returns when all calls have returned; the
  // calling thread takes tasks too. The first exception a task throws is rethrown here, after
  // every call has ended (the others still run). When the pool's threads are not free for it (one
  // thread, a started task holding them, or a call from inside one of this pool's tasks) the
  // calling thread runs every task itself, in index order.
  template <typename Task>
  void run(size_t count, Task&& task) {
    if (count == 0) return;
    if (count == 1 || threads_ == 1 || count > kMostChunks || !threadsFree()) {
      std::exception_ptr error;
      for (size_t k = 0; k < count; ++k) {
        try {
          task(k);
        } catch (...) {
          if (!error) error = std::current_exception();
        }
      }
      if (error) std::rethrow_exception(error);
      return;
    }
    using Plain = std::remove_reference_t<Task>;
    dispatch(count, &task, [](void* context, size_t k) { (*static_cast<Plain*>(context))(k); });
  }

  // Starts task() on one of the pool's threads and returns at once: the caller goes on with its
  // own work while the task runs (Box2D's enqueueTask / finishTask, for one task). The pool takes
  // no other job until the handle's wait(); a run meanwhile runs on the calling thread. Throws
  // std::logic_error when a started task is not yet waited for or when called from one of this
  // pool's tasks, std::invalid_argument on a pool of one thread (it has none besides the
  // caller's), and std::system_error when the system refuses to start any thread.
  [[nodiscard]] Started start(std::function<void()> task);

  // A started task. wait() returns when the task has returned and rethrows its exception; if no
  // thread has taken the task by then, the waiting thread runs it. Destroying a handle that was not
  // waited for waits and drops the exception. A handle must not outlive its pool.
  class Started {
   public:
    Started(Started&& other) noexcept : pool_(std::exchange(other.pool_, nullptr)) {}
    Started& operator=(Started&&) = delete;
    ~Started();
    void wait();  // once; afterwards the handle is empty

   private:
    friend class WorkerPool;
    explicit Started(WorkerPool* pool) : pool_(pool) {}
    WorkerPool* pool_;
  };

 private:
  using Trampoline = void (*)(void* context, size_t k);
  struct Job {
    void* context = nullptr;
    Trampoline call = nullptr;
    size_t count = 0;
    // The pools whose tasks the publishing thread was inside: the job's tasks are inside them too.
    const detail::InsideTask* outer = nullptr;
  };
  // A job as published: its fields are atomics because a worker may read a slot while the owner
  // writes the job two generations later into it; the ticket tells the worker afterwards (below).
  struct JobSlot {
    std::atomic<void*> context{nullptr};
    std::atomic<Trampoline> call{nullptr};
    std::atomic<size_t> count{0};
    std::atomic<const detail::InsideTask*> outer{nullptr};
  };
  // The ticket: the job's generation in the high half, the next chunk to take in the low half. A
  // worker takes chunk k of generation g by one compare-and-swap from (g, k) to (g, k + 1), so a
  // worker that arrives after the job has ended (the ticket has moved on to g + 1) can take
  // nothing of the new job by mistake, without any lock or count of the workers inside.
  static constexpr int kGenerationShift = 32;
  static constexpr size_t kMostChunks = 0xffffffffu;  // a run of more tasks runs on the calling thread
  static uint32_t generationOf(uint64_t ticket) { return uint32_t(ticket >> kGenerationShift); }
  static size_t chunkOf(uint64_t ticket) { return size_t(ticket & 0xffffffffu); }

  bool runningOwnTask() const;  // whether this thread is inside one of this pool's tasks
  bool inheritedWorkers() const;  // whether workers_ were started in the process this one forked from
  void dropInheritedWorkers();    // detaches them, and makes the state they shared anew
  bool threadsFree() const;     // see run
  void startWorkers();
  void dispatch(size_t count, void* context, Trampoline call);
  void publish(const Job& job);
  void finishJob();  // takes the job's chunks left, waits for the rest, rethrows the first exception
  void workerLoop();
  // Takes chunks of `job`, generation `generation`, until none is left of it.
  void takeChunks(const Job& job, uint32_t generation);
  Job readSlot(uint32_t generation) const;

  int threads_ = 1;
  std::vector<std::thread> workers_;  // threads_ − 1 of them once started
  unsigned workersFork_ = 0;          // the process's fork count (worker_pool.cpp) when they started
  // Handing a job out takes no lock: the owner writes the job into the slot of its generation's
  // parity and then the ticket; idle workers poll the ticket for a while (kSpinTime) and only then
  // sleep on wake_. The owner takes the lock only when some worker sleeps (sleepers_), a finishing
  // worker only when the owner sleeps (ownerWaiting_): a loop of the 316² cloth's step on 16
  // threads costs a few microseconds of hand-over instead of one lock per worker (bench/README.md,
  // "The core past two threads").
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  JobSlot slots_[2];
  // The ticket and the finished count on cache lines of their own: threads polling the ticket do
  // not lose their copy each time a chunk is counted finished, nor the counters theirs to the polls.
  alignas(64) std::atomic<uint64_t> ticket_{0};
  std::atomic<int> sleepers_{0};          // workers asleep on wake_, or about to be
  std::atomic<bool> ownerWaiting_{false}; // the owner asleep on done_, or about to be
  std::atomic<bool> stopping_{false};
  alignas(64) std::atomic<size_t> finished_{0};  // the job's chunks whose call has returned
  std::exception_ptr error_;         // the first exception of the job's tasks, under mutex_
  std::atomic<bool> failed_{false};  // whether error_ is set: the owner looks without the lock
  // The started task: set by the owning thread before the job that calls it is published.
  std::function<void()> started_;
  bool startedPending_ = false;  // until the handle's wait(); the owning thread's alone
};

// The chunks a loop over n items is cut into: ⌈n / grain⌉, at least 1 when n > 0.
inline size_t chunkCount(size_t n, size_t grain) {
  return grain == 0 ? (n > 0) : (n + grain - 1) / grain;
}

// Calls body(begin, end) on the chunks of [0, n) (see above); pool may be null (serial).
// Without a pool the chunks run one after the other on the calling thread, the same calls as on
// threads (a chunk's work may depend on which chunk it is: DampedSpringForce's chunk-local values).
template <typename Body>
void forChunks(WorkerPool* pool, size_t n, size_t grain, Body&& body) {
  const size_t chunks = chunkCount(n, grain);
  if (chunks <= 1 || pool == nullptr) {
    for (size_t k = 0; k < chunks; ++k) body(k * grain, std::min(n, (k + 1) * grain));
    return;
  }
  pool->run(chunks, [&](size_t k) { body(k * grain, std::min(n, (k + 1) * grain)); });
}

// Entries per chunk of a whole-vector update (128 KiB of doubles): the state of the 25² cloth is
// one chunk, the 316² cloth's 25.
constexpr size_t kVectorChunk = 16384;
// Points per chunk of derivEval's passes over the points (System::derivEval).
constexpr size_t kPointChunk = 4096;

// Calls body(start, length) over the chunks of a vector of n entries: for elementwise updates,
// whose results do not depend on the split at all.
template <typename Body>
void forSegments(WorkerPool* pool, long n, Body&& body) {
  forChunks(pool, size_t(n), kVectorChunk, [&](size_t begin, size_t end) { body(long(begin), long(end - begin)); });
}

// Whether hit(i) holds for some i in [0, n), the chunks on the pool: a yes/no that no order of
// the chunks can change. `found` is scratch (kept by the caller, so the loop does not allocate).
template <typename Hit>
bool anyOf(WorkerPool* pool, size_t n, size_t grain, std::vector<char>& found, Hit&& hit) {
  found.assign(chunkCount(n, grain), 0);
  forChunks(pool, n, grain, [&](size_t begin, size_t end) {
    // The whole chunk, into a local flag: no early exit, so the loop can vectorise (a hit is the rare
    // case), and no store to `found` (chars) inside it, which would make every load repeat.
    bool any = false;
    for (size_t i = begin; i < end; ++i) any |= hit(i);
    found[begin / grain] = any ? 1 : 0;
  });
  return std::find(found.begin(), found.end(), 1) != found.end();
}

// Σ over the chunks of [0, n) of part(begin, end), added in chunk order: the same bits for every
// thread count. `partials` is scratch (kept by the caller, so the loop does not allocate).
template <typename Part>
double sumChunks(WorkerPool* pool, size_t n, size_t grain, std::vector<double>& partials, Part&& part) {
  const size_t chunks = chunkCount(n, grain);
  if (chunks <= 1) return n > 0 ? part(size_t(0), n) : 0.0;
  partials.resize(chunks);
  auto one = [&](size_t k) { partials[k] = part(k * grain, std::min(n, (k + 1) * grain)); };
  if (pool == nullptr) {
    for (size_t k = 0; k < chunks; ++k) one(k);
  } else {
    pool->run(chunks, one);
  }
  double sum = 0.0;
  for (size_t k = 0; k < chunks; ++k) sum += partials[k];
  return sum;
}

}  // namespace particles
