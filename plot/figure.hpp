#pragma once
// Figures for reports: a description of a chart (data, labels, scales) and writeFigure, which draws
// it with cairo to SVG (vector, for documents) or PNG (for screens), chosen by the extension.
// A Figure is plain data: build one, or take one from statsFigure / stabilityFigure
// (stats_figure.hpp, stability_figure.hpp), adjust titles or sizes, and write it.
//
// Text is drawn with DejaVu Sans loaded from `fontFile` through FreeType, not looked up through
// fontconfig, so a figure looks the same on every machine and the same input gives the same bytes.

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace particles::plot {

// The Debian package fonts-dejavu-core puts it here (scripts/deps installs it).
inline const std::filesystem::path kDejaVuSans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

enum class AxisScale {
  Linear,  // "nice" ticks in steps of 1, 2 or 5 × 10^k; the range is widened to whole steps
  Log,     // ticks at decades, minor ticks at 2…9 × 10^k; the range is widened to whole decades.
           // Points with y ≤ 0 cannot be shown on a log axis: they are left out and the line is
           // broken there (as it is at NaN or ±inf on either kind of axis).
};

// One named line. x and y must have the same length. Colours follow the series' order in its panel.
struct Series {
  std::string name;  // in the legend; an empty name leaves the series out of the legend
  std::vector<double> x, y;
  bool markers = false;  // a dot at every point, for a few measured points rather than a time series
};

struct Panel {
  std::string yLabel;  // with units, e.g. "energy [J]"
  AxisScale yScale = AxisScale::Linear;
  std::vector<Series> series;
};

// One or more panels stacked top to bottom, sharing one x axis (x labels on the bottom panel).
struct LineChart {
  std::string xLabel;  // e.g. "t [s]"
  std::vector<Panel> panels;
  AxisScale xScale = AxisScale::Linear;  // Log: points with x ≤ 0 are left out, as on a log y axis
};

// One bar per category in each group; the groups are told apart by colour and the legend.
struct BarGroup {
  std::string name;            // e.g. "largest stable dt"
  std::vector<double> values;  // one per category; a value ≤ 0 or not finite is drawn as "n/a"
};

// Bars on a log y axis starting at its bottom edge, each labelled with its value.
struct BarChart {
  std::string xLabel;                   // may be empty, e.g. "integrator"
  std::string yLabel;                   // e.g. "dt [s]"
  std::vector<std::string> categories;  // e.g. euler, midpoint, rk4
  std::vector<BarGroup> groups;
};

struct Figure {
  std::string title;  // drawn above the chart; also the SVG's <title>
  std::variant<LineChart, BarChart> chart;
  // Pixels in the PNG; user units ("px") in the SVG. Text sizes are fixed in pixels (13–16 px),
  // chosen for the default size.
  int widthPx = 1200;
  int heightPx = 800;
  std::filesystem::path fontFile = kDejaVuSans;
};

enum class ImageFormat { Svg, Png };

// The format an output path asks for: ".svg" or ".png" (any case). Throws FigureError naming the
// path for anything else.
ImageFormat formatForPath(const std::filesystem::path& out);

// The encoded file contents. Throws FigureError (bad figure, missing font, cairo failure).
std::vector<std::uint8_t> renderFigure(const Figure& figure, ImageFormat format);

// Renders and writes `out` (SVG or PNG by extension) through output::PendingOutput: the figure
// appears only when complete; on any failure `out` is left as it was and FigureError says which
// path and which call failed.
void writeFigure(const Figure& figure, const std::filesystem::path& out);

}  // namespace particles::plot
