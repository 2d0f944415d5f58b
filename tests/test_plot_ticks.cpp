// Tick selection and number labels for the figures' axes.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "plot/ticks.hpp"

using namespace particles::plot;

namespace {

// The major tick labels as "a | b | c", superscripts after "^": a failing check prints them.
std::string texts(const AxisTicks& axis) {
  std::string out;
  for (const Tick& t : axis.major) {
    if (!out.empty()) out += " | ";
    out += t.label.text + (t.label.superscript.empty() ? "" : "^" + t.label.superscript);
  }
  return out;
}

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : " | ") + p;
  return out;
}

const std::string kMinus = "\u2212";

}  // namespace

TEST_CASE("plot ticks: nice steps are 1, 2 or 5 times a power of ten") {
  CHECK(niceStep(0.13) == doctest::Approx(0.2));
  CHECK(niceStep(1.0) == doctest::Approx(1.0));
  CHECK(niceStep(2.1) == doctest::Approx(5.0));
  CHECK(niceStep(7.0) == doctest::Approx(10.0));
  CHECK(niceStep(3e-7) == doctest::Approx(5e-7));
  CHECK(niceStep(1000.0) == doctest::Approx(1000.0));
}

TEST_CASE("plot ticks: a linear y axis widens to whole steps") {
  const AxisTicks axis = linearTicks(0.3, 9.8, 6, true);
  CHECK(axis.lo == 0);
  CHECK(axis.hi == doctest::Approx(10));
  CHECK(texts(axis) == joined({"0", "2", "4", "6", "8", "10"}));
  CHECK(axis.minor.empty());
}

TEST_CASE("plot ticks: a linear x axis keeps the data range and labels the steps inside it") {
  const AxisTicks axis = linearTicks(0.05, 9.7, 6, false);
  CHECK(axis.lo == 0.05);
  CHECK(axis.hi == 9.7);
  CHECK(texts(axis) == joined({"2", "4", "6", "8"}));
}

TEST_CASE("plot ticks: labels share their decimals and use a real minus sign") {
  CHECK(texts(linearTicks(-0.3, 0.3, 7, true)) ==
        joined({kMinus + "0.3", kMinus + "0.2", kMinus + "0.1", "0.0", "0.1", "0.2", "0.3"}));
  CHECK(texts(linearTicks(0, 2.5, 6, true)) == joined({"0.0", "0.5", "1.0", "1.5", "2.0", "2.5"}));
}

TEST_CASE("plot ticks: tiny and huge linear values are labelled in scientific form") {
  CHECK(texts(linearTicks(0, 3e-7, 4, true)) ==
        joined({"0", "10^" + kMinus + "7", "2\u00d710^" + kMinus + "7", "3\u00d710^" + kMinus + "7"}));
  CHECK(texts(linearTicks(0, 4e6, 3, true)) == joined({"0", "2\u00d710^6", "4\u00d710^6"}));
}

TEST_CASE("plot ticks: constant, zero and non-finite ranges fall back to something drawable") {
  const AxisTicks constant = linearTicks(5, 5, 5, true);
  CHECK(constant.lo <= 4.5);
  CHECK(constant.hi >= 5.5);
  CHECK(constant.major.size() >= 2);
  const AxisTicks zero = linearTicks(0, 0, 5, true);
  CHECK(zero.lo == 0);
  CHECK(zero.hi == 1);
  const AxisTicks nan = linearTicks(NAN, 1, 5, true);
  CHECK(nan.lo == 0);
  CHECK(nan.hi == 1);
}

