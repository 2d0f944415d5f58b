#include "plot/ticks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace particles::plot {

namespace {

// U+2212 MINUS SIGN in place of the hyphen fmt writes.
std::string typesetMinus(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '-') {
      out += "\u2212";
    } else {
      out += c;
    }
  }
  return out;
}

std::string trimTrailingZeros(std::string s) {
  if (s.find('.') == std::string::npos) return s;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

// Exponent of the leading digit: floor(log10(|v|)) for v ≠ 0, guarded against log10 rounding
// just below an exact power of ten.
int decimalExponent(double v) {
  const double a = std::fabs(v);
  if (!(a > 0.0) || !std::isfinite(a)) return 0;  // no leading digit; and casting ±inf to int is undefined
  int e = static_cast<int>(std::floor(std::log10(a)));
  if (std::pow(10.0, e + 1) <= a) ++e;
  if (std::pow(10.0, e) > a) --e;
  return e;
}

Label scientific(double mantissa, int exponent, int decimals) {
  std::string m = trimTrailingZeros(fmt::format("{:.{}f}", mantissa, decimals));
  return {typesetMinus(m) + "\u00d710", typesetMinus(std::to_string(exponent))};
}

// One format for all labels of a linear axis, so they line up and show the same precision.
std::vector<Tick> labelLinear(const std::vector<double>& values, double step, double maxAbs) {
  const int stepExponent = decimalExponent(step);
  std::vector<Tick> ticks;
  const bool useScientific = stepExponent <= -4 || maxAbs >= 1e5;
  const int maxExponent = maxAbs > 0 ? decimalExponent(maxAbs) : 0;
  for (double v : values) {
    Label label;
    if (!useScientific) {
      label.text = typesetMinus(fmt::format("{:.{}f}", v, std::max(0, -stepExponent)));
    } else if (v == 0) {
      label.text = "0";
    } else {
      const double mantissa = v / std::pow(10.0, maxExponent);
      label = scientific(mantissa, maxExponent, std::max(0, maxExponent - stepExponent));
      if (label.text == "1\u00d710") label.text = "10";
      if (label.text == "\u22121\u00d710") label.text = "\u221210";
    }
    ticks.push_back({v, label});
  }
  return ticks;
}

}  // namespace

double axisFraction(double v, const AxisTicks& axis) {
  const double span = axis.hi - axis.lo;
  if (std::isfinite(span)) return (v - axis.lo) / span;
  return (0.5 * v - 0.5 * axis.lo) / (0.5 * axis.hi - 0.5 * axis.lo);  // halving is exact here
}

double niceStep(double rawStep) {
  const double magnitude = std::pow(10.0, decimalExponent(rawStep));
  const double f = rawStep / magnitude;
  if (f <= 1.0) return magnitude;
  if (f <= 2.0) return 2.0 * magnitude;
  if (f <= 5.0) return 5.0 * magnitude;
  return 10.0 * magnitude;
}

