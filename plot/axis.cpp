// What both charts share: the y axis of a plot area (ticks, labels, grid) and the title.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "plot/charts.hpp"

namespace particles::plot {

double YAxis::toPixel(double v, const Rect& plot) const {
  double f;
  if (scale == AxisScale::Log) {
    f = (std::log10(v) - std::log10(ticks.lo)) / (std::log10(ticks.hi) - std::log10(ticks.lo));
  } else {
    f = axisFraction(v, ticks);
  }
  return plot.bottom() - f * plot.h;
}

double tickLabelWidth(const Canvas& canvas, const AxisTicks& ticks) {
  double w = 0;
  for (const Tick& t : ticks.major) w = std::max(w, canvas.textWidth(t.label, kTickLabelSizePx));
  return w;
}

void drawYGrid(const Canvas& canvas, const YAxis& axis, const Rect& plot) {
  for (const Tick& t : axis.ticks.major) {
    const double y = axis.toPixel(t.value, plot);
    if (y > plot.y + 0.5 && y < plot.bottom() - 0.5) canvas.hairline(plot.x, y, plot.right(), y, kGrid);
  }
}

void drawYAxis(const Canvas& canvas, const YAxis& axis, const Rect& plot, const std::string& label, double labelX) {
  for (const Tick& t : axis.ticks.major) {
    const double y = axis.toPixel(t.value, plot);
    canvas.hairline(plot.x - kTickLengthPx, y, plot.x, y, kInk);
    canvas.text(t.label, plot.x - kTickLengthPx - kTickLabelGapPx, pixelCentre(y), kTickLabelSizePx, HAlign::Right,
                VAlign::Middle, kInk);
  }
  for (double v : axis.ticks.minor) {
    const double y = axis.toPixel(v, plot);
    canvas.hairline(plot.x - kMinorTickLengthPx, y, plot.x, y, kInk);
  }
  if (!label.empty()) {
    canvas.text({label, ""}, labelX, plot.y + plot.h / 2, kAxisLabelSizePx, HAlign::Center, VAlign::Top, kInk,
                std::numbers::pi / 2);
  }
}

double drawTitle(const Canvas& canvas, const Figure& figure) {
  if (figure.title.empty()) return kOuterPadPx;
  const double top = kOuterPadPx;
  canvas.text({figure.title, ""}, figure.widthPx / 2.0, top, kTitleSizePx, HAlign::Center, VAlign::Top, kInk);
  return top + Canvas::capHeight(kTitleSizePx) + 24;  // room below for descenders and air
}

}  // namespace particles::plot
