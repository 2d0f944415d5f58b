// The program's one way onto threads (src/core/worker_pool.hpp): every chunk runs once whatever the
// thread count, exceptions reach the caller after every chunk has ended, and chunked sums are the
// same bits for 1–8 threads; coarse tasks, more of them than threads, each with a System of its
// own (nested pools); a task that calls run on its own pool; a task started in the background and
// waited for; pools destroyed idle. Run under ThreadSanitizer too (scripts/test's TSan stage).
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/solver.hpp"
#include "core/worker_pool.hpp"
#include "scenario/scenario.hpp"

using particles::chunkCount;
using particles::forChunks;
using particles::sumChunks;
using particles::WorkerPool;

TEST_CASE("worker pool: every task index runs exactly once, for any count and thread number") {
  for (int threads : {1, 2, 3, 4, 8}) {
    WorkerPool pool(threads);
    CHECK(pool.threads() == threads);
    for (size_t count : {size_t(0), size_t(1), size_t(2), size_t(7), size_t(64), size_t(1000)}) {
      std::vector<int> hits(count, 0);
      pool.run(count, [&](size_t k) { ++hits[k]; });
      for (size_t k = 0; k < count; ++k) REQUIRE(hits[k] == 1);
    }
  }
  CHECK(WorkerPool(0).threads() == 1);
  CHECK(WorkerPool(-3).threads() == 1);
}

TEST_CASE("worker pool: many short jobs in a row (the hand-over between jobs)") {
  WorkerPool pool(4);
  std::vector<long> sums(20000, 0);
  for (size_t job = 0; job < sums.size(); ++job) {
    std::vector<long> parts(3, 0);
    pool.run(parts.size(), [&](size_t k) { parts[k] = long(job * 10 + k); });
    sums[job] = parts[0] + parts[1] + parts[2];
  }
  for (size_t job = 0; job < sums.size(); ++job) REQUIRE(sums[job] == long(job * 30 + 3));
}

TEST_CASE("worker pool: late threads never take a chunk of the next job (the ticket's generation)") {
  // Jobs of 1 to 5 chunks, one after another on 8 threads, some chunks slow: a thread that arrives
  // after its job has ended finds the ticket on a later generation and takes nothing of that job by
  // mistake. Each chunk of each job runs exactly once, with the job's own task.
  WorkerPool pool(8);
  for (int job = 0; job < 5000; ++job) {
    const size_t count = size_t(job % 5) + 1;
    std::vector<int> hits(count, 0);
    std::vector<int> owner(count, -1);
    pool.run(count, [&, job](size_t k) {
      ++hits[k];
      owner[k] = job;
      if (job % 97 == 0) std::this_thread::sleep_for(std::chrono::microseconds(50));
    });
    for (size_t k = 0; k < count; ++k) {
      REQUIRE(hits[k] == 1);
      REQUIRE(owner[k] == job);
    }
  }
}

TEST_CASE("worker pool: threads that went to sleep between jobs wake for the next one") {
  // Longer than the threads' polling (100 µs) between jobs: each job is handed to sleeping threads,
  // and a slow chunk makes the owner sleep too, waiting for the last one.
  WorkerPool pool(4);
  for (int job = 0; job < 20; ++job) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::atomic<int> ran{0};
    pool.run(16, [&](size_t k) {
      if (k == 3) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      ++ran;
    });
    REQUIRE(ran.load() == 16);
  }
}

TEST_CASE("worker pool: a task's exception reaches the caller after every task has ended") {
  for (int threads : {1, 2, 4}) {
    WorkerPool pool(threads);
    std::atomic<int> ran{0};
    CHECK_THROWS_AS(pool.run(50,
                             [&](size_t k) {
                               ++ran;
                               if (k == 7) throw std::runtime_error("chunk 7");
                             }),
                    std::runtime_error);
    CHECK(ran.load() == 50);
    // The pool is still usable.
    std::vector<int> hits(10, 0);
    pool.run(hits.size(), [&](size_t k) { hits[k] = 1; });
    for (int h : hits) CHECK(h == 1);
  }
}

TEST_CASE("worker pool: chunks depend on n and the grain alone") {
  CHECK(chunkCount(0, 100) == 0);
  CHECK(chunkCount(1, 100) == 1);
  CHECK(chunkCount(100, 100) == 1);
  CHECK(chunkCount(101, 100) == 2);
  for (int threads : {1, 3}) {
    WorkerPool pool(threads);
    std::vector<std::pair<size_t, size_t>> seen(4, {0, 0});
    forChunks(&pool, 350, 100, [&](size_t b, size_t e) { seen[b / 100] = {b, e}; });
    CHECK(seen[0] == std::pair<size_t, size_t>(0, 100));
    CHECK(seen[3] == std::pair<size_t, size_t>(300, 350));
  }
}