AxisTicks linearTicks(double dataLo, double dataHi, int targetCount, bool widenToTicks) {
  double lo = std::min(dataLo, dataHi), hi = std::max(dataLo, dataHi);
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 0;
    hi = 1;
  }
  // A span below 1e-9 of the magnitude is rounding noise around a constant, not a range to label.
  if (hi - lo <= 1e-9 * std::max(std::fabs(lo), std::fabs(hi))) {
    // Halved first only where lo + hi overflows (near ±1.8e308): halving a subnormal first loses it.
    double c = 0.5 * (lo + hi);
    if (!std::isfinite(c)) c = 0.5 * lo + 0.5 * hi;
    if (c == 0) {
      lo = 0;
      hi = 1;
    } else {
      // Stopping at the largest double: a constant near ±1.8e308 gave a non-finite end and no
      // pixel for its points (tests/test_plot_figure.cpp's marked series count them).
      lo = std::max(c - 0.1 * std::fabs(c), std::numeric_limits<double>::lowest());
      hi = std::min(c + 0.1 * std::fabs(c), std::numeric_limits<double>::max());
    }
  }
  // Nor is a span below kMinLinearSpan: it is widened to that around its middle, so that the step,
  // its power of ten and the ticks are normal doubles (5e-324 and -5e-324 once gave a
  // zero step, an axis from 0 to 0 and non-finite pixels).
  if (hi - lo < kMinLinearSpan) {
    const double c = 0.5 * lo + 0.5 * hi;
    lo = c - 0.5 * kMinLinearSpan;
    hi = c + 0.5 * kMinLinearSpan;
  }
  // Divided before subtracting: the span of data near ±1.8e308 overflows to infinity.
  const double intervals = std::max(1, targetCount - 1);
  double step = niceStep(hi / intervals - lo / intervals);
  if (!std::isfinite(step)) step = niceStep(0.5 * (hi / intervals) - 0.5 * (lo / intervals));
  // Ticks are i × step for integer i, so zero is exactly 0 and labels don't show 1e-17.
  const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
  AxisTicks axis;
  double lowest = first, highest = last;
  axis.lo = lo;
  axis.hi = hi;
  // Widened outward to whole steps, unless that passes the largest double.
  if (widenToTicks && std::isfinite(std::floor(lo / step + 1e-9) * step)) {
    lowest = std::floor(lo / step + 1e-9);
    axis.lo = lowest * step;
  }
  if (widenToTicks && std::isfinite(std::ceil(hi / step - 1e-9) * step)) {
    highest = std::ceil(hi / step - 1e-9);
    axis.hi = highest * step;
  }
  std::vector<double> values;
  // About targetCount ticks by construction; the cap only keeps a bug from looping for ever.
  for (double i = lowest; i <= highest && values.size() < 1000; i += 1) {
    values.push_back(i * step + 0.0);  // + 0.0: no "−0.0"
  }
  axis.major = labelLinear(values, step, std::max(std::fabs(axis.lo), std::fabs(axis.hi)));
  return axis;
}

AxisTicks logTicks(double dataLo, double dataHi, int maxMajor) {
  double lo = std::min(dataLo, dataHi), hi = std::max(dataLo, dataHi);
  if (!(lo > 0) || !std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 1;
    hi = 10;
  }
  int eLo = decimalExponent(lo);
  int eHi = decimalExponent(hi);
  if (std::pow(10.0, eHi) < hi) ++eHi;  // round up unless hi is itself a power of ten
  if (eHi == eLo) ++eHi;
  // Decades a double can hold: 10^308 is the last power of ten below the largest double, 10^-323
  // the last above zero (a subnormal).
  eHi = std::min(eHi, 308);
  eLo = std::max(std::min(eLo, eHi - 1), -323);
  eHi = std::max(eHi, eLo + 1);  // at least one decade: data at 4.9e-324 alone spans none above -323
  // Label every k-th decade, k chosen so at most maxMajor labels fit; align to multiples of k.
  const int k = std::max(1, (eHi - eLo + std::max(1, maxMajor - 1) - 1) / std::max(1, maxMajor - 1));
  // Aligned outward to multiples of k, but not past the decades a double holds (10^-324 is 0 and
  // 10^309 infinite: an axis ending there gave non-finite pixels).
  const auto floorDiv = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  eLo = std::max(floorDiv(eLo, k) * k, -323);
  eHi = std::min(-floorDiv(-eHi, k) * k, 308);
  AxisTicks axis;
  // Past those decades the axis reaches the data: 4.9e-324 (the smallest subnormal) and 1.8e308.
  axis.lo = std::min(std::pow(10.0, eLo), lo);
  axis.hi = std::max(std::pow(10.0, eHi), hi);
  for (int e = eLo; e <= eHi; ++e) {
    const double decade = std::pow(10.0, e);
    if (floorDiv(e, k) * k == e) {
      axis.major.push_back({decade, {"10", typesetMinus(std::to_string(e))}});
    } else {
      axis.minor.push_back(decade);
    }
    if (k == 1 && e < eHi) {
      for (int m = 2; m <= 9; ++m) axis.minor.push_back(m * decade);
    }
  }
  return axis;
}

