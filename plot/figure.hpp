#pragma once
// Figures for reports: a description of a chart (data, labels, scales) and writeFigure, which draws
// it with cairo to SVG, PDF (vector, for documents) or PNG (for screens), chosen by the extension.
// A Figure is plain data: build one, or take one from statsFigure / stabilityFigure
// (stats_figure.hpp, stability_figure.hpp), adjust titles or sizes, and write it.
//
// Text is drawn with DejaVu Sans loaded from `fontFile` through FreeType, not looked up through
// fontconfig, so a figure looks the same on every machine and the same input gives the same bytes.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace particles::plot {

// The Debian package fonts-dejavu-core puts it here (scripts/deps installs it).
inline const std::filesystem::path kDejaVuSans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
// Where a release (scripts/release) keeps its own copy, relative to the folder of the program, the
// library or the Python module that draws: the archive's bin/ and lib/ are beside its share/, the
// wheel's module beside it.
inline constexpr const char* kBundledFontFolders[] = {"../share/particles/fonts", "share/particles/fonts"};

// The font a figure or frame is drawn with unless told otherwise: a release's own DejaVu Sans,
// found from where the code that draws was loaded, else kDejaVuSans. A release's own copy comes
// first so that it draws the same bytes on any machine, whatever font that machine has.
const std::filesystem::path& defaultFontFile();

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

// An interval of x shaded across every panel and labelled at the top of the first one: when
// something outside the data acts, e.g. a scripted mouse holds a particle from t = 12 s to 22 s.
struct Band {
  double from, to;
  std::string label;  // may be empty
};

// One or more panels stacked top to bottom, sharing one x axis (x labels on the bottom panel).
struct LineChart {
  std::string xLabel;  // e.g. "t [s]"
  std::vector<Panel> panels;
  AxisScale xScale = AxisScale::Linear;  // Log: points with x ≤ 0 are left out, as on a log y axis
  std::vector<Band> bands = {};
};

// One value per category in each group, e.g. the largest stable dt per integrator.
struct DotGroup {
  std::string name;                    // in the legend, e.g. "largest stable dt"
  std::vector<double> values;          // one per category; a value ≤ 0 or not finite is drawn as "n/a"
  std::vector<bool> lowerBounds = {};  // empty, or one per category: true labels the value "≥ v"
};

// A value known from elsewhere for one category: a point (lo == hi) or a range in which it lies.
struct Reference {
  double lo, hi;
};

// A dot plot: one row per category, the groups' values as dots (each labelled with its value) on a
// log x axis fitted to the data, and optional reference values as open diamonds or ranges. Unlike
// bars on a log axis, a dot's position does not depend on where the axis happens to start.
struct DotChart {
  std::string xLabel;                   // e.g. "dt [s]"
  std::vector<std::string> categories;  // the rows, top to bottom, e.g. euler, midpoint, rk4
  std::vector<DotGroup> groups;
  std::string referenceName;                         // in the legend, e.g. "report"; used when `references` has any
  std::vector<std::optional<Reference>> references;  // empty, or one per category
};

struct Figure {
  std::string title;  // drawn above the chart; also the SVG's <title>
  std::variant<LineChart, DotChart> chart;
  // Lines of small text under the chart (wrapped to the width): what a reader needs to read it,
  // such as the criteria behind the values or what a shaded interval means.
  std::vector<std::string> caption;
  // Pixels in the PNG; user units ("px") in the SVG. Text sizes are fixed in pixels (13–16 px),
  // chosen for the default size.
  int widthPx = 1200;
  int heightPx = 800;
  std::filesystem::path fontFile = defaultFontFile();
};

// SVG (vector, for web pages), PNG (pixels, for screens), PDF (vector, for LaTeX; its page is the
// figure at 96 px per inch, text kept as text).
enum class ImageFormat { Svg, Png, Pdf };

// The format an output path asks for: ".svg", ".png" or ".pdf" (any case). Throws FigureError
// naming the path for anything else.
ImageFormat formatForPath(const std::filesystem::path& out);

// The encoded file contents. Throws FigureError (bad figure, missing font, cairo failure).
std::vector<std::uint8_t> renderFigure(const Figure& figure, ImageFormat format);

// Renders and writes `out` (SVG, PNG or PDF by extension) through output::PendingOutput: the figure
// appears only when complete; on any failure `out` is left as it was and FigureError says which
// path and which call failed.
void writeFigure(const Figure& figure, const std::filesystem::path& out);

}  // namespace particles::plot
