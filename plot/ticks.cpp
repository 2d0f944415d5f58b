#include "plot/ticks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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
    const double c = 0.5 * (lo + hi);
    if (c == 0) {
      lo = 0;
      hi = 1;
    } else {
      lo = c - 0.1 * std::fabs(c);
      hi = c + 0.1 * std::fabs(c);
    }
  }
  const double step = niceStep((hi - lo) / std::max(1, targetCount - 1));
  // Ticks are i × step for integer i, so zero is exactly 0 and labels don't show 1e-17.
  const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
  AxisTicks axis;
  if (widenToTicks) {
    axis.lo = std::floor(lo / step + 1e-9) * step;
    axis.hi = std::ceil(hi / step - 1e-9) * step;
  } else {
    axis.lo = lo;
    axis.hi = hi;
  }
  const double lowest = widenToTicks ? std::floor(lo / step + 1e-9) : first;
  const double highest = widenToTicks ? std::ceil(hi / step - 1e-9) : last;
  std::vector<double> values;
  for (double i = lowest; i <= highest; i += 1) values.push_back(i * step + 0.0);  // + 0.0: no "−0.0"
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
  // Label every k-th decade, k chosen so at most maxMajor labels fit; align to multiples of k.
  const int k = std::max(1, (eHi - eLo + std::max(1, maxMajor - 1) - 1) / std::max(1, maxMajor - 1));
  const auto floorDiv = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  eLo = floorDiv(eLo, k) * k;
  eHi = -floorDiv(-eHi, k) * k;
  AxisTicks axis;
  axis.lo = std::pow(10.0, eLo);
  axis.hi = std::pow(10.0, eHi);
  for (int e = eLo; e <= eHi; ++e) {
    const double decade = std::pow(10.0, e);
    if ((e - eLo) % k == 0) {
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

Label formatValue(double v, int significantDigits) {
  if (v == 0) return {"0", ""};
  if (!std::isfinite(v)) return {std::isnan(v) ? "NaN" : (v > 0 ? "\u221e" : "\u2212\u221e"), ""};
  const int digits = std::max(1, significantDigits);
  // Round first: 9.996 with 3 digits is 10.0, whose exponent is one more than 9.996's.
  const double rounded = std::stod(fmt::format("{:.{}e}", v, digits - 1));
  const int e = decimalExponent(rounded);
  if (e >= -4 && e < 5) {
    return {typesetMinus(trimTrailingZeros(fmt::format("{:.{}f}", rounded, std::max(0, digits - 1 - e)))), ""};
  }
  return scientific(rounded / std::pow(10.0, e), e, digits - 1);
}

}  // namespace particles::plot
