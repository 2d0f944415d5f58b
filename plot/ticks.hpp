#pragma once
// Axis ticks and number labels. Linear axes use "nice" steps of 1, 2 or 5 × 10^k (Heckbert,
// "Nice numbers for graph labels", Graphics Gems, 1990); log axes put major ticks on decades
// (every k-th decade when there are too many to label) and minor ticks at 2…9 × 10^k.

#include <string>
#include <vector>

namespace particles::plot {

// A label that may end in a superscript: {"10", "−3"} is 10⁻³, {"2.5×10", "−7"} is 2.5×10⁻⁷.
// Minus signs are U+2212, as typeset, not the hyphen.
struct Label {
  std::string text;
  std::string superscript;
  bool operator==(const Label&) const = default;
};

struct Tick {
  double value;
  Label label;
};

struct AxisTicks {
  double lo = 0, hi = 1;      // the axis range, in data units
  std::vector<Tick> major;    // labelled
  std::vector<double> minor;  // unlabelled (log axes only)
};

// Where v lies on the axis: 0 at lo, 1 at hi (linear). Also for ranges wider than the largest
// double, whose span hi − lo overflows.
double axisFraction(double v, const AxisTicks& axis);

// Smallest 1, 2 or 5 × 10^k that is ≥ rawStep (> 0).
double niceStep(double rawStep);

// The narrowest range a linear axis shows: a tenth of a step is then still a normal double
// (≥ 2.2e-308), and so are the ticks and the powers of ten that label them.
inline constexpr double kMinLinearSpan = 1e-300;

// Ticks for data in [dataLo, dataHi] on a linear axis, about `targetCount` of them. With
// widenToTicks the range grows outward to whole steps (for y axes); otherwise it stays the data
// range (for a time axis that should start and end with the data). A constant value c gets the
// range c ± 10 % (0 gets [0, 1]); a range narrower than kMinLinearSpan (subnormal data) is widened
// to it around its middle; a non-finite range falls back to [0, 1].
AxisTicks linearTicks(double dataLo, double dataHi, int targetCount, bool widenToTicks);

// Ticks for positive data in [dataLo, dataHi] on a log axis: the range is widened to whole decades
// (at least one), with at most `maxMajor` labelled decades. Non-positive or non-finite input falls
// back to [1, 10].
AxisTicks logTicks(double dataLo, double dataHi, int maxMajor);

// Ticks for a log axis over exactly [lo, hi] (0 < lo < hi), not widened: the densest of
// 10^k, {1, 2, 5} × 10^k and {1 … 9} × 10^k that gives 2 … maxMajor labelled ticks inside the
// range (labelled as plain numbers, e.g. 0.002), the other m × 10^k as minor ticks; a range too
// narrow for two such ticks gets linear "nice" ones. For an axis fitted to the data.
AxisTicks logTicksWithin(double lo, double hi, int maxMajor);

// A value with `significantDigits` significant digits, trailing zeros dropped: plain for
// 10⁻⁴ ≤ |v| < 10⁵ ("0.00052", "340"), otherwise in scientific form ({"3.2×10", "−5"}).
Label formatValue(double v, int significantDigits);

}  // namespace particles::plot
