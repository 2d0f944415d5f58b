#include "scenario/style_values.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "input/closest_name.hpp"
#include "input/printable_text.hpp"
#include "style/color.hpp"
#include "style/colormap.hpp"

namespace particles::scenario::detail {

namespace {

// yaml-cpp tags a quoted scalar "!": `scale: "0.1"` is a text, as everywhere in a scenario.
bool isPlainScalar(const Value& v) {
  return v.isScalar() && v.node().Tag() != "!";
}

std::optional<double> parseFinite(std::string_view text) {
  const std::string s(text);
  if (s.empty() || std::isspace(static_cast<unsigned char>(s.front()))) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

// Where a label stops being one line of printable text: a line break or tab (the label is drawn
// on one line), another control character (an instruction to a terminal, no glyph) or a byte
// that is not UTF-8. Empty when there is none.
std::string unprintableWhy(const std::string& text) {
  size_t character = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if ((c & 0xC0u) != 0x80u) ++character;
    if (c == '\n') return fmt::format("a line break at character {}", character);
    if (c == '\t') return fmt::format("a tab at character {}", character);
  }
  // printableText shows every other control character and every byte that is not UTF-8 as an
  // escape: any difference is one of those.
  const std::string shown = input::printableText(text);
  if (shown == text) return "";
  return fmt::format("a control character or a byte that is not UTF-8 (shown escaped: {})", input::quotedValue(text));
}

}  // namespace

void failUnknownName(const Value& at, std::string_view what, const std::string& name,
                     const std::vector<std::string>& known) {
  const std::string suggestion = input::closestName(name, known);
  std::string message = fmt::format("unknown {} {}", what, input::quotedValue(name));
  if (!suggestion.empty()) message += fmt::format("; did you mean {}?", input::quotedValue(suggestion));
  message += fmt::format(" (one of {})", fmt::join(known, ", "));
  at.fail(message);
}

bool isNumber(const Value& v) {
  double x = 0.0;
  return isPlainScalar(v) && YAML::convert<double>::decode(v.node(), x);
}

bool isBoolean(const Value& v) {
  bool b = false;
  return isPlainScalar(v) && YAML::convert<bool>::decode(v.node(), b);
}

style::Colormap readColormap(const Value& v) {
  return named(v, "colormap", style::colormapFromName, style::colormapNames());
}

style::Color readColor(const Value& v) {
  const std::string text = v.string();
  if (const auto color = style::colorFromText(text)) return *color;
  if (text.front() == '#') {
    v.fail(fmt::format("expected #rrggbb or #rrggbbaa (6 or 8 hex digits), got {}", input::quotedValue(text)));
  }
  // 148 CSS names: the closest alone, not the list.
  const std::string suggestion = input::closestName(text, style::colorNames());
  v.fail(fmt::format(
      "unknown colour {}{}; expected a CSS colour name (orange, steelblue, …) or #rrggbb / #rrggbbaa",
      input::quotedValue(text),
      suggestion.empty() ? std::string() : fmt::format("; did you mean {}?", input::quotedValue(suggestion))));
}

style::Length readLength(const Value& v) {
  constexpr const char* kForms = "a length: 3px (pixels), 0.02m or 0.02 (metres)";
  if (!v.isScalar()) v.fail(fmt::format("expected {}, {}", kForms, v.found()));
  std::string_view text = v.node().Scalar();
  bool pixels = false;
  if (text.ends_with("px")) {
    pixels = true;
    text.remove_suffix(2);
  } else if (text.ends_with("m")) {
    text.remove_suffix(1);
  }
  const std::optional<double> value = parseFinite(text);
  if (!value) v.fail(fmt::format("expected {}, {}", kForms, v.found()));
  if (!(*value > 0.0)) v.fail(fmt::format("expected a length > 0, got {}", input::quotedValue(v.node().Scalar())));
  return {*value, pixels};
}

style::Range readRange(const Value& v) {
  style::Range range;
  if (v.isScalar() && v.node().Scalar() == "auto") return range;
  std::optional<Value> lo, hi;
  if (v.isSequence() && v.node().size() == 2) {
    lo = v.item(0);
    hi = v.item(1);
  } else if (v.isMap()) {
    const MapReader m(v, {"min", "max", "scale"});
    lo = m.optional("min");
    hi = m.optional("max");
    if (lo.has_value() != hi.has_value()) {
      (lo ? *lo : *hi).fail("expected both 'min' and 'max', or neither (the range is then automatic)");
    }
    if (auto s = m.optional("scale")) {
      const std::string scale = s->string();
      if (scale != "linear" && scale != "log") failUnknownName(*s, "scale", scale, {"linear", "log"});
      range.logScale = scale == "log";
    }
  } else {
    v.fail(fmt::format("expected auto, [lo, hi] or a map {{min, max, scale}}, {}", v.found()));
  }
  if (!lo) return range;
  range.automatic = false;
  range.lo = lo->number();
  range.hi = hi->number();
  if (!(range.lo < range.hi)) {
    v.fail(fmt::format("expected lo < hi, got lo = {} and hi = {}", formatNumber(range.lo), formatNumber(range.hi)));
  }
  if (range.logScale && !(range.lo > 0.0)) {
    lo->fail(fmt::format("a log scale needs min > 0, got {}", formatNumber(range.lo)));
  }
  return range;
}

std::string readLabel(const Value& v) {
  const std::string text = v.string();
  if (const std::string why = unprintableWhy(text); !why.empty()) {
    v.fail(fmt::format("expected one line of printable text, got {}", why));
  }
  const size_t characters = size_t(
      std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0u) != 0x80u; }));
  if (characters > style::kMaxLabelLength) {
    v.fail(fmt::format("expected at most {} characters (Unicode code points), got {}", style::kMaxLabelLength,
                       characters));
  }
  return text;
}

}  // namespace particles::scenario::detail
