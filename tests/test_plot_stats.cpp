// The stats CSV reader (strict, errors with file, line and column) and the two ready-made figures.

#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include "plot/errors.hpp"
#include "plot/stability_figure.hpp"
#include "plot/figure.hpp"
#include "plot/stats_figure.hpp"
#include "plot_support.hpp"

using namespace particles::plot;
using particles::test::TempDir;

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

TEST_CASE("plot stats figure: energy above, errors below on a log axis only when they span decades") {
  StatsTable table;
  for (int i = 0; i < 10; ++i) {
    table.t.push_back(0.1 * i);
    table.kinetic.push_back(i);
    table.potential.push_back(10 - i);
    table.total.push_back(10);
    table.constraintError.push_back(1e-9 * std::pow(10.0, i));  // nine decades
    table.penetration.push_back(0);
  }
  Figure f = statsFigure(table);
  const auto& chart = std::get<LineChart>(f.chart);
  CHECK(chart.xLabel == "t [s]");
  REQUIRE(chart.panels.size() == 2);
  CHECK(chart.panels[0].series.size() == 3);
  CHECK(chart.panels[0].series[2].name == "total");
  CHECK(chart.panels[0].yScale == AxisScale::Linear);
  CHECK(chart.panels[1].yScale == AxisScale::Log);
  CHECK(chart.panels[1].series[1].y == table.penetration);

  for (double& e : table.constraintError) e = 1e-3 * (1 + e);  // within a decade
  CHECK(std::get<LineChart>(statsFigure(table).chart).panels[1].yScale == AxisScale::Linear);
  for (double& e : table.constraintError) e = 0;  // nothing positive
  CHECK(std::get<LineChart>(statsFigure(table).chart).panels[1].yScale == AxisScale::Linear);

  table.penetration.pop_back();
  CHECK_THROWS_AS(statsFigure(table), FigureError);
}

TEST_CASE("plot stability figure: integrators as categories, the two dt columns as groups") {
  const std::vector<StabilityRow> rows = {
      {"euler", 1, 0.0021, 0.00052, 1923, 1}, {"midpoint", 2, 0.031, 0.012, 166, 11.6}, {"rk4", 4, 0.29, 0.11, 36, 53}};
  const Figure f = stabilityFigure(rows);
  const auto& chart = std::get<BarChart>(f.chart);
  CHECK(chart.categories == std::vector<std::string>{"euler", "midpoint", "rk4"});
  REQUIRE(chart.groups.size() == 2);
  CHECK(chart.groups[0].name == "largest stable dt");
  CHECK(chart.groups[0].values == std::vector<double>{0.0021, 0.031, 0.29});
  CHECK(chart.groups[1].name == "largest dt without shaking");
  CHECK(chart.groups[1].values == std::vector<double>{0.00052, 0.012, 0.11});
  CHECK_FALSE(renderFigure(f, ImageFormat::Png).empty());
}

// Values near ±1.8e308 once overflowed the axis span: the tick loop never ended (and cast ±inf to
// int); later cairo refused the non-finite coordinates. Any finite data must give a figure.
TEST_CASE("plot stats figure: values up to the largest double give a figure, not a hang or an error") {
  TempDir dir;
  const StatsTable table = readStatsCsv(writeText(
      dir, kHeader + "\n0,1e308,-1e308,0,0,0\n1,-1.7976931348623157e308,1.7976931348623157e308,0,1e308,1e308\n2,1,2,3,0,0\n"));
  for (const char* name : {"huge.svg", "huge.png"}) {
    CAPTURE(name);
    CHECK_NOTHROW(writeFigure(statsFigure(table), dir / name));
    CHECK(std::filesystem::file_size(dir / name) > 1000);
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
