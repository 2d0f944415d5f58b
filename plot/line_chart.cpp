// Stacked line panels sharing one x axis. Layout, top to bottom: title, panels separated by a gap,
// x tick labels and the x label under the bottom panel, then the caption. Bands (intervals of x)
// are shaded under the grid of every panel and labelled inside the top one. The left margin fits the widest y tick
// label of any panel, so all panels line up.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include "plot/charts.hpp"
#include "plot/column_reduction.hpp"

namespace particles::plot {

namespace {

constexpr double kPanelGapPx = 28;
constexpr double kLineWidthPx = 2;
constexpr double kIsolatedPointRadiusPx = 2.5;  // a point with no neighbour to draw a line to
constexpr double kMarkerRadiusPx = 3.5;        // each point of a series with markers
constexpr double kLegendInsetPx = 10;
constexpr double kLegendRowPx = 20;
constexpr double kLegendSwatchPx = 26;

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
};

bool drawable(double x, double y, AxisScale scale, AxisScale xScale) {
  return std::isfinite(x) && std::isfinite(y) && (scale != AxisScale::Log || y > 0) &&
         (xScale != AxisScale::Log || x > 0);
}

// Runs of consecutive drawable points, in pixels. A point that cannot be drawn ends a run; so does
// one whose pixel is not finite, which the axes' ranges should never give (cairo would refuse the
// whole figure for it).
std::vector<std::vector<Point>> pixelRuns(const Series& s, const XAxis& xAxis, const YAxis& yAxis, const Rect& plot) {
  std::vector<std::vector<Point>> runs;
  bool inRun = false;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const Point p = drawable(s.x[i], s.y[i], yAxis.scale, xAxis.scale)
                        ? Point{xAxis.toPixel(s.x[i], plot), yAxis.toPixel(s.y[i], plot)}
                        : Point{NAN, NAN};
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      inRun = false;
      continue;
    }
    if (!inRun) runs.emplace_back();
    inRun = true;
    runs.back().push_back(p);
  }
  return runs;
}

// Liang–Barsky: does the segment a–b meet the rectangle r?
bool segmentMeetsRect(Point a, Point b, const Rect& r) {
  double t0 = 0, t1 = 1;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const std::array<double, 4> p = {-dx, dx, -dy, dy};
  const std::array<double, 4> q = {a.x - r.x, r.right() - a.x, a.y - r.y, r.bottom() - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
    } else {
      const double t = q[i] / p[i];
      if (p[i] < 0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
    }
  }
  return t0 <= t1;
}

using PanelRuns = std::vector<std::vector<std::vector<Point>>>;  // per series, per run

// How much of the data a legend at r would hide: the number of segments and points under it.
std::size_t legendOverlap(const Rect& r, const PanelRuns& runs) {
  std::size_t n = 0;
  for (const auto& series : runs) {
    for (const auto& run : series) {
      if (run.size() == 1) n += segmentMeetsRect(run[0], run[0], r);
      for (std::size_t i = 1; i < run.size(); ++i) n += segmentMeetsRect(run[i - 1], run[i], r);
    }
  }
  return n;
}

void drawLegend(const Canvas& canvas, const Panel& panel, const Rect& plot, const PanelRuns& runs) {
  std::vector<std::size_t> entries;
  double textWidth = 0;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    if (panel.series[i].name.empty()) continue;
    entries.push_back(i);
    textWidth = std::max(textWidth, canvas.textWidth({panel.series[i].name, ""}, kLegendSizePx));
  }
  if (entries.empty()) return;
  const double w = 8 + kLegendSwatchPx + 8 + textWidth + 10, h = entries.size() * kLegendRowPx + 10;
  // Preference order top right, top left, bottom right, bottom left; the first that hides least.
  const double left = plot.x + kLegendInsetPx, right = plot.right() - kLegendInsetPx - w;
  const double top = plot.y + kLegendInsetPx, bottom = plot.bottom() - kLegendInsetPx - h;
  const std::array<Rect, 4> candidates = {Rect{right, top, w, h}, Rect{left, top, w, h}, Rect{right, bottom, w, h},
                                          Rect{left, bottom, w, h}};
  Rect box = candidates[0];
  std::size_t best = std::numeric_limits<std::size_t>::max();
  for (const Rect& c : candidates) {
    const std::size_t overlap = legendOverlap({c.x - 4, c.y - 4, c.w + 8, c.h + 8}, runs);
    if (overlap < best) {
      best = overlap;
      box = c;
    }
  }
  box.x = std::round(box.x);
  box.y = std::round(box.y);

  canvas.fillRect(box, kBackground, 0.9);
  canvas.frame(box, kLegendBorder);
  cairo_t* cr = canvas.cr();
  for (std::size_t row = 0; row < entries.size(); ++row) {
    const Series& s = panel.series[entries[row]];
    const double y = box.y + 5 + kLegendRowPx * (row + 0.5);
    const Rgb c = seriesColour(entries[row]);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_set_line_width(cr, kLineWidthPx);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cairo_move_to(cr, box.x + 8, std::round(y));
    cairo_line_to(cr, box.x + 8 + kLegendSwatchPx, std::round(y));
    cairo_stroke(cr);
    canvas.text({s.name, ""}, box.x + 8 + kLegendSwatchPx + 8, y, kLegendSizePx, HAlign::Left, VAlign::Middle, kInk);
  }
}

