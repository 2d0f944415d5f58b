// Figures written to SVG and PNG: what is drawn (read back from the SVG), where text lands (in
// the PNG's pixels), byte-identical output, and the failures writeFigure reports.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "plot/errors.hpp"
#include "plot/figure.hpp"
#include "plot/palette.hpp"
#include "plot_support.hpp"

using namespace particles::plot;
using particles::test::decodePng;
using particles::test::glyphsIn;
using particles::test::parseXml;
using particles::test::PathBounds;
using particles::test::pathBounds;
using particles::test::pathShape;
using particles::test::plotFrames;
using particles::test::sameColour;
using particles::test::styleProperty;
using particles::test::TempDir;
using particles::test::XmlElement;

namespace {

// A zigzag: cairo merges collinear line segments, so a straight line would have fewer vertices.
Series line(std::string name, std::size_t points, double slope) {
  Series s{std::move(name), {}, {}};
  for (std::size_t i = 0; i < points; ++i) {
    s.x.push_back(0.5 * i);
    s.y.push_back(1.0 + slope * i + 0.3 * (i % 2));
  }
  return s;
}

// One linear panel with three series of 5, 7 and 9 points.
Figure threeSeries(std::string title, bool named) {
  Figure f;
  f.title = std::move(title);
  f.chart = LineChart{"t [s]",
                      {Panel{"energy [J]",
                             AxisScale::Linear,
                             {line(named ? "alpha" : "", 5, 1.0), line(named ? "beta" : "", 7, -0.5),
                              line(named ? "gamma" : "", 9, 0.25)}}}};
  return f;
}

std::vector<XmlElement> svgOf(const Figure& f) {
  return parseXml(renderFigure(f, ImageFormat::Svg));
}

// <path> elements stroked (or filled) in series colour `index`.
std::vector<XmlElement> pathsIn(const std::vector<XmlElement>& svg, const char* property, std::size_t index) {
  std::vector<XmlElement> out;
  for (const XmlElement& e : svg) {
    if (e.name == "path" && sameColour(styleProperty(e, property), seriesColour(index))) out.push_back(e);
  }
  return out;
}

// The value of `key` that poppler's pdfinfo prints for a PDF file ("Page size:   900 x 600 pts" →
// "900 x 600 pts"), or "(missing)".
std::string pdfInfo(const std::filesystem::path& pdf, const std::string& key) {
  const std::filesystem::path out = pdf.string() + ".info";
  const std::string command = "pdfinfo '" + pdf.string() + "' > '" + out.string() + "' 2>&1";
  REQUIRE_MESSAGE(std::system(command.c_str()) == 0, command);
  std::ifstream in(out);
  const std::string info = "\n" + std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const auto at = info.find("\n" + key + ":");
  if (at == std::string::npos) return "(missing)";
  const auto start = info.find_first_not_of(' ', at + key.size() + 2);
  return info.substr(start, info.find('\n', start) - start);
}

// cairo draws text as glyph outlines, each shown by one <use> element per glyph drawn.
long glyphsDrawn(const std::vector<XmlElement>& svg) {
  return std::count_if(svg.begin(), svg.end(), [](const XmlElement& e) { return e.name == "use"; });
}

}  // namespace

TEST_CASE("plot: SVG has one line per series, with every point, plus one legend swatch") {
  const auto svg = svgOf(threeSeries("Three lines", true));
  const std::size_t points[] = {5, 7, 9};
  for (std::size_t i = 0; i < 3; ++i) {
    CAPTURE(i);
    const auto stroked = pathsIn(svg, "stroke", i);
    REQUIRE(stroked.size() == 2);  // the data line and its legend swatch
    const auto longest = std::max_element(stroked.begin(), stroked.end(), [](const auto& a, const auto& b) {
      return pathShape(a).vertices < pathShape(b).vertices;
    });
    CHECK(pathShape(*longest).vertices == static_cast<int>(points[i]));
    CHECK(pathShape(*longest).subpaths == 1);
  }
  CHECK(pathsIn(svg, "stroke", 3).empty());  // no fourth colour
}

