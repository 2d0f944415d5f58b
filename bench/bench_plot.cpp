// A stats figure of a long run (100,000 rows once took 8.8 s to become a PNG): R rows whose energies alternate ±1 from row to row,
// the worst case for a line chart (every pixel column is crossed top to bottom many times), drawn
// by renderFigure into a 1200 × 800 PNG, SVG or PDF (the encoded bytes, in memory; no file). The
// table is built and statsFigure called outside the clock; inside it: axes, the lines (reduced to at
// most 4 points per quarter-pixel column, plot/column_reduction.hpp), text, and the encoder.
// `time_per_row` is CPU time per figure divided by R.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "plot/figure.hpp"
#include "plot/stats_figure.hpp"

namespace {

using namespace particles;

plot::StatsTable alternating(std::size_t rows) {
  plot::StatsTable table;
  for (std::size_t i = 0; i < rows; ++i) {
    const double v = i % 2 ? 1.0 : -1.0;
    table.t.push_back(0.001 * double(i));
    table.kinetic.push_back(v);
    table.potential.push_back(0);
    table.total.push_back(v);
    table.constraintError.push_back(0);
    table.penetration.push_back(0);
  }
  return table;
}

void BM_PlotAlternating(benchmark::State& state, plot::ImageFormat format) {
  const std::size_t rows = std::size_t(state.range(0));
  const plot::Figure figure = plot::statsFigure(alternating(rows));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<std::uint8_t> encoded = plot::renderFigure(figure, format);
    bytes = encoded.size();
    benchmark::DoNotOptimize(encoded.data());
  }
  state.counters["time_per_row"] = benchmark::Counter(double(rows) * double(state.iterations()),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["bytes"] = double(bytes);
}

}  // namespace

BENCHMARK_CAPTURE(BM_PlotAlternating, png, plot::ImageFormat::Png)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(300'000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlotAlternating, svg, plot::ImageFormat::Svg)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(300'000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PlotAlternating, pdf, plot::ImageFormat::Pdf)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(300'000)
    ->Unit(benchmark::kMillisecond);
