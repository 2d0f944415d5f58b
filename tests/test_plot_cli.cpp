// `particles plot` on numbers at the ends of the doubles and on long files, through the real
// program: valid numbers give a figure (exit 0), text that is not a finite number is bad input
// naming the file and line (exit 2), never an output failure (exit 3); a long file is drawn within
// a generous CPU guard (not a speed measurement: that is bench/bench_plot.cpp).

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <string>

#include "cli_support.hpp"

using namespace particles::test;

namespace {

const std::string kHeaderLine = "t,kinetic,potential,total,constraint_error,penetration\n";

}  // namespace

TEST_CASE("plot cli: subnormal, huge and single-valued columns give a figure, exit 0, in every format") {
  Scratch s;
  s.write("denormal.csv", kHeaderLine + "0,5e-324,0,0,0,0\n0.1,-5e-324,0,0,0,0\n");  // once exit 3
  s.write("huge.csv", kHeaderLine + "0,1e308,1,1,0,0\n0.1,-1e308,1,1,0,0\n");
  s.write("single.csv", kHeaderLine + "0,3,3,3,3,3\n0.1,3,3,3,3,3\n");
  s.write("tiny_log.csv", kHeaderLine + "0,1,1,1,5e-324,1e-323\n0.1,1,1,1,1e-320,5e-324\n");
  for (const char* input : {"denormal", "huge", "single", "tiny_log"}) {
    for (const char* ext : {"svg", "png", "pdf"}) {
      const std::string out = fmt::format("{}.{}", input, ext);
      CAPTURE(out);
      const Result r = s.run(fmt::format("plot {}.csv -o {} --quiet", input, out));
      CHECK(r.code == 0);
      CHECK(r.err == "");
      CHECK(fs::file_size(s.dir / out) > 1000);
    }
  }
}

TEST_CASE("plot cli: infinities and numbers past the doubles are bad input naming the file and line") {
  Scratch s;
  s.write("inf.csv", kHeaderLine + "0,1,1,1,0,0\n0.1,inf,0,0,0,0\n");
  s.write("minus_inf.csv", kHeaderLine + "0,1,1,1,0,-Infinity\n");
  s.write("overflow.csv", kHeaderLine + "0,1,1e309,1,0,0\n");
  s.write("nan.csv", kHeaderLine + "0,1,1,NaN,0,0\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"inf", "error: inf.csv:3:5: column 'kinetic': 'inf' is not a finite number\n"},
      {"minus_inf", "error: minus_inf.csv:2:11: column 'penetration': '-Infinity' is not a finite number\n"},
      {"overflow", "error: overflow.csv:2:5: column 'potential': '1e309' is not a finite number\n"},
      {"nan", "error: nan.csv:2:7: column 'total': 'NaN' is not a finite number\n"}};
  for (const auto& [input, message] : cases) {
    CAPTURE(input);
    const Result r = s.run("plot " + input + ".csv -o out.png");
    CHECK(r.code == 2);
    CHECK(r.err == message);
    CHECK_FALSE(fs::exists(s.dir / "out.png"));
  }
}

// 300,000 rows alternating ±1 took more than 20 s to draw into a PNG (100,000: 8.8 s); the reduced
// line takes about 0.4 s of CPU for the whole command. The guard is 5× that, and is not checked
// under the sanitizers, which slow everything: there 30,000 rows, still about 7 to each
// quarter-pixel column the line is reduced by (plot/column_reduction.hpp).
TEST_CASE("plot cli: 300,000 rows alternating ±1 become a PNG, SVG and PDF within 2 s of CPU each") {
  Scratch s;
  std::string csv = kHeaderLine;
  const int rows = kSanitized ? 30'000 : 300'000;
  for (int i = 0; i < rows; ++i) csv += fmt::format("{},{},0,{},0,0\n", 0.001 * i, i % 2 ? 1 : -1, i % 2 ? 1 : -1);
  s.write("long.csv", csv);
  for (const char* out : {"long.png", "long.svg", "long.pdf"}) {
    CAPTURE(out);
    Scratch::Usage usage;
    const Result r = s.runBounded(fmt::format("plot long.csv -o {} --quiet", out), usage);
    CHECK(r.code == 0);
    CHECK(r.err == "");
    CAPTURE(usage.cpuSeconds);
    if (!kSanitized) CHECK(usage.cpuSeconds <= 2.0);
    // The reduced line: at most 4 points per quarter of the ~1,100 px plot, not 300,000.
    CHECK(fs::file_size(s.dir / out) < 2'000'000);
  }
}