// Data near the ends of the double range once overflowed the span to infinity, cast it to int
// (undefined) and looped for ever on a zero step; every finite range must give a few finite ticks.
// Stats rows 5e-324 and -5e-324 once gave a step of 0, an axis from 0 to 0, non-finite
// pixels and "cannot draw figure: invalid matrix" (exit 3, an output failure, for valid input).
TEST_CASE("plot ticks: any finite range, down to subnormals and up to the largest double, gives distinct ticks") {
  const double big = std::numeric_limits<double>::max(), tiny = std::numeric_limits<double>::denorm_min();
  const std::vector<std::pair<double, double>> ranges = {
      {-1e308, 1e308},   {-big, big},       {0, big},      {1.7e308, big},   {-big, -1e307},
      {tiny, 20 * tiny}, {-1e-300, 1e-300}, {-tiny, tiny}, {tiny, 2 * tiny}, {tiny, tiny},
      {-tiny, -tiny},    {1e-310, 1e-310},  {0, 1e-305},   {-1e-301, 2e-301}};
  for (const auto& [lo, hi] : ranges) {
    for (const bool widen : {true, false}) {
      CAPTURE(lo);
      CAPTURE(hi);
      CAPTURE(widen);
      const AxisTicks axis = linearTicks(lo, hi, 6, widen);
      CAPTURE(texts(axis));
      CHECK(std::isfinite(axis.lo));
      CHECK(std::isfinite(axis.hi));
      CHECK(axis.lo <= lo);
      CHECK(axis.hi >= hi);
      CHECK(axis.hi - axis.lo >= kMinLinearSpan);
      REQUIRE(axis.major.size() >= 2);
      CHECK(axis.major.size() <= 12);
      for (std::size_t i = 0; i < axis.major.size(); ++i) {
        const Tick& t = axis.major[i];
        CHECK(std::isfinite(t.value));
        CHECK(t.value >= axis.lo);
        CHECK(t.value <= axis.hi);
        CHECK((t.value == 0 || std::fabs(t.value) >= std::numeric_limits<double>::min()));  // 0 or normal
        if (i > 0) CHECK(t.value > axis.major[i - 1].value);
        if (i > 0) CHECK(t.label != axis.major[i - 1].label);
      }
    }
    if (lo > 0) {
      const AxisTicks axis = logTicks(lo, hi, 8);
      CHECK(axis.lo > 0);
      CHECK(std::isfinite(axis.hi));
      CHECK(axis.major.size() >= 2);
    }
  }
  // A range at least that wide is kept (an x axis shows the data's range exactly).
  const AxisTicks narrow = linearTicks(1e-290, 3e-290, 5, false);
  CHECK(narrow.lo == 1e-290);
  CHECK(narrow.hi == 3e-290);
}

// The decades were aligned to every k-th one past those a double holds: an axis from 10^-356 (0) or
// to 10^356 (infinity).
TEST_CASE("plot ticks: a log axis over hundreds of decades stays within the doubles and reaches the data") {
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  const std::vector<std::pair<double, double>> ranges = {{tiny, 1e300},    {1e-300, big},  {tiny, big},
                                                         {tiny, 2 * tiny}, {tiny, 1e-320}, {1e307, big}};
  for (const auto& [lo, hi] : ranges) {
    for (const int maxMajor : {2, 5, 8, 20}) {
      CAPTURE(lo);
      CAPTURE(hi);
      CAPTURE(maxMajor);
      const AxisTicks axis = logTicks(lo, hi, maxMajor);
      CAPTURE(texts(axis));
      CHECK(axis.lo > 0);
      CHECK(axis.lo <= lo);
      CHECK(axis.hi >= hi);
      CHECK(std::isfinite(axis.hi));
      CHECK(std::isfinite(std::log10(axis.hi) - std::log10(axis.lo)));
      CHECK(axis.major.size() >= 1);
      CHECK(axis.major.size() <= std::size_t(std::max(2, maxMajor)) + 1);
      for (const Tick& t : axis.major) CHECK((t.value > 0 && std::isfinite(t.value)));
      for (double v : axis.minor) CHECK((v > 0 && std::isfinite(v)));
    }
    const AxisTicks fitted = logTicksWithin(lo, hi, 10);
    for (const Tick& t : fitted.major) CHECK((t.value > 0 && std::isfinite(t.value)));
  }
}

// std::stod of the rounded digits threw out_of_range for both (an "internal error").
TEST_CASE("plot ticks: the largest double and the smallest subnormal are labelled") {
  CHECK(formatValue(std::numeric_limits<double>::max(), 3) == Label{"1.8\u00d710", "308"});
  CHECK(formatValue(-std::numeric_limits<double>::max(), 1) == Label{kMinus + "2\u00d710", "308"});
  CHECK(formatValue(std::numeric_limits<double>::denorm_min(), 3) == Label{"4.94\u00d710", kMinus + "324"});
}

