// The hand-over cost of a parallel loop: the core's WorkerPool against an OpenMP parallel for, both on 2
// threads, each loop two chunks of 8,192 multiply-adds (the grain of the core's loops), and the same
// work on one thread. docs/architecture.md ("Threads") cites it for the choice of the pool. Not part of
// the build (it needs -fopenmp); run it with
//   g++ -O2 -std=c++20 -fopenmp -Isrc bench/standalone/pool_vs_openmp.cpp src/core/worker_pool.cpp -o pool_vs_openmp && ./pool_vs_openmp
#include "core/worker_pool.hpp"
#include <chrono>
#include <cstdio>
#include <vector>
#include <omp.h>
using namespace particles;
int main() {
  std::vector<double> x(2 * 8192, 1.0);
  const int reps = 50000;
  WorkerPool pool(2);
  auto work = [&](size_t k) { for (size_t i = k * 8192; i < (k + 1) * 8192; ++i) x[i] = x[i] * 1.0000001 + 1e-9; };
  for (int w = 0; w < 2; ++w) {
    auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) pool.run(2, work);
    auto t1 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) {
#pragma omp parallel for num_threads(2) schedule(static)
      for (int k = 0; k < 2; ++k) work(size_t(k));
    }
    auto t2 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) { work(0); work(1); }
    auto t3 = std::chrono::steady_clock::now();
    auto us = [&](auto a, auto b) { return std::chrono::duration<double, std::micro>(b - a).count() / reps; };
    std::printf("pool %.2f us  openmp %.2f us  serial %.2f us per loop of 2 chunks\n", us(t0, t1), us(t1, t2), us(t2, t3));
  }
}
