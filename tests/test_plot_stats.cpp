// The stats CSV reader (strict, errors with file, line and column) and the two ready-made figures.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "plot/errors.hpp"
#include "plot/figure.hpp"
#include "plot/palette.hpp"
#include "plot/stability_figure.hpp"
#include "plot/stats_figure.hpp"
#include "plot_support.hpp"

using namespace particles::plot;
using particles::test::parseXml;
using particles::test::PathBounds;
using particles::test::pathBounds;
using particles::test::PathPoint;
using particles::test::pathPoints;
using particles::test::pathShape;
using particles::test::plotFrames;
using particles::test::sameColour;
using particles::test::styleProperty;
using particles::test::TempDir;
using particles::test::XmlElement;

namespace {

const std::string kHeader = "t,kinetic,potential,total,constraint_error,penetration";

std::filesystem::path writeText(const TempDir& dir, const std::string& text) {
  const auto path = dir / "stats.csv";
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The CsvError reading `text` gives; fails the test if there is none.
CsvError csvError(const std::string& text) {
  TempDir dir;
  const auto path = writeText(dir, text);
  try {
    readStatsCsv(path);
  } catch (const CsvError& e) {
    CHECK(std::string(e.what()).rfind(path.string() + ":", 0) == 0);  // starts with the file name
    return e;
  }
  FAIL("no CsvError for: " << text);
  return CsvError("", 0, 0, "");
}

}  // namespace

TEST_CASE("plot stats CSV: rows are read into columns, CRLF and a missing final newline accepted") {
  TempDir dir;
  const auto table =
      readStatsCsv(writeText(dir, kHeader + "\r\n0,1.5,-2,-0.5,0,0\r\n0.0166666666666666664,2,3,5,1e-12,2.5E-3"));
  REQUIRE(table.rows() == 2);
  CHECK(table.t[1] == 0.0166666666666666664);
  CHECK(table.kinetic == std::vector<double>{1.5, 2});
  CHECK(table.potential == std::vector<double>{-2, 3});
  CHECK(table.total == std::vector<double>{-0.5, 5});
  CHECK(table.constraintError == std::vector<double>{0, 1e-12});
  CHECK(table.penetration == std::vector<double>{0, 2.5e-3});
  CHECK(readStatsCsv(writeText(dir, kHeader + "\n")).rows() == 0);
}

TEST_CASE("plot stats CSV: text in memory is read by the same rules, its name labelling errors") {
  const auto table = parseStatsCsv(kHeader + "\n0,1,2,3,0,0\n0.5,1,2,3,1e-9,0\n", "memory.csv");
  CHECK(table.t == std::vector<double>{0, 0.5});
  CHECK(table.constraintError == std::vector<double>{0, 1e-9});
  CHECK_THROWS_WITH_AS(parseStatsCsv(kHeader + "\n0,1,2,3,0\n", "memory.csv"),
                       doctest::Contains("memory.csv:2:10: expected 6 fields, found 5"), CsvError);
}

TEST_CASE("plot stats CSV: errors carry the line and the column of the offending field") {
  SUBCASE("header") {
    const CsvError e = csvError("t,kinetic,potential,total,constraint_err,penetration\n");
    CHECK(e.line() == 1);
    CHECK(e.column() == 41);  // where "constraint_err," and "constraint_error" part
    CHECK(std::string(e.what()).find(kHeader) != std::string::npos);
  }
  SUBCASE("non-numeric field") {
    const CsvError e = csvError(kHeader + "\n0,1,2,3,0,0\n0.1,abc,2,3,0,0\n");
    CHECK(e.line() == 3);
    CHECK(e.column() == 5);
    CHECK(std::string(e.what()).find("'kinetic'") != std::string::npos);
    CHECK(std::string(e.what()).find("'abc'") != std::string::npos);
  }
  SUBCASE("trailing garbage, a space, an empty field, NaN") {
    CHECK(csvError(kHeader + "\n0,1,2,3x,0,0\n").column() == 7);
    CHECK(csvError(kHeader + "\n0,1,2, 3,0,0\n").column() == 7);
    CHECK(csvError(kHeader + "\n0,1,,3,0,0\n").column() == 5);
    CHECK(csvError(kHeader + "\n0,1,2,3,nan,0\n").column() == 9);
  }
  SUBCASE("too few and too many fields") {
    const CsvError few = csvError(kHeader + "\n0,1,2\n");
    CHECK(few.line() == 2);
    CHECK(few.column() == 6);
    const CsvError many = csvError(kHeader + "\n0,1,2,3,4,5,6\n");
    CHECK(many.line() == 2);
    CHECK(many.column() == 13);
  }
  SUBCASE("blank line and empty file") {
    CHECK(csvError(kHeader + "\n0,1,2,3,0,0\n\n1,1,2,3,0,0\n").line() == 3);
    CHECK(csvError("").line() == 1);
  }
}

TEST_CASE("plot stats CSV: a missing file is an error naming it") {
  TempDir dir;
  try {
    readStatsCsv(dir / "absent.csv");
    FAIL("no error");
  } catch (const CsvError& e) {
    CHECK(std::string(e.what()).find((dir / "absent.csv").string()) != std::string::npos);
    CHECK(e.line() == 0);
  }
}

TEST_CASE("plot stats figure: energy, then constraint error on a log axis and penetration, each on its own panel") {
  StatsTable table;
  for (int i = 0; i < 10; ++i) {
    table.t.push_back(0.1 * i);
    table.kinetic.push_back(i);
    table.potential.push_back(10 - i);
    table.total.push_back(10);
    table.constraintError.push_back(1e-3 * (1 + i));        // within a decade: still a log axis
    table.penetration.push_back(1e-9 * std::pow(10.0, i));  // nine decades
  }
  Figure f = statsFigure(table);
  const auto& chart = std::get<LineChart>(f.chart);
  CHECK(chart.xLabel == "t [s]");
  REQUIRE(chart.panels.size() == 3);
  CHECK(chart.panels[0].series.size() == 3);
  CHECK(chart.panels[0].series[2].name == "total");
  CHECK(chart.panels[0].yScale == AxisScale::Linear);
  CHECK(chart.panels[1].yLabel == "constraint error [m]");
  CHECK(chart.panels[1].yScale == AxisScale::Log);
  CHECK(chart.panels[1].series[0].y == table.constraintError);
  CHECK(chart.panels[2].yLabel == "penetration [m]");
  CHECK(chart.panels[2].yScale == AxisScale::Log);
  CHECK(chart.panels[2].series[0].y == table.penetration);
  CHECK(f.caption.empty());
  CHECK(chart.bands.empty());

  for (double& p : table.penetration) p = 1e-3 * (1 + p);  // within a decade: linear
  CHECK(std::get<LineChart>(statsFigure(table).chart).panels[2].yScale == AxisScale::Linear);

  // A column that is 0 throughout gets a line in the caption instead of a panel hiding on its axis.
  for (double& e : table.constraintError) e = 0;
  f = statsFigure(table);
  REQUIRE(std::get<LineChart>(f.chart).panels.size() == 2);
  CHECK(std::get<LineChart>(f.chart).panels[1].yLabel == "penetration [m]");
  CHECK(f.caption == std::vector<std::string>{"Constraint error: 0 throughout."});
  for (double& p : table.penetration) p = 0;
  f = statsFigure(table);
  CHECK(std::get<LineChart>(f.chart).panels.size() == 1);
  CHECK(f.caption.size() == 2);

  table.penetration.pop_back();
  CHECK_THROWS_AS(statsFigure(table), FigureError);
}

TEST_CASE("plot stats figure: the title names the scenario, integrator and dt, mouse intervals become bands") {
  StatsTable table;
  for (int i = 0; i <= 60; ++i) {
    table.t.push_back(i);
    table.kinetic.push_back(i % 7);
    table.potential.push_back(1);
    table.total.push_back(1 + i % 7);
    table.constraintError.push_back(0);
    table.penetration.push_back(0);
  }
  CHECK(statsFigure(table).title == "Energy and constraint error");
  StatsFigureContext fromCsv;
  fromCsv.source = "man.csv";
  CHECK(statsFigure(table, fromCsv).title == "Energy and constraint error: man.csv");
  StatsFigureContext context{
      "soft_body", "rk4", 0.15, "man.csv", {{12, 22, "mouse: torso[2][1]"}, {32, 42, "mouse: arm_l[0][0]"}}};
  const Figure f = statsFigure(table, context);
  CHECK(f.title == "Energy and constraint error: soft_body, rk4, dt = 0.15 s");
  REQUIRE(std::get<LineChart>(f.chart).bands.size() == 2);
  CHECK(f.caption.front().find("mouse") != std::string::npos);

  // In the SVG: each band is a rectangle filled in the band colour in the (one) panel, from the
  // x of its start to the x of its end on the time axis, which spans the data (0 … 60 s).
  const auto svg = parseXml(renderFigure(f, ImageFormat::Svg));
  const auto frames = plotFrames(svg);
  REQUIRE(!frames.empty());
  const PathBounds plot = frames.front();
  std::vector<PathBounds> bands;
  for (const XmlElement& e : svg) {
    if (e.name == "path" && sameColour(styleProperty(e, "fill"), kBand)) bands.push_back(pathBounds(e));
  }
  REQUIRE(bands.size() == 2);
  const auto xOf = [&](double t) { return plot.x0 + (plot.x1 - plot.x0) * t / 60; };
  for (int k = 0; k < 2; ++k) {
    CAPTURE(k);
    const auto& band = std::get<LineChart>(f.chart).bands[k];
    CHECK(std::abs(bands[k].x0 - xOf(band.from)) < 1.0);
    CHECK(std::abs(bands[k].x1 - xOf(band.to)) < 1.0);
    CHECK(bands[k].y0 >= plot.y0 - 1);
    CHECK(bands[k].y1 <= plot.y1 + 1);
  }
}

TEST_CASE("plot stability figure: a dot per integrator and limit on a log axis fitted to the data, references beside") {
  const std::vector<StabilityRow> rows = {
      {"euler", 1, 0.0021, 0.00052, 1923, 1}, {"midpoint", 2, 0.031, 0.012, 166, 11.6}, {"rk4", 4, 0.29, 0.11, 36, 53}};
  Figure f = stabilityFigure(rows);
  const auto& chart = std::get<DotChart>(f.chart);
  CHECK(chart.categories == std::vector<std::string>{"euler", "midpoint", "rk4"});
  REQUIRE(chart.groups.size() == 2);
  CHECK(chart.groups[0].name == "largest stable dt");
  CHECK(chart.groups[0].values == std::vector<double>{0.0021, 0.031, 0.29});
  CHECK(chart.groups[1].name == "largest dt without shaking");
  CHECK(chart.groups[1].values == std::vector<double>{0.00052, 0.012, 0.11});
  CHECK(chart.references.empty());
  CHECK(chart.groups[0].lowerBounds == std::vector<bool>{false, false, false});
  std::vector<StabilityRow> bounded = rows;
  bounded[2].stableAtMaxDt = true;  // still stable at --max-dt: "≥ 0.29"
  CHECK(std::get<DotChart>(stabilityFigure(bounded).chart).groups[0].lowerBounds ==
        std::vector<bool>{false, false, true});

  // Dots: filled circles in the group's colour (one more in the legend). From two dots' centres
  // and the frame, the axis' ends: fitted to the data, not widened to whole decades (0.0001 … 1).
  auto svg = parseXml(renderFigure(f, ImageFormat::Svg));
  std::vector<PathBounds> stable;
  for (const XmlElement& e : svg) {
    if (e.name == "path" && sameColour(styleProperty(e, "fill"), seriesColour(0)) && pathShape(e).curves > 0)
      stable.push_back(pathBounds(e));
  }
  REQUIRE(stable.size() == 3 + 1);
  const PathBounds plot = plotFrames(svg).front();
  std::sort(stable.begin(), stable.end(), [](const auto& a, const auto& b) { return a.centreY() > b.centreY(); });
  stable.pop_back();  // the legend's, above the plot
  std::sort(stable.begin(), stable.end(), [](const auto& a, const auto& b) { return a.centreX() < b.centreX(); });
  const double f0 = (stable[0].centreX() - plot.x0) / (plot.x1 - plot.x0);  // 0.0021
  const double f2 = (stable[2].centreX() - plot.x0) / (plot.x1 - plot.x0);  // 0.29
  const double decadesPerWidth = (std::log10(0.29) - std::log10(0.0021)) / (f2 - f0);
  const double axisLo = std::log10(0.0021) - f0 * decadesPerWidth, axisHi = axisLo + decadesPerWidth;
  CHECK(axisLo > std::log10(0.00052) - 0.5);  // the smallest value, 0.00052, is near the left end
  CHECK(axisLo < std::log10(0.00052));
  CHECK(axisHi > std::log10(0.29));
  CHECK(axisHi < std::log10(0.29) + 0.7);  // room for its label, not a decade of air

  // References: a point (an open diamond) and a range (a bar with end caps), and one in the legend.
  StabilityFigureNotes notes;
  notes.references = {{"euler", {0.003, 0.005}}, {"rk4", {0.3, 0.3}}};
  notes.referenceName = "report";
  notes.caption = {"Criteria."};
  f = stabilityFigure(rows, notes);
  const auto& withReferences = std::get<DotChart>(f.chart);
  REQUIRE(withReferences.references.size() == 3);
  CHECK(withReferences.references[0]->lo == 0.003);
  CHECK_FALSE(withReferences.references[1].has_value());
  CHECK(f.caption == notes.caption);
  // Marks are stroked 1.5 px wide in ink (ticks and frames are 1 px hairlines).
  const auto inkStrokes = [](const std::vector<XmlElement>& doc) {
    return std::count_if(doc.begin(), doc.end(), [](const XmlElement& e) {
      return e.name == "path" && sameColour(styleProperty(e, "stroke"), kInk) &&
             styleProperty(e, "stroke-width") == "1.5";
    });
  };
  CHECK(inkStrokes(parseXml(renderFigure(f, ImageFormat::Svg))) - inkStrokes(svg) == 3);
}

// Values near ±1.8e308 once overflowed the axis span: the tick loop never ended (and cast ±inf to
// int); later cairo refused the non-finite coordinates. Any finite data must give a figure.
TEST_CASE("plot stats figure: values up to the largest double give a figure with every line in its panel") {
  TempDir dir;
  const StatsTable table = readStatsCsv(writeText(
      dir,
      kHeader +
          "\n0,1e308,-1e308,0,0,0\n1,-1.7976931348623157e308,1.7976931348623157e308,0,1e308,1e308\n2,1,2,3,0,0\n"));
  for (const char* name : {"huge.svg", "huge.png"}) {
    CAPTURE(name);
    REQUIRE_NOTHROW(writeFigure(statsFigure(table), dir / name));
  }
  // The SVG: three panels (energy; constraint error, one positive value: a dot on a log axis;
  // penetration, linear), each line with all its points, at the panel's edges where the data are
  // the axis' ends. Lines are stroked in the series' colour, the legend's swatches are 26 px wide.
  const auto svg = parseXml(particles::test::readBytes(dir / "huge.svg"));
  const auto frames = plotFrames(svg);
  REQUIRE(frames.size() == 3);
  const auto line = [&](std::size_t colour, const PathBounds& frame) {
    std::vector<PathPoint> points;
    for (const XmlElement& e : svg) {
      const PathBounds b = pathBounds(e);
      if (e.name != "path" || !sameColour(styleProperty(e, "stroke"), seriesColour(colour)) || b.x1 - b.x0 == 26 ||
          b.y0 < frame.y0 - 1 || b.y1 > frame.y1 + 1) {
        continue;
      }
      CHECK_MESSAGE(points.empty(), "two lines of colour " << colour);
      points = pathPoints(e);
    }
    return points;
  };
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1.5; };
  const PathBounds& energy = frames[0];
  const auto kinetic = line(0, energy), potential = line(1, energy), total = line(2, energy);
  REQUIRE(kinetic.size() == 3);
  REQUIRE(potential.size() == 3);
  REQUIRE(total.size() >= 2);
  for (const auto* points : {&kinetic, &potential, &total}) {
    CHECK(near(points->front().x, energy.x0));
    CHECK(near(points->back().x, energy.x1));
  }
  CHECK(near(kinetic[1].x, energy.centreX()));
  CHECK(near(kinetic[1].y, energy.y1));    // −1.8e308, the axis' bottom
  CHECK(near(potential[1].y, energy.y0));  // +1.8e308, its top
  CHECK(kinetic[0].y < total[0].y);        // 1e308 above 0 …
  CHECK(potential[0].y > total[0].y);      // … −1e308 below
  CHECK(total.front().y == total.back().y);
  CHECK(near(kinetic[2].y, total.back().y));  // 1 J and 3 J are 0 at this scale
  std::size_t dots = 0;
  for (const XmlElement& e : svg) {
    if (e.name != "path" || !sameColour(styleProperty(e, "fill"), seriesColour(0))) continue;
    ++dots;
    const PathBounds b = pathBounds(e);
    CHECK(near(b.centreX(), frames[1].centreX()));
    CHECK(near(b.centreY(), frames[1].y0));  // 1e308 at the top of its decade
  }
  CHECK(dots == 1);
  const auto penetration = line(0, frames[2]);
  REQUIRE(penetration.size() == 3);
  CHECK(near(penetration[0].y, frames[2].y1));
  CHECK(near(penetration[1].x, frames[2].centreX()));
  CHECK(near(penetration[1].y, frames[2].y0));
  CHECK(near(penetration[2].y, frames[2].y1));

