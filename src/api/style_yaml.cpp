#include "api/style_yaml.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <particles/errors.hpp>

namespace particles::api {

namespace {

// A map's keys and their values, already written as YAML, in the order YAML's section lists them.
using Entries = std::vector<std::pair<std::string_view, std::string>>;

std::string flowMap(const Entries& entries) {
  std::string out = "{";
  for (const auto& [key, value] : entries) {
    if (out.size() > 1) out += ", ";
    out += fmt::format("{}: {}", key, value);
  }
  return out + "}";
}

// JSON's double-quoted form, which YAML reads the same: a colour's `#`, a word like `yes` or `~`, and
// a label holding `: ` or `"` stay the text they are. Bytes from 0x80 on are left as they are (the
// loader checks the UTF-8).
std::string yamlString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7F) {
      out += fmt::format("\\x{:02x}", byte);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// The shortest text that reads back as the same double; YAML's spelling of the non-finite ones, which
// the loader refuses with its own message.
std::string yamlNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return fmt::format("{}", value);
}

void addKey(Entries& e, std::string_view key, const std::optional<std::string>& value) {
  if (value) e.emplace_back(key, yamlString(*value));
}
void addKey(Entries& e, std::string_view key, const std::optional<double>& value) {
  if (value) e.emplace_back(key, yamlNumber(*value));
}

std::string rangeYaml(const ColorRange& range, std::string_view path) {
  if (range.scale != RangeScale::linear && range.scale != RangeScale::log) {
    throw ArgumentError(fmt::format("Scenario::setStyle: {}.range.scale is not a RangeScale (linear or log), got {}",
                                    path, int(range.scale)));
  }
  if (!range.min && !range.max && range.scale == RangeScale::linear) return "auto";
  Entries e;
  addKey(e, "min", range.min);
  addKey(e, "max", range.max);
  e.emplace_back("scale", range.scale == RangeScale::log ? "log" : "linear");
  return flowMap(e);
}

// The keys particles, springs and bodies share: a quantity through a colormap over a range, or a colour.
template <class Shapes>
void addColoring(Entries& e, const Shapes& s, std::string_view path) {
  addKey(e, "color_by", s.colorBy);
  addKey(e, "colormap", s.colormap);
  if (s.range) e.emplace_back("range", rangeYaml(*s.range, path));
  addKey(e, "color", s.color);
}

// One class of shapes' map: the keys all three share, then its own (radius, width or outline).
template <class Shapes>
std::string shapesYaml(const Shapes& s, std::string_view path, std::string_view ownKey,
                       const std::optional<std::string>& own) {
  Entries e;
  addColoring(e, s, path);
  addKey(e, ownKey, own);
  return flowMap(e);
}

std::string colorbarYaml(const ColorbarStyle& bar) {
  if (!bar.show) return "false";
  Entries e;
  addKey(e, "for", bar.for_);
  addKey(e, "label", bar.label);
  addKey(e, "position", bar.position);
  return e.empty() ? "true" : flowMap(e);
}

// One reference as a scalar, as a scenario usually writes it; several as a list.
std::string referencesYaml(const std::vector<std::string>& refs) {
  if (refs.size() == 1) return yamlString(refs.front());
  std::string out = "[";
  for (const std::string& ref : refs) out += (out.size() > 1 ? ", " : "") + yamlString(ref);
  return out + "]";
}

std::string trailYaml(const TrailStyle& t) {
  Entries e;
  if (t.seconds) e.emplace_back("seconds", std::isinf(*t.seconds) && *t.seconds > 0 ? "all" : yamlNumber(*t.seconds));
  addKey(e, "width", t.width);
  addKey(e, "color", t.color);
  return flowMap(e);
}

std::string arrowYaml(const ArrowStyle& a) {
  Entries e;
  addKey(e, "of", a.of);
  addKey(e, "scale", a.scale);
  addKey(e, "max", a.max);
  addKey(e, "color", a.color);
  return flowMap(e);
}

std::string selectionYaml(const StyleSelection& s) {
  Entries e;
  if (!s.particles.empty()) e.emplace_back("particles", referencesYaml(s.particles));
  if (!s.bodies.empty()) e.emplace_back("bodies", referencesYaml(s.bodies));
  addKey(e, "color", s.color);
  addKey(e, "radius", s.radius);
  if (s.trail) e.emplace_back("trail", trailYaml(*s.trail));
  if (s.arrow) e.emplace_back("arrow", arrowYaml(*s.arrow));
  addKey(e, "label", s.label);
  return flowMap(e);
}

}  // namespace

bool isEmpty(const Style& style) {
  return style == Style{};
}

std::string styleYaml(const Style& style) {
  Entries e;
  const ParticleStyle& p = style.particles;
  const SpringStyle& s = style.springs;
  const BodyStyle& b = style.bodies;
  if (p != ParticleStyle{}) e.emplace_back("particles", shapesYaml(p, "particles", "radius", p.radius));
  if (s != SpringStyle{}) e.emplace_back("springs", shapesYaml(s, "springs", "width", s.width));
  if (b != BodyStyle{}) e.emplace_back("bodies", shapesYaml(b, "bodies", "outline", b.outline));
  if (style.colorbar) e.emplace_back("colorbar", colorbarYaml(*style.colorbar));
  addKey(e, "title", style.title);
  if (style.scaleBar) e.emplace_back("scale_bar", *style.scaleBar ? "true" : "false");
  if (!style.select.empty()) {
    std::string list = "[";
    for (const StyleSelection& s : style.select) list += (list.size() > 1 ? ", " : "") + selectionYaml(s);
    e.emplace_back("select", list + "]");
  }
  return flowMap(e);
}

}  // namespace particles::api
