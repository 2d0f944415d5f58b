// What both charts share: the y axis of a plot area (ticks, labels, grid) and the title.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

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

double XAxis::toPixel(double v, const Rect& plot) const {
  if (scale == AxisScale::Log) {
    return plot.x + (std::log10(v) - std::log10(ticks.lo)) / (std::log10(ticks.hi) - std::log10(ticks.lo)) * plot.w;
  }
  return plot.x + axisFraction(v, ticks) * plot.w;
}

double xAxisMargin(const Canvas& canvas, const Figure& figure, const std::string& xLabel) {
  const double tickLabelsBottom = kTickLengthPx + kTickLabelGapPx + Canvas::capHeight(kTickLabelSizePx);
  return tickLabelsBottom + (xLabel.empty() ? 0 : 14 + kAxisLabelSizePx) + 4 + kOuterPadPx +
         captionHeight(canvas, figure);
}

void drawXLabels(const Canvas& canvas, const XAxis& axis, const Rect& plot, const std::string& xLabel) {
  const double labelsTop = plot.bottom() + kTickLengthPx + kTickLabelGapPx;
  for (const Tick& t : axis.ticks.major) {
    canvas.text(t.label, pixelCentre(axis.toPixel(t.value, plot)), labelsTop, kTickLabelSizePx, HAlign::Center,
                VAlign::Top, kInk);
  }
  if (!xLabel.empty()) {
    canvas.text({xLabel, ""}, plot.x + plot.w / 2, labelsTop + Canvas::capHeight(kTickLabelSizePx) + 14,
                kAxisLabelSizePx, HAlign::Center, VAlign::Top, kInk);
  }
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

namespace {

// The caption's lines, each paragraph broken between words to fit the width.
std::vector<std::string> captionLines(const Canvas& canvas, const Figure& figure) {
  const double width = figure.widthPx - 2 * kOuterPadPx;
  std::vector<std::string> lines;
  for (const std::string& paragraph : figure.caption) {
    std::string line;
    std::size_t pos = 0;
    while (pos < paragraph.size()) {
      std::size_t end = paragraph.find(' ', pos);
      if (end == std::string::npos) end = paragraph.size();
      const std::string word = paragraph.substr(pos, end - pos);
      pos = end + 1;
      const std::string longer = line.empty() ? word : line + " " + word;
      if (!line.empty() && canvas.textWidth({longer, ""}, kCaptionSizePx) > width) {
        lines.push_back(line);
        line = word;
      } else {
        line = longer;
      }
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace

double captionHeight(const Canvas& canvas, const Figure& figure) {
  if (figure.caption.empty()) return 0;
  return captionLines(canvas, figure).size() * kCaptionLinePx + 10;
}

void drawCaption(const Canvas& canvas, const Figure& figure) {
  const std::vector<std::string> lines = captionLines(canvas, figure);
  double y = figure.heightPx - kOuterPadPx - (lines.size() - 1) * kCaptionLinePx;
  for (const std::string& line : lines) {
    canvas.text({line, ""}, kOuterPadPx, y, kCaptionSizePx, HAlign::Left, VAlign::Baseline, kMutedInk);
    y += kCaptionLinePx;
  }
}

}  // namespace particles::plot