TEST_CASE("plot: SVG carries the title and draws legend and title text as glyphs") {
  const auto svg = svgOf(threeSeries("Lines", true));
  const auto title = std::find_if(svg.begin(), svg.end(), [](const XmlElement& e) { return e.name == "title"; });
  REQUIRE(title != svg.end());
  CHECK(title->text == "Lines");
  // Names without spaces, so the count doesn't depend on whether cairo emits a glyph for a space.
  const long legendGlyphs = std::string("alphabetagamma").size();
  CHECK(glyphsDrawn(svg) - glyphsDrawn(svgOf(threeSeries("Lines", false))) == legendGlyphs);
  CHECK(glyphsDrawn(svg) - glyphsDrawn(svgOf(threeSeries("", true))) == std::string("Lines").size());
}

TEST_CASE("plot: a log axis leaves out non-positive points and breaks the line there") {
  Figure f;
  // Runs: {1, 10}, {100} (alone between two gaps: drawn as a dot), {1000, 10⁴}.
  Series s{"decades", {0, 1, 2, 3, 4, 5, 6}, {1, 10, -1, 100, 0, 1000, 1e4}};
  f.chart = LineChart{"x", {Panel{"y", AxisScale::Log, {s}}}};
  const auto svg = svgOf(f);
  const auto stroked = pathsIn(svg, "stroke", 0);
  REQUIRE(stroked.size() == 2);
  const auto data = pathShape(stroked[0]).vertices > 2 ? stroked[0] : stroked[1];
  CHECK(pathShape(data).subpaths == 2);
  CHECK(pathShape(data).vertices == 4);
  CHECK(pathsIn(svg, "fill", 0).size() == 1);  // the dot at 100

  // The same data on a linear axis is one unbroken line of 7 points.
  std::get<LineChart>(f.chart).panels[0].yScale = AxisScale::Linear;
  const auto linear = pathsIn(svgOf(f), "stroke", 0);
  REQUIRE(linear.size() == 2);
  CHECK(std::max(pathShape(linear[0]).vertices, pathShape(linear[1]).vertices) == 7);
}