  // The PNG: the same figure in pixels, its lines' colours where the SVG puts them.
  const auto png = particles::test::decodePng(particles::test::readBytes(dir / "huge.png"));
  REQUIRE(png.width == 1200);
  REQUIRE(png.height == 800);
  const auto colourAt = [&](const PathPoint& a, const PathPoint& b, std::size_t colour) {
    const int x = int(std::lround((a.x + b.x) / 2)), y = int(std::lround((a.y + b.y) / 2));
    bool found = false;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) found = found || png.is(x + dx, y + dy, seriesColour(colour));
    }
    return found;
  };
  CHECK(colourAt(kinetic[0], kinetic[1], 0));
  CHECK(colourAt(potential[1], potential[2], 1));
  CHECK(colourAt(total.front(), total.back(), 2));
  CHECK(colourAt(penetration[0], penetration[1], 0));
}

// Rows 5e-324 and -5e-324 were once refused as an output failure ("cannot draw figure:
// invalid matrix", exit 3). Valid numbers at any scale are drawn, in every format, and the line is there.
TEST_CASE("plot stats figure: subnormal, huge, single-valued and tiny log values are drawn in every format") {
  TempDir dir;
  const std::vector<std::string> tables = {
      "0,5e-324,0,0,0,0\n0.1,-5e-324,0,0,0,0\n",                                         // once refused, exit 3
      "0,5e-324,5e-324,5e-324,5e-324,5e-324\n0.1,5e-324,5e-324,5e-324,5e-324,5e-324\n",  // one subnormal value
      "0,1e308,1,1,0,0\n0.1,-1e308,1,1,0,0\n",                                           // huge, in one column
      "0,1e-310,2e-310,3e-310,5e-324,1e-323\n0.1,1e-310,2e-310,3e-310,1e-320,5e-324\n",  // log panels, tiny positives
      "0,5e-324,0,0,1e-300,0\n1e-300,5e-324,0,0,1e300,0\n",                              // a log panel over 600 decades
      "5e-324,1,1,1,0,0\n1e-323,2,1,1,0,0\n",                                            // a subnormal time axis
      "0,7,7,7,7,7\n",                                                                   // one row
  };
  for (const std::string& rows : tables) {
    CAPTURE(rows);
    const Figure figure = statsFigure(readStatsCsv(writeText(dir, kHeader + "\n" + rows)));
    for (const ImageFormat format : {ImageFormat::Svg, ImageFormat::Png, ImageFormat::Pdf}) {
      CAPTURE(int(format));
      std::vector<std::uint8_t> bytes;
      CHECK_NOTHROW(bytes = renderFigure(figure, format));
      CHECK(bytes.size() > 1000);
    }
    // Each panel's first line (a dot for one row) lies inside its panel's frame, one per panel;
    // the legend's swatch, in the same colour, is the one 26 px wide.
    const auto svg = parseXml(renderFigure(figure, ImageFormat::Svg));
    const auto frames = plotFrames(svg);
    REQUIRE(!frames.empty());
    std::size_t drawn = 0;
    for (const XmlElement& e : svg) {
      if (e.name != "path") continue;
      const PathBounds b = pathBounds(e);
      const bool line = sameColour(styleProperty(e, "stroke"), seriesColour(0)) && b.x1 - b.x0 != 26;
      const bool dot = sameColour(styleProperty(e, "fill"), seriesColour(0));
      if (!line && !dot) continue;
      CAPTURE(e.attributes.at("d").substr(0, 200));
      CHECK(std::any_of(frames.begin(), frames.end(), [&](const PathBounds& f) {
        return b.y0 >= f.y0 - 4 && b.y1 <= f.y1 + 4 && b.x0 >= f.x0 - 4 && b.x1 <= f.x1 + 4;
      }));
      ++drawn;
    }
    CHECK(drawn == frames.size());
  }
}