TEST_CASE("plot ticks: a log axis spans whole decades with minor ticks at 2..9") {
  const AxisTicks axis = logTicks(3e-5, 2e-2, 10);
  CHECK(axis.lo == doctest::Approx(1e-5));
  CHECK(axis.hi == doctest::Approx(1e-1));
  CHECK(texts(axis) == joined({"10^" + kMinus + "5", "10^" + kMinus + "4", "10^" + kMinus + "3", "10^" + kMinus + "2",
                               "10^" + kMinus + "1"}));
  CHECK(axis.minor.size() == 4 * 8);
  CHECK(axis.minor.front() == doctest::Approx(2e-5));
}

TEST_CASE("plot ticks: a log axis over many decades labels every k-th one") {
  const AxisTicks axis = logTicks(1e-12, 1e3, 6);  // 15 decades, at most 6 labels: every 3rd
  CHECK(axis.lo == doctest::Approx(1e-12));
  CHECK(axis.hi == doctest::Approx(1e3));
  CHECK(axis.major.size() == 6);
  CHECK(axis.major[1].label.superscript == kMinus + "9");
  CHECK(axis.minor.size() == 15 - 5);  // the unlabelled decades
}

TEST_CASE("plot ticks: a log axis within one decade, or without positive data, still shows a decade") {
  const AxisTicks within = logTicks(2e-3, 3e-3, 5);
  CHECK(within.lo == doctest::Approx(1e-3));
  CHECK(within.hi == doctest::Approx(1e-2));
  const AxisTicks exact = logTicks(1e-3, 1e-3, 5);
  CHECK(exact.lo == doctest::Approx(1e-3));
  CHECK(exact.hi == doctest::Approx(1e-2));
  const AxisTicks none = logTicks(-1, 0, 5);
  CHECK(none.lo == 1);
  CHECK(none.hi == 10);
}

TEST_CASE("plot ticks: a log axis fitted to its range keeps the range and picks 1-2-5 or 1…9 ticks inside it") {
  // 0.0004 … 0.4: three decades; 1, 2, 5 × 10^k gives 9 labels, within 10.
  AxisTicks axis = logTicksWithin(4e-4, 0.4, 10);
  CHECK(axis.lo == 4e-4);
  CHECK(axis.hi == 0.4);
  CHECK(texts(axis) == joined({"0.0005", "0.001", "0.002", "0.005", "0.01", "0.02", "0.05", "0.1", "0.2"}));
  CHECK(axis.minor.size() == 6 + 9 + 9 + 4 - 9);  // every m × 10^k in range (0.0004 … 0.4) but the labelled
  for (double v : axis.minor) CHECK((v >= axis.lo && v <= axis.hi));
  // Fewer labels allowed: decades only.
  CHECK(texts(logTicksWithin(4e-4, 0.4, 4)) == joined({"0.001", "0.01", "0.1"}));
  // Within a factor of three: every m × 10^k.
  CHECK(texts(logTicksWithin(0.2, 0.55, 10)) == joined({"0.2", "0.3", "0.4", "0.5"}));
  // Too narrow for two of them: linear steps inside the range.
  axis = logTicksWithin(0.21, 0.29, 5);
  CHECK(axis.major.size() >= 2);
  for (const Tick& t : axis.major) CHECK((t.value >= 0.21 && t.value <= 0.29));
  // Many decades and few labels: whole decades, still inside the range.
  axis = logTicksWithin(3e-7, 2e4, 4);
  CHECK(axis.lo == 3e-7);
  CHECK(axis.major.size() <= 4);
  for (const Tick& t : axis.major) CHECK((t.value >= 3e-7 && t.value <= 2e4));
}

TEST_CASE("plot ticks: values are labelled with their significant digits") {
  CHECK(formatValue(0.0125, 3) == Label{"0.0125", ""});
  CHECK(formatValue(0.00052, 2) == Label{"0.00052", ""});
  CHECK(formatValue(0.29, 3) == Label{"0.29", ""});
  CHECK(formatValue(9.996, 3) == Label{"10", ""});
  CHECK(formatValue(3.2e-5, 2) == Label{"3.2\u00d710", kMinus + "5"});
  CHECK(formatValue(123456, 3) == Label{"1.23\u00d710", "5"});
  CHECK(formatValue(-0.5, 3) == Label{kMinus + "0.5", ""});
  CHECK(formatValue(0, 3) == Label{"0", ""});
}