TEST_CASE("plot: empty, constant and all-non-positive data make a panel each, with a line or \"no data\" in it") {
  Figure f;
  f.chart = LineChart{
      "t [s]",
      {Panel{"empty", AxisScale::Linear, {}}, Panel{"constant", AxisScale::Linear, {{"c", {0, 1, 2}, {3, 3, 3}}}},
       Panel{"zero", AxisScale::Linear, {{"z", {0, 1}, {0, 0}}}},
       Panel{"log of nothing", AxisScale::Log, {{"n", {0, 1}, {0, -2}}}}}};
  const auto svg = svgOf(f);
  // Four frames of one width (plotFrames keeps them top to bottom), stacked without overlapping.
  const auto frames = plotFrames(svg);
  REQUIRE(frames.size() == 4);
  for (std::size_t k = 1; k < frames.size(); ++k) {
    CAPTURE(k);
    CHECK(frames[k].x0 == frames[0].x0);
    CHECK(frames[k].x1 == frames[0].x1);
    CHECK(frames[k].y0 > frames[k - 1].y1);
  }
  // "no data" (7 glyphs, the space one) in the middle of the panels with nothing to draw, and
  // nowhere else; a line in the others: the constant across the middle of its range (2.5 … 3.5),
  // the zeros on the bottom edge from t = 0 to 1 (of 0 … 2). The legend's swatches are 26 px wide.
  const long noDataGlyphs = std::string("no data").size();
  const auto middle = [](const PathBounds& frame) {
    return PathBounds{frame.centreX() - 50, frame.centreY() - 10, frame.centreX() + 50, frame.centreY() + 10};
  };
  const auto lines = [&](const PathBounds& frame) {
    std::vector<PathBounds> inside;
    for (const XmlElement& e : pathsIn(svg, "stroke", 0)) {
      const PathBounds b = pathBounds(e);
      if (b.x1 - b.x0 != 26 && b.x0 >= frame.x0 - 1 && b.x1 <= frame.x1 + 1 && b.y0 >= frame.y0 - 1 &&
          b.y1 <= frame.y1 + 1) {
        inside.push_back(b);
      }
    }
    return inside;
  };
  CHECK(glyphsIn(svg, middle(frames[0])) == noDataGlyphs);
  CHECK(glyphsIn(svg, middle(frames[3])) == noDataGlyphs);
  CHECK(glyphsIn(svg, middle(frames[1])) == 0);
  CHECK(glyphsIn(svg, middle(frames[2])) == 0);
  CHECK(lines(frames[0]).empty());
  CHECK(lines(frames[3]).empty());
  const auto constant = lines(frames[1]);
  REQUIRE(constant.size() == 1);
  // Within a pixel: frames are stroked on half pixels, lines at the data's pixel coordinates.
  CHECK(std::abs(constant[0].x0 - frames[1].x0) <= 1);
  CHECK(std::abs(constant[0].x1 - frames[1].x1) <= 1);
  CHECK(std::abs(constant[0].centreY() - frames[1].centreY()) <= 1);
  const auto zeros = lines(frames[2]);
  REQUIRE(zeros.size() == 1);
  CHECK(std::abs(zeros[0].x0 - frames[2].x0) <= 1);
  CHECK(std::abs(zeros[0].x1 - frames[2].centreX()) <= 1);
  CHECK(std::abs(zeros[0].centreY() - frames[2].y1) <= 1);

  // The PNG has the SVG's layout: the figure's size, the constant's line in the series' colour
  // where the SVG has it, white above it, "no data" dark in the empty panel's middle and nothing
  // dark in the zeros' middle.
  const auto png = decodePng(renderFigure(f, ImageFormat::Png));
  REQUIRE(png.width == 1200);
  REQUIRE(png.height == 800);
  const int lineY = int(constant[0].centreY());
  for (const double share : {0.1, 0.5, 0.9}) {
    const int x = int(frames[1].x0 + share * (frames[1].x1 - frames[1].x0));
    CAPTURE(x);
    CHECK(png.is(x, lineY, seriesColour(0)));
    CHECK(png.inkedPixels(x, lineY - 20, x + 1, lineY - 5) == 0);
  }
  const PathBounds text = middle(frames[0]);
  CHECK(png.darkPixels(int(text.x0), int(text.y0), int(text.x1), int(text.y1)) > 20);
  const PathBounds empty = middle(frames[2]);
  CHECK(png.darkPixels(int(empty.x0), int(empty.y0), int(empty.x1), int(empty.y1)) == 0);
  // The PDF's page is the figure at 96 px per inch: 900 × 600 pt, as poppler's pdfinfo reads it (cairo
  // 1.18 compresses the page dictionary that 1.16 wrote as text).
  TempDir dir;
  writeFigure(f, dir / "empty.pdf");
  CHECK(pdfInfo(dir / "empty.pdf", "Page size") == "900 x 600 pts");

  // No panels at all, or a dot chart of nothing: one frame saying "no data".
  using Chart = std::variant<LineChart, DotChart>;
  for (const Chart& chart : {Chart{LineChart{}}, Chart{DotChart{}}}) {
    f.chart = chart;
    const auto nothing = svgOf(f);
    const auto frame = plotFrames(nothing);
    REQUIRE(frame.size() == 1);
    CHECK(glyphsIn(nothing, middle(frame[0])) == noDataGlyphs);
  }
}

// gather's figure: markers on log or linear axes, fitted to a parameter and results that may lie
// anywhere in the doubles (such ranges were once refused as an output failure).
TEST_CASE("plot: marked series on log and linear axes at the ends of the doubles are drawn") {
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  const std::vector<std::vector<double>> columns = {
      {tiny, 2 * tiny}, {tiny, 1e-300, 1e300, big}, {-tiny, tiny}, {-big, big}, {5, 5}, {1e-310, 1e-310}};
  for (const auto& xs : columns) {
    for (const auto& ys : columns) {
      for (const AxisScale xScale : {AxisScale::Linear, AxisScale::Log}) {
        for (const AxisScale yScale : {AxisScale::Linear, AxisScale::Log}) {
          const std::size_t n = std::min(xs.size(), ys.size());
          Series s{"rk4", std::vector<double>(xs.begin(), xs.begin() + long(n)),
                   std::vector<double>(ys.begin(), ys.begin() + long(n)), true};
          Figure f;
          f.chart = LineChart{"x", {Panel{"y", yScale, {s}}}, xScale};
          CAPTURE(xs.front());
          CAPTURE(ys.front());
          CAPTURE(int(xScale));
          CAPTURE(int(yScale));
          // One marker per point that its axes can show (a log axis only positive values), all in
          // the series' one filled path, one sub-path each.
          std::size_t plottable = 0;
          for (std::size_t i = 0; i < n; ++i) {
            plottable += (xScale == AxisScale::Linear || xs[i] > 0) && (yScale == AxisScale::Linear || ys[i] > 0);
          }
          std::vector<XmlElement> svg;
          REQUIRE_NOTHROW(svg = svgOf(f));
          int markers = 0;
          for (const XmlElement& dots : pathsIn(svg, "fill", 0)) markers += pathShape(dots).subpaths;
          CHECK(markers == int(plottable));
        }
      }
    }
  }
}

