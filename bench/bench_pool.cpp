// What the worker pool itself costs (src/core/worker_pool.hpp), apart from any physics: the
// question of what holds the 316² cloth's step on many threads. A step of that cloth is a handful
// of passes over its state (25 chunks of kVectorChunk entries, or of kPointChunk points), each one
// pool.run on T threads (the second argument; the first is the chunk count):
//   BM_PoolHandOut   a run of that many tasks that do nothing: the hand-out and the join alone,
//                    the floor under every pass on T threads
//   BM_PoolCopy      forSegments copying the 316² cloth's state (399,424 doubles, 3.2 MB), the
//                    explosion guard's backup: a whole-state pass that does only memory traffic
// Wall time (the pool's threads are the point), and the process's CPU time beside it: spinning
// threads show there.
#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include "core/worker_pool.hpp"

namespace {

using namespace particles;

void BM_PoolHandOut(benchmark::State& state) {
  const size_t tasks = size_t(state.range(0));
  WorkerPool pool(int(state.range(1)));
  std::vector<char> touched(tasks);
  for (auto _ : state) {
    pool.run(tasks, [&](size_t k) { touched[k] = 1; });
    benchmark::DoNotOptimize(touched.data());
  }
}

void BM_PoolCopy(benchmark::State& state) {
  constexpr long kEntries = 4 * 316 * 316;  // positions and velocities, two coordinates each
  WorkerPool pool(int(state.range(0)));
  WorkerPool* used = state.range(0) > 1 ? &pool : nullptr;  // as System::pool(): none on one thread
  const Eigen::VectorXd from = Eigen::VectorXd::LinSpaced(kEntries, 0.0, 1.0);
  Eigen::VectorXd to(kEntries);
  for (auto _ : state) {
    forSegments(used, kEntries, [&](long i, long n) { to.segment(i, n) = from.segment(i, n); });
    benchmark::DoNotOptimize(to.data());
  }
  state.SetBytesProcessed(state.iterations() * kEntries * long(sizeof(double)) * 2);
}

BENCHMARK(BM_PoolHandOut)
    ->ArgsProduct({{25}, {2, 4, 8, 16}})
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PoolCopy)
    ->ArgsProduct({{1, 2, 4, 8, 16}})
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
