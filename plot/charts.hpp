#pragma once
// The two kinds of chart, drawn onto a canvas the size of the figure. Internal to plot/: users call
// writeFigure or renderFigure (figure.hpp).

#include "plot/canvas.hpp"
#include "plot/figure.hpp"

namespace particles::plot {

void drawLineChart(const Canvas& canvas, const Figure& figure, const LineChart& chart);
void drawDotChart(const Canvas& canvas, const Figure& figure, const DotChart& chart);

// Shared by both: the title centred above the chart, and the height it takes from the top.
double drawTitle(const Canvas& canvas, const Figure& figure);
// The caption under the chart, wrapped to the figure's width: its height (0 without a caption),
// for the bottom margin, and drawing it against the bottom edge.
double captionHeight(const Canvas& canvas, const Figure& figure);
void drawCaption(const Canvas& canvas, const Figure& figure);

// The y axis of one panel: ticks on the left edge of `plot`, their labels, and the rotated axis
// label at `labelX` (its left edge). Grid lines at the major ticks go across the plot.
struct YAxis {
  AxisScale scale;
  AxisTicks ticks;
  // Data value to pixel row inside `plot`.
  double toPixel(double v, const Rect& plot) const;
};
void drawYAxis(const Canvas& canvas, const YAxis& axis, const Rect& plot, const std::string& label, double labelX);

// The x axis shared by the charts: data value to pixel column inside `plot`.
struct XAxis {
  AxisTicks ticks;
  AxisScale scale = AxisScale::Linear;
  double toPixel(double v, const Rect& plot) const;
};
// The height under the plot taken by the x tick labels, the x label (if any) and the caption.
double xAxisMargin(const Canvas& canvas, const Figure& figure, const std::string& xLabel);
// Under `plot`: the major ticks' labels, and the x label under them.
void drawXLabels(const Canvas& canvas, const XAxis& axis, const Rect& plot, const std::string& xLabel);
void drawYGrid(const Canvas& canvas, const YAxis& axis, const Rect& plot);
// Widest tick label of the axis, for the left margin.
double tickLabelWidth(const Canvas& canvas, const AxisTicks& ticks);

// Layout constants shared by the charts, in pixels.
inline constexpr double kOuterPadPx = 20;  // figure edge to the nearest text
inline constexpr double kRightMarginPx = 32;  // plot area to the figure's right edge
inline constexpr double kTickLengthPx = 6;
inline constexpr double kMinorTickLengthPx = 3;
inline constexpr double kTickLabelGapPx = 6;   // tick end to its label
inline constexpr double kAxisLabelGapPx = 12;  // tick labels to the axis label
inline constexpr double kCaptionSizePx = 13;
inline constexpr double kCaptionLinePx = 18;

}  // namespace particles::plot