TEST_CASE("plot: dot chart draws one dot per positive value and a legend dot per group") {
  Figure f;
  f.chart = DotChart{
      "dt [s]", {"euler", "midpoint", "rk4"}, {{"stable", {0.002, 0.03, 0.3}}, {"smooth", {0.0005, 0.0, 0.1}}}, "", {}};
  const auto svg = svgOf(f);
  CHECK(pathsIn(svg, "fill", 0).size() == 3 + 1);
  CHECK(pathsIn(svg, "fill", 1).size() == 2 + 1);  // 0 is not drawable on the log axis: "n/a"

  std::get<DotChart>(f.chart).groups.pop_back();
  CHECK(pathsIn(svgOf(f), "fill", 1).empty());
  std::get<DotChart>(f.chart).references = {Reference{0.1, 0.2}};  // one reference for three rows
  CHECK_THROWS_AS(renderFigure(f, ImageFormat::Svg), FigureError);
}

TEST_CASE("plot: a caption is wrapped to the figure's width under the chart") {
  Figure f = threeSeries("Captioned", true);
  const auto without = decodePng(renderFigure(f, ImageFormat::Png));
  f.caption = {std::string(40, 'x') + " " + std::string(40, 'y') + " " + std::string(40, 'z')};
  f.widthPx = 400;
  const auto narrow = parseXml(renderFigure(f, ImageFormat::Svg));
  f.widthPx = 1200;
  const auto wide = parseXml(renderFigure(f, ImageFormat::Svg));
  // Three words of 40 letters do not fit on one line of 400 px: more lines, the plot less tall.
  CHECK(plotFrames(narrow).front().y1 < plotFrames(wide).front().y1 - 10);
  // In the PNG the caption's ink is in the bottom strip (where the x label was without it).
  const auto with = decodePng(renderFigure(f, ImageFormat::Png));
  CHECK(with.inkedPixels(0, with.height - 36, with.width, with.height) >
        without.inkedPixels(0, without.height - 36, without.width, without.height) + 300);
}

TEST_CASE("plot: PNG has text where the title and axis labels go and nothing in the margins") {
  Figure f = threeSeries("A title for the figure", true);
  const auto png = decodePng(renderFigure(f, ImageFormat::Png));
  REQUIRE(png.width == 1200);
  REQUIRE(png.height == 800);
  const int w = png.width, h = png.height;
  // Title: centred, its capitals from 20 px down; x label: centred under the bottom tick labels;
  // y label: rotated, in the leftmost 20–40 px, centred on the panel.
  CHECK(png.darkPixels(w / 2 - 150, 15, w / 2 + 150, 40) > 100);
  CHECK(png.darkPixels(w / 2 - 100, h - 50, w / 2 + 100, h - 15) > 40);
  CHECK(png.darkPixels(15, h / 2 - 100, 40, h / 2 + 100) > 80);
  // The outer 12 px of the figure are margin: pure background.
  CHECK(png.inkedPixels(0, 0, w, 12) == 0);
  CHECK(png.inkedPixels(0, h - 12, w, h) == 0);
  CHECK(png.inkedPixels(0, 0, 12, h) == 0);
  CHECK(png.inkedPixels(w - 12, 0, w, h) == 0);

  // The measure tells text from no text: without a title, its band is empty.
  f.title.clear();
  const auto untitled = decodePng(renderFigure(f, ImageFormat::Png));
  CHECK(untitled.darkPixels(w / 2 - 150, 0, w / 2 + 150, 18) == 0);
}

