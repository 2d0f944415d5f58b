// Dense lines thinned to at most 4 points per column before cairo strokes them
// (plot/column_reduction.hpp): sparse lines unchanged, each column's extremes kept, the same pixels.
// 100,000 rows alternating ±1 once took 8.8 s to draw as a PNG.

#include <cairo.h>
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "plot/column_reduction.hpp"
#include "plot/figure.hpp"
#include "plot/palette.hpp"
#include "plot_support.hpp"

using namespace particles::plot;
using particles::test::parseXml;
using particles::test::pathBounds;
using particles::test::PathBounds;
using particles::test::PathPoint;
using particles::test::pathPoints;
using particles::test::plotFrames;
using particles::test::sameColour;
using particles::test::styleProperty;
using particles::test::XmlElement;

namespace {

// n points spread evenly over [x0, x1) px, y from `value(i)`.
template <typename F>
std::vector<Point> spread(std::size_t n, double x0, double x1, F value) {
  std::vector<Point> points;
  for (std::size_t i = 0; i < n; ++i) points.push_back({x0 + (x1 - x0) * double(i) / double(n), value(i)});
  return points;
}

std::vector<Point> randomWalk(std::size_t n, double x0, double x1, double y0, double stepPx) {
  std::mt19937_64 random(26);
  std::normal_distribution<double> step(0.0, stepPx);
  double y = y0;
  return spread(n, x0, x1, [&](std::size_t) { return y += step(random); });
}

bool samePoint(Point a, Point b) {
  return a.x == b.x && a.y == b.y;
}

// The longest path stroked in series colour 0 (the data line, not its legend swatch).
XmlElement dataLine(const std::vector<XmlElement>& svg) {
  XmlElement longest;
  for (const XmlElement& e : svg) {
    if (e.name == "path" && sameColour(styleProperty(e, "stroke"), seriesColour(0)) &&
        e.attributes.at("d").size() > (longest.attributes.count("d") ? longest.attributes.at("d").size() : 0)) {
      longest = e;
    }
  }
  return longest;
}

Figure oneSeries(std::vector<double> x, std::vector<double> y) {
  Figure f;
  f.chart = LineChart{"t [s]", {Panel{"y", AxisScale::Linear, {Series{"", std::move(x), std::move(y)}}}}};
  return f;
}

// The polyline stroked as the line chart strokes a series (2 px, round joins and caps) into a
// white kImageW × kImageH RGB24 image: its pixels.
constexpr int kImageW = 300, kImageH = 200;
std::vector<std::uint32_t> stroke(const std::vector<Point>& points) {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, kImageW, kImageH);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_rgb(cr, 0.12, 0.47, 0.71);
  cairo_move_to(cr, points[0].x, points[0].y);
  for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr, points[i].x, points[i].y);
  cairo_set_line_width(cr, 2);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_stroke(cr);
  cairo_surface_flush(surface);
  std::vector<std::uint32_t> pixels;
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  for (int y = 0; y < kImageH; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + std::size_t(y) * std::size_t(stride));
    pixels.insert(pixels.end(), row, row + kImageW);
  }
  cairo_destroy(cr);
  cairo_surface_destroy(surface);
  return pixels;
}

}  // namespace

TEST_CASE("plot reduction: a line with at most 4 points per column comes back unchanged") {
  const std::vector<std::vector<Point>> lines = {
      {},
      {{1, 1}},
      {{1, 1}, {1, 5}, {1, 2}, {1, 9}},                                                               // 4 in one column
      spread(1000, 100, 1100, [](std::size_t i) { return 400 + 300 * std::sin(0.05 * double(i)); }),  // 1 per px
      spread(4000, 100, 1100, [](std::size_t i) { return 400 + 300 * std::sin(0.01 * double(i)); }),  // 1 per column
      randomWalk(4000, 100, 1100, 400, 20)};
  for (const auto& line : lines) {
    CAPTURE(line.size());
    const std::vector<Point> reduced = reduceToColumns(line, kReductionColumnPx);
    REQUIRE(reduced.size() == line.size());
    for (std::size_t i = 0; i < line.size(); ++i) CHECK(samePoint(reduced[i], line[i]));
  }
}

