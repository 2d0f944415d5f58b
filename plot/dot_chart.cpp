// A dot plot: one row per category, top to bottom; in each row one dot per group (and the
// reference, if any) on its own line within the row, each labelled with its value to the right.
// Layout, top to bottom: title, a one-line legend, the plot, x tick labels, the x label, the
// caption. The log x axis is fitted to the data (not widened to whole decades), with room on the
// right for the last value's label.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "plot/charts.hpp"

namespace particles::plot {

namespace {

constexpr double kDotRadiusPx = 5;
constexpr double kDiamondPx = 7;  // half diagonal of a reference's open diamond
constexpr double kCapPx = 6;      // half height of a reference range's end caps
constexpr double kValueGapPx = 10;
constexpr double kSwatchGapPx = 8;
constexpr double kLegendSpacingPx = 28;

bool drawable(double v) {
  return std::isfinite(v) && v > 0;
}

bool drawable(const std::optional<Reference>& r) {
  return r && drawable(r->lo) && drawable(r->hi) && r->hi >= r->lo;
}

Label referenceLabel(const Reference& r) {
  if (r.lo == r.hi) return formatValue(r.lo, 3);
  const Label lo = formatValue(r.lo, 3), hi = formatValue(r.hi, 3);
  if (!lo.superscript.empty() || !hi.superscript.empty()) return {lo.text + "…", ""};  // not expected for dt
  return {lo.text + "\u2013" + hi.text, ""};
}

// "0.012", or "≥ 10" for a lower bound.
Label valueLabel(const DotGroup& group, std::size_t category) {
  Label label = formatValue(group.values[category], 3);
  if (category < group.lowerBounds.size() && group.lowerBounds[category]) label.text = "\u2265 " + label.text;
  return label;
}

void dot(const Canvas& canvas, double x, double y, Rgb colour) {
  cairo_t* cr = canvas.cr();
  cairo_set_source_rgb(cr, colour.r, colour.g, colour.b);
  cairo_new_sub_path(cr);
  cairo_arc(cr, x, y, kDotRadiusPx, 0, 2 * std::numbers::pi);
  cairo_fill(cr);
}

void diamond(const Canvas& canvas, double x, double y) {
  cairo_t* cr = canvas.cr();
  cairo_set_source_rgb(cr, kInk.r, kInk.g, kInk.b);
  cairo_set_line_width(cr, 1.5);
  cairo_move_to(cr, x, y - kDiamondPx);
  cairo_line_to(cr, x + kDiamondPx, y);
  cairo_line_to(cr, x, y + kDiamondPx);
  cairo_line_to(cr, x - kDiamondPx, y);
  cairo_close_path(cr);
  cairo_stroke(cr);
}

// A range [x0, x1] with end caps: where a value is known to lie.
void range(const Canvas& canvas, double x0, double x1, double y) {
  cairo_t* cr = canvas.cr();
  cairo_set_source_rgb(cr, kInk.r, kInk.g, kInk.b);
  cairo_set_line_width(cr, 1.5);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  cairo_move_to(cr, x0, y);
  cairo_line_to(cr, x1, y);
  cairo_move_to(cr, x0, y - kCapPx);
  cairo_line_to(cr, x0, y + kCapPx);
  cairo_move_to(cr, x1, y - kCapPx);
  cairo_line_to(cr, x1, y + kCapPx);
  cairo_stroke(cr);
}

bool hasReferences(const DotChart& chart) {
  return std::any_of(chart.references.begin(), chart.references.end(), [](const auto& r) { return drawable(r); });
}

// The legend: a dot per group, a diamond for the reference; centred; returns the top of what follows.
double drawLegendRow(const Canvas& canvas, const Figure& figure, const DotChart& chart, double top) {
  const bool references = hasReferences(chart) && !chart.referenceName.empty();
  double total = 0;
  std::size_t entries = 0;
  auto add = [&](const std::string& name) {
    total += (entries > 0 ? kLegendSpacingPx : 0) + 2 * kDiamondPx + kSwatchGapPx +
             canvas.textWidth({name, ""}, kLegendSizePx);
    ++entries;
  };
  for (const DotGroup& g : chart.groups) {
    if (!g.name.empty()) add(g.name);
  }
  if (references) add(chart.referenceName);
  if (entries == 0) return top;
  double x = std::round(figure.widthPx / 2.0 - total / 2);
  const double y = top + kDiamondPx;
  auto label = [&](const std::string& name) {
    x += 2 * kDiamondPx + kSwatchGapPx;
    canvas.text({name, ""}, x, y, kLegendSizePx, HAlign::Left, VAlign::Middle, kInk);
    x += canvas.textWidth({name, ""}, kLegendSizePx) + kLegendSpacingPx;
  };
  for (std::size_t i = 0; i < chart.groups.size(); ++i) {
    if (chart.groups[i].name.empty()) continue;
    dot(canvas, x + kDiamondPx, y, seriesColour(i));
    label(chart.groups[i].name);
  }
  if (references) {
    const bool ranges = std::any_of(chart.references.begin(), chart.references.end(),
                                    [](const auto& r) { return drawable(r) && r->hi > r->lo; });
    if (ranges) {
      range(canvas, x, x + 2 * kDiamondPx, y);
    } else {
      diamond(canvas, x + kDiamondPx, y);
    }
    label(chart.referenceName);
  }
  return top + 2 * kDiamondPx + 18;
}

// The values' range, and the widest value label (room is kept for it right of the largest value).
struct DotRange {
  double lo = INFINITY, hi = -INFINITY, widestLabel = 0;
  bool any() const { return lo <= hi; }
};

DotRange dotRangeOf(const Canvas& canvas, const DotChart& chart) {
  DotRange range;
  auto include = [&](double v, const Label& label) {
    range.lo = std::min(range.lo, v);
    range.hi = std::max(range.hi, v);
    range.widestLabel = std::max(range.widestLabel, canvas.textWidth(label, kTickLabelSizePx));
  };
  for (const DotGroup& g : chart.groups) {
    for (std::size_t c = 0; c < g.values.size(); ++c) {
      if (drawable(g.values[c])) include(g.values[c], valueLabel(g, c));
    }
  }
  for (const auto& r : chart.references) {
    if (!drawable(r)) continue;
    include(r->lo, referenceLabel(*r));
    include(r->hi, referenceLabel(*r));
  }
  return range;
}

// In decades: at least a factor of 2 shown, 8 % of the span as air on the left, and the right
// end pushed out until the largest value's label fits inside the frame.
XAxis dotAxis(const DotRange& range, const Rect& plot) {
  XAxis axis{logTicks(1, 10, 2), AxisScale::Log};
  if (!range.any()) return axis;
  double l0 = std::log10(range.lo), l1 = std::log10(range.hi);
  const double minSpan = std::log10(2.0);
  if (l1 - l0 < minSpan) {
    const double mid = (l0 + l1) / 2;
    l0 = mid - minSpan / 2;
    l1 = mid + minSpan / 2;
  }
  const double axisLo = l0 - 0.08 * (l1 - l0);
  const double usable = std::clamp((plot.w - range.widestLabel - kValueGapPx - kDotRadiusPx - 8) / plot.w, 0.5, 1.0);
  const double axisHi = axisLo + (l1 - axisLo) / usable;
  // Within the doubles: past them pow gives 0 or infinity, and the axis non-finite pixels.
  const double from = std::max(std::pow(10.0, axisLo), std::numeric_limits<double>::denorm_min());
  const double to = std::min(std::pow(10.0, axisHi), std::numeric_limits<double>::max());
  axis.ticks = logTicksWithin(from, to, std::max(2, int(plot.w / 70)));
  return axis;
}

// One row per category: a line per group (its dot and value, or n/a) and one for the reference.
void drawDotRows(const Canvas& canvas, const DotChart& chart, const Rect& plot, const XAxis& axis) {
  auto toPixel = [&](double v) { return axis.toPixel(v, plot); };
  const bool references = hasReferences(chart);
  const std::size_t rows = chart.categories.size();
  const std::size_t lines = chart.groups.size() + (references ? 1 : 0);
  const double rowHeight = rows > 0 ? plot.h / rows : plot.h;
  const double lineStep = std::min(18.0, rowHeight / (lines + 1.0));
  for (std::size_t c = 0; c < rows; ++c) {
    const double centre = std::round(plot.y + (c + 0.5) * rowHeight);
    if (c > 0)
      canvas.hairline(plot.x, std::round(plot.y + c * rowHeight), plot.right(), std::round(plot.y + c * rowHeight),
                      kGrid);
    auto lineY = [&](std::size_t i) { return std::round(centre + (i - (lines - 1) / 2.0) * lineStep); };
    for (std::size_t g = 0; g < chart.groups.size(); ++g) {
      const double v = c < chart.groups[g].values.size() ? chart.groups[g].values[c] : NAN;
      const double y = lineY(g);
      if (!drawable(v)) {
        canvas.text({"n/a", ""}, plot.x + 8, y, kTickLabelSizePx, HAlign::Left, VAlign::Middle, kMutedInk);
        continue;
      }
      const double x = toPixel(v);
      dot(canvas, x, y, seriesColour(g));
      canvas.text(valueLabel(chart.groups[g], c), x + kDotRadiusPx + kValueGapPx / 2, y, kTickLabelSizePx, HAlign::Left,
                  VAlign::Middle, kInk);
    }
    if (references && c < chart.references.size() && drawable(chart.references[c])) {
      const Reference& r = *chart.references[c];
      const double y = lineY(chart.groups.size());
      const double x0 = toPixel(r.lo), x1 = toPixel(r.hi);
      if (r.lo == r.hi) {
        diamond(canvas, x0, y);
      } else {
        range(canvas, x0, x1, y);
      }
      canvas.text(referenceLabel(r), x1 + kDiamondPx + kValueGapPx / 2, y, kTickLabelSizePx, HAlign::Left,
                  VAlign::Middle, kMutedInk);
    }
    canvas.text({chart.categories[c], ""}, plot.x - 12, centre, kAxisLabelSizePx, HAlign::Right, VAlign::Middle, kInk);
  }
}

}  // namespace

void drawDotChart(const Canvas& canvas, const Figure& figure, const DotChart& chart) {
  const double top = drawLegendRow(canvas, figure, chart, drawTitle(canvas, figure));
  const double bottomMargin = xAxisMargin(canvas, figure, chart.xLabel);
  const double plotHeight = std::max(40.0, std::round(figure.heightPx - top - bottomMargin));
  const DotRange range = dotRangeOf(canvas, chart);

  double widestCategory = 0;
  for (const std::string& c : chart.categories) {
    widestCategory = std::max(widestCategory, canvas.textWidth({c, ""}, kAxisLabelSizePx));
  }
  const double left = std::round(kOuterPadPx + widestCategory + 14);
  const Rect plot{left, std::round(top), std::round(std::max(40.0, figure.widthPx - left - kRightMarginPx)),
                  plotHeight};
  const XAxis axis = dotAxis(range, plot);
  auto toPixel = [&](double v) { return axis.toPixel(v, plot); };

  for (const Tick& t : axis.ticks.major) {
    const double x = pixelCentre(toPixel(t.value));
    if (x > plot.x + 0.5 && x < plot.right() - 0.5) canvas.hairline(x, plot.y, x, plot.bottom(), kGrid);
  }
  drawDotRows(canvas, chart, plot, axis);
  if (!range.any()) {
    canvas.text({"no data", ""}, plot.x + plot.w / 2, plot.y + plot.h / 2, kAxisLabelSizePx, HAlign::Center,
                VAlign::Middle, kMutedInk);
  }
  canvas.frame(plot, kInk);

  for (double v : axis.ticks.minor) {
    const double x = pixelCentre(toPixel(v));
    canvas.hairline(x, plot.bottom(), x, plot.bottom() + kMinorTickLengthPx, kInk);
  }
  for (const Tick& t : axis.ticks.major) {
    const double x = pixelCentre(toPixel(t.value));
    canvas.hairline(x, plot.bottom(), x, plot.bottom() + kTickLengthPx, kInk);
  }
  drawXLabels(canvas, axis, plot, chart.xLabel);
  drawCaption(canvas, figure);
}

}  // namespace particles::plot
