#pragma once
// Dense polylines thinned before cairo strokes them: consecutive points whose x falls in the same
// column of the output keep only the first, the lowest, the highest and the last, in their order
// (M4: Jugel et al., "M4: A Visualization-Oriented Time Series Data Aggregation", PVLDB 7(10),
// 2014; matplotlib's path simplification does the like). Within one column the full polyline is
// connected and passes through the column's lowest and highest points, so it covers the column
// from its minimum to its maximum; so does the reduced one, and both leave the column at the same
// points. Where they differ is where inside the column (less than its width) the strokes run.
// Internal to plot/.
//
// Why: cairo rasterises a stroke as one polygon, at a cost that grows with its edges times the rows
// they cross: 100,000 points alternating ±1 took seconds to draw into a PNG, and a small
// cost per row once reduced (bench/bench_plot.cpp; bench/README.md, "Figures of long runs").

#include <cstddef>
#include <vector>

namespace particles::plot {

struct Point {
  double x, y;  // pixels
};

// The column width, for every format: a quarter of a figure pixel, so that the reduced line runs
// within 0.25 px of the full one (and an SVG or PDF still looks the same zoomed in 4×). Measured on
// a 1200 × 800 stats figure of 100,000 rows (a random walk): with whole-pixel columns the PNG
// differed from the full line's by up to 205 of 255 in 0.5 % of its pixels; with quarter pixels by
// at most 49, in 0.01 % (tests/test_plot_reduction.cpp checks the same on a small image). The
// price: quarter pixels take about twice the CPU of whole ones (bench/README.md, "Figures of long
// runs").
inline constexpr double kReductionColumnPx = 0.25;

// `run` reduced column by column (columns are [k·w, (k + 1)·w) in x for integer k, w =
// columnWidthPx > 0). A column with at most 4 consecutive points keeps them all, so a polyline
// with at most one point per column comes back unchanged. Points keep their order; each kept point
// is one of the input's, unchanged.
std::vector<Point> reduceToColumns(const std::vector<Point>& run, double columnWidthPx);

}  // namespace particles::plot