TEST_CASE("plot reduction: a dense line keeps each column's first, lowest, highest and last point, in order") {
  const std::vector<Point> line = randomWalk(100'000, 100.3, 1100.3, 400, 3);
  const std::vector<Point> reduced = reduceToColumns(line, kReductionColumnPx);
  CHECK(reduced.size() <= 4 * 4 * 1001);  // 4 per quarter pixel
  CHECK(reduced.size() >= 2 * 4 * 1000);  // every column keeps at least its first and last point
  // Per column: the input's points and the kept ones.
  std::map<long, std::vector<std::size_t>> full, kept;
  for (std::size_t i = 0; i < line.size(); ++i) full[long(std::floor(line[i].x / kReductionColumnPx))].push_back(i);
  std::size_t at = 0;  // each kept point is the input's, found in order
  for (const Point& p : reduced) {
    while (at < line.size() && !samePoint(line[at], p)) ++at;
    REQUIRE(at < line.size());
    kept[long(std::floor(p.x / kReductionColumnPx))].push_back(at++);
  }
  REQUIRE(kept.size() == full.size());
  for (const auto& [column, indices] : full) {
    CAPTURE(column);
    const std::vector<std::size_t>& k = kept[column];
    CHECK(k.size() <= 4);
    CHECK(k.front() == indices.front());
    CHECK(k.back() == indices.back());
    const auto byY = [&](std::size_t a, std::size_t b) { return line[a].y < line[b].y; };
    CHECK(line[*std::min_element(k.begin(), k.end(), byY)].y ==
          line[*std::min_element(indices.begin(), indices.end(), byY)].y);
    CHECK(line[*std::max_element(k.begin(), k.end(), byY)].y ==
          line[*std::max_element(indices.begin(), indices.end(), byY)].y);
  }
}

// What "visually identical" means here, measured: 20,000 points (80 per pixel column) stroked
// whole and reduced into the same 300 × 200 image (the full line is what is slow to draw, so the
// image is small). A column's reduced strokes run at most a quarter pixel from the full ones, so
// only anti-aliased edge pixels change, by little. Measured (largest difference of 255, pixels of
// the 60,000 that differ by more than 32): ±1: 52 and 160, all in the pixel column where the band
// ends (its last quarter-pixel column's strokes end up to a quarter pixel sooner); random walk: 45
// and 11; sine: 3 and 0.
TEST_CASE("plot reduction: the reduced line has the full line's pixels, up to anti-aliasing at its edges") {
  const std::vector<std::vector<Point>> lines = {
      spread(20'000, 25, 275, [](std::size_t i) { return i % 2 ? 20.0 : 180.0; }),  // ±1, once slow
      randomWalk(20'000, 25, 275, 100, 1),
      spread(20'000, 25, 275, [](std::size_t i) { return 100 + 80 * std::sin(5e-4 * double(i)); })};
  for (std::size_t n = 0; n < lines.size(); ++n) {
    CAPTURE(n);
    const std::vector<Point> reduced = reduceToColumns(lines[n], kReductionColumnPx);
    CHECK(reduced.size() < lines[n].size() / 5);
    const std::vector<std::uint32_t> full = stroke(lines[n]), thin = stroke(reduced);
    int largest = 0;
    std::size_t over32 = 0;
    for (std::size_t i = 0; i < full.size(); ++i) {
      int d = 0;
      for (int shift : {0, 8, 16})
        d = std::max(d, std::abs(int((full[i] >> shift) & 0xff) - int((thin[i] >> shift) & 0xff)));
      largest = std::max(largest, d);
      over32 += d > 32;
    }
    CAPTURE(largest);
    CAPTURE(over32);
    CHECK(largest <= 64);
    CHECK(over32 <= kImageH);  // one pixel column's worth
  }
}

// Through the figure: the SVG's data line of a dense series is the reduced one (the old code wrote
// all 100,000 points), with every column's extremes; a sparse series keeps every point.
TEST_CASE("plot: a dense series is drawn with at most 4 points per quarter pixel and keeps its envelope") {
  std::vector<double> x, y;
  for (int i = 0; i < 100'000; ++i) {
    x.push_back(0.001 * i);
    y.push_back(i % 2 ? 1.0 : -1.0);
  }
  const auto svg = parseXml(renderFigure(oneSeries(x, y), ImageFormat::Svg));
  const std::vector<PathPoint> points = pathPoints(dataLine(svg));
  const PathBounds frame = plotFrames(svg).front();
  CAPTURE(points.size());
  CHECK(points.size() <= 4 * std::size_t((frame.x1 - frame.x0) / kReductionColumnPx + 2));
  CHECK(points.size() >= 2 * std::size_t((frame.x1 - frame.x0) / kReductionColumnPx - 2));
  // The envelope: the line spans the plot, and every column reaches both +1 and −1.
  double top = INFINITY, bottom = -INFINITY;
  for (const PathPoint& p : points) {
    top = std::min(top, p.y);
    bottom = std::max(bottom, p.y);
  }
  CHECK(std::fabs(points.front().x - frame.x0) <= 1);  // the frame is a hairline on pixel centres
  CHECK(std::fabs(points.back().x - frame.x1) <= 1);
  std::map<long, std::pair<double, double>> columns;  // lowest and highest y per column
  for (const PathPoint& p : points) {
    auto [it, fresh] = columns.try_emplace(long(std::floor(p.x / kReductionColumnPx)), p.y, p.y);
    it->second = {std::min(it->second.first, p.y), std::max(it->second.second, p.y)};
  }
  std::size_t full = 0;
  for (const auto& [column, extent] : columns) full += extent.first == top && extent.second == bottom;
  CHECK(full >= columns.size() - 2);  // perhaps not the first and last, which the data only touches

  // 1,000 points over ~1,100 px: every point drawn, as before.
  const auto sparse = parseXml(renderFigure(
      oneSeries(std::vector<double>(x.begin(), x.begin() + 1000), std::vector<double>(y.begin(), y.begin() + 1000)),
      ImageFormat::Svg));
  CHECK(pathPoints(dataLine(sparse)).size() == 1000);
}
