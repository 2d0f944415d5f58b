// The core's threads (src/core/worker_pool.hpp): every chunk runs once whatever the thread count,
// exceptions reach the caller after every chunk has ended, and chunked sums are the same bits for
// 1–8 threads. Run under ThreadSanitizer too (scripts/test's TSan stage).
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/worker_pool.hpp"

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