void drawSeries(const Canvas& canvas, std::size_t index, const std::vector<std::vector<Point>>& runs, bool markers) {
  cairo_t* cr = canvas.cr();
  const Rgb c = seriesColour(index);
  cairo_set_source_rgb(cr, c.r, c.g, c.b);
  bool anyLine = false;
  for (const auto& fullRun : runs) {
    if (fullRun.size() < 2) continue;
    // The line through at most 4 points per column (column_reduction.hpp); dots (below) and the
    // legend's placement still see every point.
    const std::vector<Point> run = reduceToColumns(fullRun, kReductionColumnPx);
    cairo_move_to(cr, run[0].x, run[0].y);
    for (std::size_t i = 1; i < run.size(); ++i) cairo_line_to(cr, run[i].x, run[i].y);
    anyLine = true;
  }
  if (anyLine) {
    cairo_set_line_width(cr, kLineWidthPx);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_stroke(cr);
  }
  bool anyDot = false;
  for (const auto& run : runs) {
    if (run.size() != 1 && !markers) continue;
    for (const Point& p : run) {
      cairo_new_sub_path(cr);
      cairo_arc(cr, p.x, p.y, markers ? kMarkerRadiusPx : kIsolatedPointRadiusPx, 0, 2 * std::numbers::pi);
    }
    anyDot = true;
  }
  if (anyDot) cairo_fill(cr);
}

// Where a band lies inside `plot`, in pixels: {x0, x1}, or nothing when it is outside the axis.
std::optional<std::pair<double, double>> bandPixels(const Band& band, const XAxis& xAxis, const Rect& plot) {
  if (!(band.to > band.from) || (xAxis.scale == AxisScale::Log && band.to <= 0)) return std::nullopt;
  const double from = xAxis.scale == AxisScale::Log ? std::max(band.from, xAxis.ticks.lo) : band.from;
  const double x0 = std::clamp(xAxis.toPixel(from, plot), plot.x, plot.right());
  const double x1 = std::clamp(xAxis.toPixel(band.to, plot), plot.x, plot.right());
  if (x1 - x0 < 0.5) return std::nullopt;
  return std::pair{x0, x1};
}

// The bands' shading (under the grid and the data) and their labels (over them, top panel only).
void shadeBands(const Canvas& canvas, const std::vector<Band>& bands, const XAxis& xAxis, const Rect& plot) {
  for (const Band& band : bands) {
    if (const auto x = bandPixels(band, xAxis, plot))
      canvas.fillRect({x->first, plot.y, x->second - x->first, plot.h}, kBand);
  }
}
void labelBands(const Canvas& canvas, const std::vector<Band>& bands, const XAxis& xAxis, const Rect& plot) {
  for (const Band& band : bands) {
    const auto x = bandPixels(band, xAxis, plot);
    if (!x || band.label.empty()) continue;
    canvas.text({band.label, ""}, x->first + 5, plot.y + 6, kTickLabelSizePx, HAlign::Left, VAlign::Top, kBandInk);
  }
}

}  // namespace

