#include "scenario/entry_args.hpp"
#include "input/printable_text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace particles::scenario::detail {

Vec2 PointBook::position(const Endpoint& e) const {
  if (e.isParticle()) return particlePos[size_t(e.particle)];
  const double c = std::cos(bodyAngle[size_t(e.body)]), s = std::sin(bodyAngle[size_t(e.body)]);
  return bodyPos[size_t(e.body)] + Vec2(c * e.anchor.x() - s * e.anchor.y(), s * e.anchor.x() + c * e.anchor.y());
}

std::string PointBook::describe(const Endpoint& e) const {
  if (!e.isParticle()) {
    return fmt::format("the anchor [{}, {}] of rigid body {}", formatNumber(e.anchor.x()), formatNumber(e.anchor.y()),
                       bodyNames[size_t(e.body)]);
  }
  return fmt::format("particle {}", particleNames[size_t(e.particle)]);
}

std::vector<std::string_view> allowedKeys(const KindSpec& kind, bool typed) {
  std::vector<std::string_view> keys;
  if (typed) keys.push_back("type");
  for (const ParamSpec& p : kind.params) keys.push_back(p.key);
  return keys;
}

EntryArgs::EntryArgs(const KindSpec& kind, const Value& entry, bool typed, const NamedObjects& names,
                     const PointBook& points)
    : kind_(kind), reader_(entry, allowedKeys(kind, typed)), names_(names), points_(points) {}

const ParamSpec& EntryArgs::spec(std::string_view key) const {
  const ParamSpec* p = kind_.param(key);
  if (!p)
    throw std::logic_error(
        fmt::format("kind {} reads the undeclared key {}", input::quotedValue(kind_.type), input::quotedValue(key)));
  return *p;
}

std::optional<Value> EntryArgs::value(const ParamSpec& spec) const {
  if (!spec.insteadOf.empty()) {  // exactly one of the pair
    const bool mine = reader_.has(spec.key), other = reader_.has(spec.insteadOf);
    if (mine && other) {
      // At whichever of the two the kind declares second, as a reader meets it.
      const bool mineFirst = kind_.param(spec.key) < kind_.param(spec.insteadOf);
      reader_.optional(mineFirst ? spec.insteadOf : spec.key)
          ->fail(fmt::format("give either {} or {}, not both",
                             input::quotedValue(mineFirst ? spec.key : spec.insteadOf),
                             input::quotedValue(mineFirst ? spec.insteadOf : spec.key)));
    }
    if (!mine && !other) {
      reader_.self()
          .child(reader_.self().node(), reader_.self().path() + "." + std::string(spec.key), YAML::Mark::null_mark())
          .fail(fmt::format("missing required key {} (or {})", input::quotedValue(spec.key),
                            input::quotedValue(spec.insteadOf)));
    }
  }
  if (spec.required) return reader_.required(spec.key);
  return reader_.optional(spec.key);
}

bool EntryArgs::has(std::string_view key) const {
  spec(key);
  return reader_.has(key);
}

double EntryArgs::number(std::string_view key) const {
  const ParamSpec& s = spec(key);
  if (const auto v = value(s)) return v->bounded(s.min, s.max);
  if (!s.defaultNumber)
    throw std::logic_error(fmt::format("kind {} reads {}, absent without a default", input::quotedValue(kind_.type),
                                       input::quotedValue(key)));
  return *s.defaultNumber;
}

Vec2 EntryArgs::vec2(std::string_view key) const {
  const ParamSpec& s = spec(key);
  if (const auto v = value(s)) return v->vec2();
  if (!s.defaultVec2)
    throw std::logic_error(fmt::format("kind {} reads {}, absent without a default", input::quotedValue(kind_.type),
                                       input::quotedValue(key)));
  return *s.defaultVec2;
}

std::vector<Endpoint> EntryArgs::points(std::string_view key) const {
  const ParamSpec& s = spec(key);
  const auto v = value(s);
  if (!v)
    throw std::logic_error(fmt::format("kind {} reads the absent optional points {}", input::quotedValue(kind_.type),
                                       input::quotedValue(key)));
  const bool particlesOnly = s.type == ParamType::particle || s.type == ParamType::particles;
  const bool list = s.type == ParamType::particles || s.type == ParamType::endpoints;
  return resolvePoints(*v, names_, particlesOnly ? PointKind::particle : PointKind::endpoint, list);
}

std::vector<Vec2> EntryArgs::path(std::string_view key) const {
  const auto v = value(spec(key));
  if (!v)
    throw std::logic_error(fmt::format("kind {} reads the absent optional path {}", input::quotedValue(kind_.type),
                                       input::quotedValue(key)));
  std::vector<Vec2> out;
  for (const Value& point : v->items()) out.push_back(point.vec2());
  if (out.empty()) v->fail("a path needs at least one point [x, y]");
  return out;
}

void EntryArgs::fail(std::string_view key, const std::string& message) const {
  if (!key.empty()) {
    if (const auto v = reader_.optional(key)) v->fail(message);
  }
  reader_.self().fail(message);
}

}  // namespace particles::scenario::detail