// The stability figure's dot chart (and a reference given on the command line) at the ends of the
// doubles: its fitted log axis once reached 10^-324 (0) or past 10^308 (infinity).
TEST_CASE("plot stability figure: limits and references at the ends of the doubles are drawn") {
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  const std::vector<std::pair<double, double>> limits = {{tiny, tiny}, {tiny, 1e-320}, {1e308, big}, {tiny, big}};
  for (const auto& [a, b] : limits) {
    CAPTURE(a);
    CAPTURE(b);
    std::vector<StabilityRow> rows = {{"euler", 1, a, a, 1, 1, false, false}, {"rk4", 4, b, b, 1, 1, false, true}};
    StabilityFigureNotes notes;
    notes.references["euler"] = Reference{a, b};
    const Figure figure = stabilityFigure(rows, notes);
    for (const ImageFormat format : {ImageFormat::Svg, ImageFormat::Png, ImageFormat::Pdf}) {
      CAPTURE(int(format));
      CHECK_NOTHROW(renderFigure(figure, format));
    }
    // Every mark is drawn: for each of the two groups (largest stable dt, without shaking) a dot in
    // the legend and one per integrator, each its own filled path; the reference's mark (a diamond
    // for a point, a range with end caps for an interval) in the legend and in euler's row.
    const auto svg = parseXml(renderFigure(figure, ImageFormat::Svg));
    for (std::size_t group = 0; group < 2; ++group) {
      CAPTURE(group);
      CHECK(std::count_if(svg.begin(), svg.end(), [&](const XmlElement& e) {
              return e.name == "path" && sameColour(styleProperty(e, "fill"), seriesColour(group));
            }) == 1 + long(rows.size()));
    }
    // A diamond is 14 px across both ways, a range's end caps 12 px high (plot/dot_chart.cpp).
    const bool point = a == b;
    CHECK(std::count_if(svg.begin(), svg.end(), [&](const XmlElement& e) {
            if (e.name != "path" || !sameColour(styleProperty(e, "stroke"), kInk)) return false;
            const auto shape = pathShape(e);
            const PathBounds box = pathBounds(e);
            const double width = box.x1 - box.x0, height = box.y1 - box.y0;
            return point ? shape.subpaths == 1 && shape.vertices == 4 && std::abs(width - 14) < 0.5 &&
                               std::abs(height - 14) < 0.5
                         : shape.subpaths == 3 && shape.vertices == 6 && std::abs(height - 12) < 0.5;
          }) == 2);
  }
}

TEST_CASE("plot stats CSV: a huge bad field is quoted by its start and its size, not echoed whole") {
  TempDir dir;
  const std::string field(10'000'000, 'x');
  try {
    readStatsCsv(writeText(dir, kHeader + "\n0," + field + ",0,0,0,0\n"));
    FAIL("expected a CsvError");
  } catch (const CsvError& e) {
    const std::string what = e.what();
    CAPTURE(what.substr(0, 200));
    CHECK(what.size() < 300);
    CHECK(what.find("(10000000 bytes)") != std::string::npos);
    CHECK(what.find(":2:3: column 'kinetic': expected a number, found 'xxxx") != std::string::npos);
  }
}