TEST_CASE("plot: the same figure gives the same bytes, in one process and written twice") {
  TempDir dir;
  const Figure f = threeSeries("Twice", true);
  for (const char* name : {"a.svg", "a.png", "a.pdf"}) {
    CAPTURE(name);
    writeFigure(f, dir / name);
    const auto first = particles::test::readBytes(dir / name);
    writeFigure(f, dir / name);  // replaces it
    CHECK(particles::test::readBytes(dir / name) == first);
    CHECK(renderFigure(f, formatForPath(name)) == first);
  }
  // Only the two outputs: no temporary left behind.
  auto entries = dir.entries();
  std::sort(entries.begin(), entries.end());
  CHECK(entries == std::vector<std::string>{"a.pdf", "a.png", "a.svg"});
  // The SVG is px-sized like the PNG.
  const auto svg = parseXml(particles::test::readBytes(dir / "a.svg"));
  CHECK(svg.front().attributes.at("width") == "1200px");
}

// poppler's tools (Debian poppler-utils) read the PDF back: another program than the one that wrote it.
TEST_CASE("plot: a PDF figure parses, its page is the figure at 96 px per inch, and its text is text") {
  TempDir dir;
  Figure f = threeSeries("Energy of a test figure", true);
  f.caption = {"Caption words here."};
  writeFigure(f, dir / "figure.pdf");
  const auto run = [&](const std::string& command) {
    const std::string out = (dir / "out.txt").string();
    REQUIRE_MESSAGE(std::system((command + " > " + out + " 2>&1").c_str()) == 0, command);
    std::ifstream in(out);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  CHECK(pdfInfo(dir / "figure.pdf", "Page size") == "900 x 600 pts");  // 1200 × 800 px
  CHECK(pdfInfo(dir / "figure.pdf", "Pages") == "1");
  CHECK(pdfInfo(dir / "figure.pdf", "Title") == "Energy of a test figure");
  const std::string text = run("pdftotext " + (dir / "figure.pdf").string() + " -");
  for (const char* words : {"Energy of a test figure", "alpha", "energy [J]", "Caption words here."}) {
    CHECK_MESSAGE(text.find(words) != std::string::npos, words << " in: " << text);
  }
}

TEST_CASE("plot: a bad extension or an unwritable path is an error naming it, and leaves no file") {
  TempDir dir;
  const Figure f = threeSeries("", true);
  const auto expectError = [&](const std::filesystem::path& out, const std::string& says) {
    CAPTURE(out);
    try {
      writeFigure(f, out);
      FAIL("no error");
    } catch (const FigureError& e) {
      const std::string message = e.what();
      CHECK(message.find(out.string()) != std::string::npos);
      CHECK(message.find(says) != std::string::npos);
    }
  };
  expectError(dir / "figure.jpg", ".svg, .png or .pdf");
  expectError(dir / "figure", ".svg, .png or .pdf");
  expectError(dir / "missing" / "figure.png", "No such file or directory");
  std::filesystem::create_directory(dir / "taken.svg");  // not ours to replace
  expectError(dir / "taken.svg", "it is a directory");
  CHECK(dir.entries() == std::vector<std::string>{"taken.svg"});
  CHECK(std::filesystem::is_empty(dir / "taken.svg"));
}

TEST_CASE("plot: a missing font file is an error naming it") {
  Figure f = threeSeries("", true);
  f.fontFile = "/nonexistent/fonts/DejaVuSans.ttf";
  try {
    renderFigure(f, ImageFormat::Png);
    FAIL("no error");
  } catch (const FigureError& e) {
    CHECK(std::string(e.what()).find("/nonexistent/fonts/DejaVuSans.ttf") != std::string::npos);
    CHECK(std::string(e.what()).find("fonts-dejavu-core") != std::string::npos);
  }
}

TEST_CASE("plot: a series whose x and y differ in length is refused") {
  Figure f;
  f.chart = LineChart{"x", {Panel{"y", AxisScale::Linear, {{"bad", {0, 1, 2}, {0, 1}}}}}};
  CHECK_THROWS_AS(renderFigure(f, ImageFormat::Svg), FigureError);
}
