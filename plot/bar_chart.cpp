// Grouped bars on a log y axis. Layout, top to bottom: title, a one-line legend of the groups,
// the plot (bars start at the axis' bottom edge and carry their value above them), category names
// and the x label.

#include <algorithm>
#include <cmath>

#include "plot/charts.hpp"

namespace particles::plot {

namespace {

constexpr double kRightMarginPx = 32;
constexpr double kGroupFraction = 0.7;  // of a category's slot taken by its bars
constexpr double kBarGapPx = 4;         // between neighbouring bars of one category
constexpr double kValueLabelGapPx = 6;  // bar top to the baseline of its value label
constexpr double kSwatchPx = 12;
constexpr double kLegendSpacingPx = 28;

bool drawable(double v) {
  return std::isfinite(v) && v > 0;
}

// Height of a value label above its baseline, superscript included.
double valueLabelHeight() {
  return Canvas::capHeight(kTickLabelSizePx) + 0.42 * kTickLabelSizePx;
}

double drawLegendRow(const Canvas& canvas, const Figure& figure, const BarChart& chart, double top) {
  double total = 0;
  std::size_t named = 0;
  for (const BarGroup& g : chart.groups) {
    if (g.name.empty()) continue;
    total += (named > 0 ? kLegendSpacingPx : 0) + kSwatchPx + 6 + canvas.textWidth({g.name, ""}, kLegendSizePx);
    ++named;
  }
  if (named == 0) return top;
  double x = std::round(figure.widthPx / 2.0 - total / 2);
  const double y = top + kSwatchPx / 2;
  for (std::size_t i = 0; i < chart.groups.size(); ++i) {
    const BarGroup& g = chart.groups[i];
    if (g.name.empty()) continue;
    canvas.fillRect({x, std::round(y - kSwatchPx / 2), kSwatchPx, kSwatchPx}, seriesColour(i));
    x += kSwatchPx + 6;
    canvas.text({g.name, ""}, x, y, kLegendSizePx, HAlign::Left, VAlign::Middle, kInk);
    x += canvas.textWidth({g.name, ""}, kLegendSizePx) + kLegendSpacingPx;
  }
  return top + kSwatchPx + 20;
}

}  // namespace

void drawBarChart(const Canvas& canvas, const Figure& figure, const BarChart& chart) {
  const double top = drawLegendRow(canvas, figure, chart, drawTitle(canvas, figure));
  const double categoriesTop = 10;  // below the plot
  const double bottomMargin = categoriesTop + Canvas::capHeight(kAxisLabelSizePx) +
                              (chart.xLabel.empty() ? 0 : 14 + kAxisLabelSizePx) + 4 + kOuterPadPx;
  const double plotHeight = std::max(40.0, std::round(figure.heightPx - top - bottomMargin));

  double lo = INFINITY, hi = -INFINITY;
  for (const BarGroup& g : chart.groups) {
    for (double v : g.values) {
      if (!drawable(v)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  const bool anyBar = lo <= hi;
  // The smallest bar is at least 0.15 decade tall (1.4×): a bar of zero height would vanish.
  // The axis grows by decades until the tallest bar's value label fits under the frame.
  YAxis axis{AxisScale::Log, {}};
  const int maxMajor = std::max(2, int(plotHeight / 36));
  const Rect probe{0, 0, 1, plotHeight};
  for (double headroom = 1; headroom <= 1e3; headroom *= 10) {
    axis.ticks = anyBar ? logTicks(lo / 1.4, hi * headroom, maxMajor) : logTicks(1, 10, maxMajor);
    if (!anyBar || axis.toPixel(hi, probe) - kValueLabelGapPx - valueLabelHeight() >= 4) break;
  }

  const double yLabelX = kOuterPadPx;
  const double left = std::round(yLabelX + 1.2 * kAxisLabelSizePx + kAxisLabelGapPx +
                                 tickLabelWidth(canvas, axis.ticks) + kTickLabelGapPx + kTickLengthPx);
  const Rect plot{left, std::round(top), std::round(std::max(40.0, figure.widthPx - left - kRightMarginPx)),
                  plotHeight};

  drawYGrid(canvas, axis, plot);
  const std::size_t nCategories = chart.categories.size(), nGroups = chart.groups.size();
  const double slot = nCategories > 0 ? plot.w / nCategories : plot.w;
  const double barWidth = nGroups > 0 ? slot * kGroupFraction / nGroups : 0;
  for (std::size_t c = 0; c < nCategories; ++c) {
    const double slotLeft = plot.x + c * slot;
    for (std::size_t g = 0; g < nGroups; ++g) {
      const double x0 = std::round(slotLeft + slot * (1 - kGroupFraction) / 2 + g * barWidth + kBarGapPx / 2);
      const double x1 = std::round(slotLeft + slot * (1 - kGroupFraction) / 2 + (g + 1) * barWidth - kBarGapPx / 2);
      const double centre = (x0 + x1) / 2;
      const double v = c < chart.groups[g].values.size() ? chart.groups[g].values[c] : NAN;
      if (!drawable(v)) {
        canvas.text({"n/a", ""}, centre, plot.bottom() - kValueLabelGapPx, kTickLabelSizePx, HAlign::Center,
                    VAlign::Baseline, kMutedInk);
        continue;
      }
      const double y = std::round(axis.toPixel(v, plot));
      canvas.fillRect({x0, y, x1 - x0, plot.bottom() - y}, seriesColour(g));
      canvas.text(formatValue(v, 3), centre, y - kValueLabelGapPx, kTickLabelSizePx, HAlign::Center, VAlign::Baseline,
                  kInk);
    }
    canvas.text({chart.categories[c], ""}, slotLeft + slot / 2, plot.bottom() + categoriesTop, kAxisLabelSizePx,
                HAlign::Center, VAlign::Top, kInk);
  }
  if (!anyBar) {
    canvas.text({"no data", ""}, plot.x + plot.w / 2, plot.y + plot.h / 2, kAxisLabelSizePx, HAlign::Center,
                VAlign::Middle, kMutedInk);
  }
  canvas.frame(plot, kInk);
  drawYAxis(canvas, axis, plot, chart.yLabel, yLabelX);
  if (!chart.xLabel.empty()) {
    canvas.text({chart.xLabel, ""}, plot.x + plot.w / 2,
                plot.bottom() + categoriesTop + Canvas::capHeight(kAxisLabelSizePx) + 14, kAxisLabelSizePx,
                HAlign::Center, VAlign::Top, kInk);
  }
}

}  // namespace particles::plot