TEST_CASE("worker pool: a chunked sum is the same bits for every thread count") {
  std::vector<double> x(100003);
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(double(i)) * std::pow(10.0, double(i % 17) - 8.0);
  auto part = [&](size_t b, size_t e) {
    double s = 0.0;
    for (size_t i = b; i < e; ++i) s += x[i];
    return s;
  };
  std::vector<double> scratch;
  const double serial = sumChunks(nullptr, x.size(), 1000, scratch, part);
  for (int threads : {1, 2, 3, 4, 8}) {
    WorkerPool pool(threads);
    const double threaded = sumChunks(&pool, x.size(), 1000, scratch, part);
    CHECK(std::memcmp(&serial, &threaded, sizeof serial) == 0);
  }
}

namespace {

// Long enough for any thread to be scheduled on a loaded machine; a test that reaches it has failed.
constexpr auto kPatience = std::chrono::seconds(30);

// A flag one thread raises and another waits for, at most kPatience: whether it was raised.
class Signal {
 public:
  void raise() {
    std::lock_guard lock(mutex_);
    raised_ = true;
    changed_.notify_all();
  }
  bool waitRaised() {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, kPatience, [&] { return raised_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool raised_ = false;
};

}  // namespace

TEST_CASE("worker pool: coarse tasks, many more than threads, each run once and kept by index") {
  WorkerPool pool(3);
  std::vector<double> results(40, 0.0);
  std::vector<std::atomic<int>> runs(results.size());
  pool.run(results.size(), [&](size_t k) {
    ++runs[k];
    double s = 0.0;  // a task of some length, so that the threads overlap
    for (int i = 1; i <= 20000; ++i) s += std::sin(double(k * 20000 + i));
    results[k] = s;
  });
  for (size_t k = 0; k < results.size(); ++k) {
    CAPTURE(k);
    REQUIRE(runs[k].load() == 1);
    double s = 0.0;
    for (int i = 1; i <= 20000; ++i) s += std::sin(double(k * 20000 + i));
    CHECK(std::memcmp(&s, &results[k], sizeof s) == 0);
  }
}

// A trial of the stability study (or a golden entry) steps a System whose pool is its own, from a
// task of another pool: the 70² cloth (4,900 points: 2 chunks of the pointwise passes, 9,660
// springs: 2 chunks), 2 threads inside each of 5 tasks on 3 threads, against one thread alone.
TEST_CASE("worker pool: tasks that each step a System with a pool of its own give the serial bits") {
  const auto step = [](int threads) {
    const std::filesystem::path cloth = std::filesystem::path(PARTICLES_SOURCE_DIR) / "scenarios/cloth.yaml";
    const std::vector<particles::scenario::Override> size{{"grids.0.size", "[70, 70]", "test"}};
    particles::System system = particles::scenario::loadScenarioFile(cloth, size).system;
    system.setThreads(threads);
    particles::Solver solver(particles::Integrator::rk4);
    for (int k = 0; k < 3; ++k) solver.doStep(system, 0.002);
    return system.state();
  };
  const Eigen::VectorXd serial = step(1);
  std::vector<Eigen::VectorXd> states(5);
  WorkerPool outer(3);
  outer.run(states.size(), [&](size_t k) { states[k] = step(2); });
  for (const Eigen::VectorXd& state : states) {
    REQUIRE(state.size() == serial.size());
    CHECK(std::memcmp(state.data(), serial.data(), sizeof(double) * size_t(serial.size())) == 0);
  }
}

TEST_CASE("worker pool: a task that calls run on its own pool runs that loop on its own thread") {
  for (int threads : {2, 4}) {
    CAPTURE(threads);
    WorkerPool pool(threads);
    std::vector<std::vector<int>> hits(6, std::vector<int>(10, 0));
    std::vector<std::thread::id> outerThread(hits.size());
    std::vector<char> innerOnOuterThread(hits.size(), 1);
    pool.run(hits.size(), [&](size_t k) {
      outerThread[k] = std::this_thread::get_id();
      pool.run(hits[k].size(), [&](size_t i) {
        ++hits[k][i];
        if (std::this_thread::get_id() != outerThread[k]) innerOnOuterThread[k] = 0;
      });
    });
    for (size_t k = 0; k < hits.size(); ++k) {
      CAPTURE(k);
      for (int h : hits[k]) CHECK(h == 1);
      CHECK(innerOnOuterThread[k] == 1);
    }
    // Through another pool's task too, on that pool's threads: pool's task → its own pool's task →
    // pool.run.
    std::atomic<int> calls{0};
    pool.run(3, [&](size_t) {
      WorkerPool inner(2);
      inner.run(2, [&](size_t) { pool.run(4, [&](size_t) { ++calls; }); });
    });
    CHECK(calls.load() == 3 * 2 * 4);
    // The pool hands out work as before once the nested calls are over.
    std::vector<std::thread::id> ran(64);
    pool.run(ran.size(), [&](size_t k) { ran[k] = std::this_thread::get_id(); });
    for (const std::thread::id& id : ran) CHECK(id != std::thread::id());
  }
}

TEST_CASE("worker pool: a started task runs beside the caller until waited for") {
  WorkerPool pool(2);
  Signal callerGoesOn, taskRan;
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id taskThread;
  bool sawCaller = false;
  WorkerPool::Started started = pool.start([&] {
    taskThread = std::this_thread::get_id();
    sawCaller = callerGoesOn.waitRaised();  // only if start() returned while this task runs
    taskRan.raise();
  });
  callerGoesOn.raise();
  CHECK(taskRan.waitRaised());
  started.wait();
  CHECK(sawCaller);
  CHECK(taskThread != caller);
  // A second start, once the first was waited for; a run afterwards uses the threads again.
  std::atomic<int> count{0};
  pool.start([&] { ++count; }).wait();
  CHECK(count.load() == 1);
  std::vector<int> hits(32, 0);
  pool.run(hits.size(), [&](size_t k) { ++hits[k]; });
  for (int h : hits) CHECK(h == 1);
}

TEST_CASE("worker pool: a started task's exception reaches wait(), and the pool goes on") {
  WorkerPool pool(3);
  WorkerPool::Started failing = pool.start([] { throw std::runtime_error("the encoder failed"); });
  CHECK_THROWS_WITH_AS(failing.wait(), "the encoder failed", std::runtime_error);
  CHECK_NOTHROW(failing.wait());  // the handle is empty now
  // Not waited for: the handle's destructor waits and drops the exception.
  {
    WorkerPool::Started dropped = pool.start([] { throw std::runtime_error("dropped"); });
  }
  std::atomic<int> count{0};
  pool.start([&] { ++count; }).wait();
  CHECK(count.load() == 1);
  CHECK_THROWS_AS(pool.run(8,
                           [](size_t k) {
                             if (k == 5) throw std::runtime_error("task 5");
                           }),
                  std::runtime_error);
}

TEST_CASE("worker pool: while a started task runs, run takes the calling thread alone and start refuses") {
  WorkerPool pool(4);
  Signal release;
  WorkerPool::Started started = pool.start([&] {
    CHECK(release.waitRaised());
    // From the started task itself: run on its own thread, start refused.
    const std::thread::id self = std::this_thread::get_id();
    bool allHere = true;
    pool.run(8, [&](size_t) { allHere = allHere && std::this_thread::get_id() == self; });
    CHECK(allHere);
    CHECK_THROWS_AS(static_cast<void>(pool.start([] {})), std::logic_error);
  });
  const std::thread::id caller = std::this_thread::get_id();
  bool allOnCaller = true;
  pool.run(16, [&](size_t) { allOnCaller = allOnCaller && std::this_thread::get_id() == caller; });
  CHECK(allOnCaller);
  CHECK_THROWS_AS(static_cast<void>(pool.start([] {})), std::logic_error);
  release.raise();
  started.wait();
  CHECK_THROWS_AS(static_cast<void>(WorkerPool(1).start([] {})), std::invalid_argument);
}

TEST_CASE("worker pool: a pool destroyed while idle ends at once, used or not") {
  for (int threads : {1, 2, 8}) {
    CAPTURE(threads);
    { WorkerPool unused(threads); }
    WorkerPool pool(threads);
    std::vector<int> hits(16, 0);
    pool.run(hits.size(), [&](size_t k) { ++hits[k]; });
    // Past the threads' polling: they sleep on the condition variable when the destructor wakes them.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  {
    WorkerPool pool(2);
    pool.start([] {}).wait();  // the thread that ran it is idle again
  }
  {
    WorkerPool pool(3);
    pool.run(4, [](size_t) {});  // destroyed while its threads still poll
  }
}
