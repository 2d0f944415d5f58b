#pragma once
// The core's threads (docs/architecture.md, "Threads"): a System owns one WorkerPool, and every
// parallel loop of derivEval, the integrators and the solvers runs on it.
//
// Results never depend on how many threads run, because the work is cut before any thread sees it:
// a loop over n items is split into chunks of a fixed `grain` (chunk k is [k·grain, (k+1)·grain)),
// so which items share a chunk depends on n and the grain alone. Threads take whole chunks, in any
// order; a chunk writes only its own items (elementwise loops, a gather by point), and a sum is
// formed per chunk and the chunk sums are added in chunk order (sumChunks). Nothing adds into a
// shared double from two threads, and no atomic touches a double.
//
// A loop of one chunk runs on the calling thread with no hand-over at all, so small scenes (the 25²
// cloth: 1,200 springs) cost what they did before the pool existed.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace particles {

class WorkerPool {
 public:
  // `threads` counts the calling thread: 1 starts no thread. Values below 1 are taken as 1. The
  // threads start at the first job of more than one chunk, so a scene whose loops are all one
  // chunk long never starts any.
  explicit WorkerPool(int threads = 1);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return threads_; }

  // Calls task(k) once for every k in [0, count) and returns when all calls have returned; the
  // calling thread takes chunks too. The first exception a task throws is rethrown here, after
  // every call has ended (the others still run). Not reentrant: a task must not call run.
  template <typename Task>
  void run(size_t count, Task&& task) {
    if (count == 0) return;
    if (count == 1 || threads_ == 1) {
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

 private:
  using Trampoline = void (*)(void* context, size_t k);
  struct Job {
    void* context = nullptr;
    Trampoline call = nullptr;
    size_t count = 0;
  };

  void dispatch(size_t count, void* context, Trampoline call);
  void workerLoop();
  void takeChunks(const Job& job);

  int threads_ = 1;
  std::vector<std::thread> workers_;  // threads_ − 1 of them once started
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  // The current job, published under mutex_ with a new generation (read without the lock only to
  // spin on it); a worker copies it under mutex_ when it joins.
  Job job_;
  std::atomic<size_t> generation_{0};
  bool stopping_ = false;            // under mutex_
  size_t inside_ = 0;                // workers that joined the current job and have not left, under mutex_
  std::atomic<size_t> next_{0};      // the job's next chunk to take
  std::atomic<size_t> finished_{0};  // the job's chunks whose call has returned
  std::exception_ptr error_;         // the first exception of the job's tasks, under mutex_
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