AxisTicks logTicksWithin(double lo, double hi, int maxMajor) {
  if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi)) return logTicks(lo, hi, maxMajor);
  const int eLo = decimalExponent(lo) - 1, eHi = decimalExponent(hi) + 1;
  // Every m × 10^k inside [lo, hi] (a hair of tolerance so that an end on a tick keeps it).
  std::vector<std::pair<double, int>> candidates;  // value, mantissa
  for (int e = eLo; e <= eHi; ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, e);
      if (std::isfinite(v) && v >= lo * (1 - 1e-12) && v <= hi * (1 + 1e-12)) candidates.push_back({v, m});
    }
  }
  const std::vector<std::vector<int>> mantissaSets = {{1, 2, 3, 4, 5, 6, 7, 8, 9}, {1, 2, 5}, {1}};
  std::vector<int> chosen;
  std::size_t best = 0;
  for (const auto& set : mantissaSets) {  // densest first: the first that fits wins
    const auto count = static_cast<std::size_t>(std::count_if(candidates.begin(), candidates.end(), [&](const auto& c) {
      return std::find(set.begin(), set.end(), c.second) != set.end();
    }));
    if (count >= 2 && count <= static_cast<std::size_t>(std::max(2, maxMajor))) {
      chosen = set;
      best = count;
      break;
    }
  }
  AxisTicks axis;
  axis.lo = lo;
  axis.hi = hi;
  if (best == 0) {
    // Too narrow for two m × 10^k (or too wide for maxMajor decades): linear steps, or decades.
    const AxisTicks linear = linearTicks(lo, hi, std::max(2, maxMajor), false);
    if (hi / lo < 100) {
      for (const Tick& t : linear.major) {
        if (t.value >= lo && t.value <= hi) axis.major.push_back(t);
      }
      return axis;
    }
    AxisTicks decades = logTicks(lo, hi, maxMajor);
    decades.lo = lo;
    decades.hi = hi;
    std::erase_if(decades.major, [&](const Tick& t) { return t.value < lo || t.value > hi; });
    std::erase_if(decades.minor, [&](double v) { return v < lo || v > hi; });
    return decades;
  }
  for (const auto& [v, m] : candidates) {
    if (std::find(chosen.begin(), chosen.end(), m) != chosen.end()) {
      axis.major.push_back({v, formatValue(v, 1)});
    } else {
      axis.minor.push_back(v);
    }
  }
  return axis;
}

Label formatValue(double v, int significantDigits) {
  if (v == 0) return {"0", ""};
  if (!std::isfinite(v)) return {std::isnan(v) ? "NaN" : (v > 0 ? "\u221e" : "\u2212\u221e"), ""};
  const int digits = std::max(1, significantDigits);
  // Round first: 9.996 with 3 digits is 10.0, whose exponent is one more than 9.996's. The mantissa
  // and exponent are read from the digits, not the rounded value: 1.8e308 (the largest double to 2
  // digits) is past the doubles, and std::stod throws for it and for subnormals.
  const std::string rounded = fmt::format("{:.{}e}", v, digits - 1);  // "-1.00e+01"
  const std::size_t mark = rounded.find('e');
  const double mantissa = std::stod(rounded.substr(0, mark));
  const int e = std::stoi(rounded.substr(mark + 1));
  if (e >= -4 && e < 5) {
    return {typesetMinus(trimTrailingZeros(fmt::format("{:.{}f}", std::stod(rounded), std::max(0, digits - 1 - e)))),
            ""};
  }
  return scientific(mantissa, e, digits - 1);
}

}  // namespace particles::plot