void drawLineChart(const Canvas& canvas, const Figure& figure, const LineChart& chart) {
  // A chart without panels is drawn as one empty panel, saying "no data".
  const std::vector<Panel> oneEmptyPanel(1);
  const std::vector<Panel>& panels = chart.panels.empty() ? oneEmptyPanel : chart.panels;
  const double top = drawTitle(canvas, figure);
  const double bottomMargin = xAxisMargin(canvas, figure, chart.xLabel);
  const std::size_t panelCount = std::max<std::size_t>(1, panels.size());
  const double panelHeight =
      std::max(40.0, (figure.heightPx - top - bottomMargin - kPanelGapPx * (panelCount - 1)) / panelCount);

  // The shared x range: every point some panel can draw.
  Range xRange;
  for (const Panel& p : panels) {
    for (const Series& s : p.series) {
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (drawable(s.x[i], s.y[i], p.yScale, chart.xScale)) xRange.add(s.x[i]);
      }
    }
  }
  std::vector<YAxis> yAxes;
  double widestTickLabel = 0;
  for (const Panel& p : panels) {
    Range yRange;
    for (const Series& s : p.series) {
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (drawable(s.x[i], s.y[i], p.yScale, chart.xScale)) yRange.add(s.y[i]);
      }
    }
    YAxis axis{p.yScale, {}};
    if (p.yScale == AxisScale::Log) {
      axis.ticks = yRange.empty() ? logTicks(1, 10, 2) : logTicks(yRange.lo, yRange.hi, int(panelHeight / 36));
    } else {
      const int target = std::clamp(int(std::lround(panelHeight / 55)), 3, 8);
      axis.ticks = yRange.empty() ? linearTicks(0, 1, target, true) : linearTicks(yRange.lo, yRange.hi, target, true);
    }
    widestTickLabel = std::max(widestTickLabel, tickLabelWidth(canvas, axis.ticks));
    yAxes.push_back(axis);
  }

  // Left to right: pad, rotated y label (one line of text), gap, tick labels, gap, ticks, plot.
  const double yLabelX = kOuterPadPx;
  const double left = std::round(yLabelX + 1.2 * kAxisLabelSizePx + kAxisLabelGapPx + widestTickLabel +
                                 kTickLabelGapPx + kTickLengthPx);
  const double plotWidth = std::max(40.0, figure.widthPx - left - kRightMarginPx);
  const int xTarget = std::clamp(int(plotWidth / 110), 3, 12);
  XAxis xAxis;
  xAxis.scale = chart.xScale;
  if (chart.xScale == AxisScale::Log) {
    xAxis.ticks = xRange.empty() ? logTicks(1, 10, 2) : logTicks(xRange.lo, xRange.hi, xTarget);
  } else {
    xAxis.ticks =
        xRange.empty() ? linearTicks(0, 1, xTarget, false) : linearTicks(xRange.lo, xRange.hi, xTarget, false);
  }

  Rect plot{left, 0, std::round(plotWidth), std::round(panelHeight)};
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const Panel& panel = panels[k];
    const YAxis& yAxis = yAxes[k];
    plot.y = std::round(top + k * (panelHeight + kPanelGapPx));

    shadeBands(canvas, chart.bands, xAxis, plot);
    drawYGrid(canvas, yAxis, plot);
    for (const Tick& t : xAxis.ticks.major) {
      const double x = xAxis.toPixel(t.value, plot);
      if (x > plot.x + 0.5 && x < plot.right() - 0.5) canvas.hairline(x, plot.y, x, plot.bottom(), kGrid);
    }

    PanelRuns runs;
    bool anyPoint = false;
    for (const Series& s : panel.series) {
      runs.push_back(pixelRuns(s, xAxis, yAxis, plot));
      anyPoint = anyPoint || !runs.back().empty();
    }
    cairo_save(canvas.cr());
    cairo_rectangle(canvas.cr(), plot.x, plot.y, plot.w, plot.h);
    cairo_clip(canvas.cr());
    for (std::size_t i = 0; i < runs.size(); ++i) drawSeries(canvas, i, runs[i], panel.series[i].markers);
    cairo_restore(canvas.cr());
    if (!anyPoint) {
      canvas.text({"no data", ""}, plot.x + plot.w / 2, plot.y + plot.h / 2, kAxisLabelSizePx, HAlign::Center,
                  VAlign::Middle, kMutedInk);
    }

    if (k == 0) labelBands(canvas, chart.bands, xAxis, plot);
    canvas.frame(plot, kInk);
    drawYAxis(canvas, yAxis, plot, panel.yLabel, yLabelX);
    for (const Tick& t : xAxis.ticks.major) {
      const double x = xAxis.toPixel(t.value, plot);
      canvas.hairline(x, plot.bottom(), x, plot.bottom() + kTickLengthPx, kInk);
    }
    drawLegend(canvas, panel, plot, runs);
  }

  drawXLabels(canvas, xAxis, plot, chart.xLabel);  // under the bottom panel only
  drawCaption(canvas, figure);
}

}  // namespace particles::plot
