#include "scenario/references.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "input/printable_text.hpp"
#include "input/closest_name.hpp"
#include "scenario/scenario.hpp"

namespace particles::scenario::detail {

namespace {

constexpr const char* kForms = "a name, grid[row][col], body@[x, y] or #index";

bool isNameStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

std::string trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::optional<double> parseNumber(std::string_view text) {
  const std::string s = trim(text);
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

std::optional<long> parseIndex(std::string_view text) {
  const std::string s = trim(text);
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const long n = std::strtol(s.c_str(), &end, 10);
  if (end != s.c_str() + s.size()) return std::nullopt;
  return n;
}

// `cloth[3][4]` → {"cloth", "[3][4]"}: the leading name and the trimmed rest.
std::pair<std::string, std::string> splitName(const std::string& text) {
  size_t end = 0;
  while (end < text.size() && isNameChar(text[end])) ++end;
  return {text.substr(0, end), trim(std::string_view(text).substr(end))};
}

// `[3][*]` → {"3", "*"}; nothing unless the text is exactly two bracketed selectors.
std::optional<std::array<std::string, 2>> cellSelectors(const std::string& rest) {
  std::vector<std::string> parts;
  size_t i = 0;
  while (i < rest.size()) {
    if (rest[i] != '[') break;
    const size_t close = rest.find(']', i);
    if (close == std::string::npos) break;
    parts.push_back(trim(std::string_view(rest).substr(i + 1, close - i - 1)));
    i = close + 1;
    while (i < rest.size() && std::isspace(static_cast<unsigned char>(rest[i]))) ++i;
  }
  if (i != rest.size() || parts.size() != 2) return std::nullopt;
  return std::array<std::string, 2>{parts[0], parts[1]};
}

const char* kindName(NamedObjects::Kind kind) {
  switch (kind) {
    case NamedObjects::Kind::particle: return "a particle";
    case NamedObjects::Kind::grid: return "a grid";
    case NamedObjects::Kind::body: return "a rigid body";
  }
  return "?";
}

// One reference string to its points.
std::vector<Endpoint> resolveOne(const Value& at, const std::string& raw, const NamedObjects& names, PointKind kind,
                                 bool allowList) {
  const std::string text = trim(raw);
  auto bad = [&](const std::string& why) { at.fail(fmt::format("reference {}: {}", input::quotedValue(text), why)); };

  if (!text.empty() && text[0] == '#') {
    const auto n = parseIndex(std::string_view(text).substr(1));
    if (!n) bad(fmt::format("expected #index with a whole number, as in #3 (forms: {})", kForms));
    if (*n < 0 || *n >= names.numParticles) {
      bad(fmt::format("particle #{} does not exist (there are {} particles, #0 to #{})", *n, names.numParticles,
                      names.numParticles - 1));
    }
    return {Endpoint::ofParticle(int(*n))};
  }

  if (text.empty() || !isNameStart(text[0])) bad(fmt::format("expected {}", kForms));
  // Plain references rather than a structured binding: the `range` lambda below uses `name`, and
  // clang before 16 cannot capture a structured binding (the fuzz build uses Debian's clang 14).
  const auto split = splitName(text);
  const std::string& name = split.first;
  const std::string& rest = split.second;
  const NamedObjects::Entry* entry = names.find(name);
  if (!entry) {
    const std::string suggestion = input::closestName(name, names.names());
    bad(fmt::format(
        "nothing is named {}{}", input::quotedValue(name),
        suggestion.empty() ? std::string() : fmt::format("; did you mean {}?", input::quotedValue(suggestion))));
  }

  if (rest.empty()) {
    switch (entry->kind) {
      case NamedObjects::Kind::particle: return {Endpoint::ofParticle(entry->index)};
      case NamedObjects::Kind::body:
        if (kind == PointKind::particle) {
          bad(fmt::format("{} is a rigid body, but only particles are allowed here", input::quotedValue(name)));
        }
        return {Endpoint::ofBody(entry->index)};
      case NamedObjects::Kind::grid: {
        if (!allowList)
          bad(fmt::format("{} is a whole grid; name one particle, as in {}[0][0]", input::quotedValue(name), name));
        std::vector<Endpoint> all;
        for (int r = 0; r < entry->grid.rows; ++r)
          for (int c = 0; c < entry->grid.cols; ++c) all.push_back(Endpoint::ofParticle(entry->grid.at(r, c)));
        return all;
      }
    }
  }

  if (rest[0] == '@') {
    if (entry->kind != NamedObjects::Kind::body) {
      bad(fmt::format("{} is {}; an anchor `name@[x, y]` needs a rigid body", input::quotedValue(name),
                      kindName(entry->kind)));
    }
    if (kind == PointKind::particle) bad("rigid-body anchors are not allowed here, only particles");
    const std::string inner = trim(std::string_view(rest).substr(1));
    const size_t comma = inner.find(',');
    std::optional<double> x, y;
    if (inner.size() >= 2 && inner.front() == '[' && inner.back() == ']' && comma != std::string::npos) {
      x = parseNumber(std::string_view(inner).substr(1, comma - 1));
      y = parseNumber(std::string_view(inner).substr(comma + 1, inner.size() - comma - 2));
    }
    if (!x || !y) bad("expected an anchor in body coordinates after '@', as in link0@[0.2, -0.05]");
    return {Endpoint::ofBody(entry->index, Vec2(*x, *y))};
  }

  if (rest[0] == '[') {
    if (entry->kind != NamedObjects::Kind::grid) {
      bad(fmt::format("{} is {}, not a grid; only grid particles are addressed as grid[row][col]",
                      input::quotedValue(name), kindName(entry->kind)));
    }
    const auto parts = cellSelectors(rest);
    if (!parts) bad(fmt::format("expected {}[row][col]", name));
    const GridIndices& g = entry->grid;
    auto range = [&](const std::string& part, int count, const char* what) -> std::pair<int, int> {
      if (part == "*") {
        if (!allowList) bad(fmt::format("'*' names a whole {}, but only one point is allowed here", what));
        return {0, count};
      }
      const auto n = parseIndex(part);
      if (!n) bad(fmt::format("expected a whole number or '*' as {} index, got {}", what, input::quotedValue(part)));
      const long k = *n < 0 ? *n + count : *n;
      if (k < 0 || k >= count) {
        bad(fmt::format("{} {} is out of range: grid {} has {} {}s (0 to {}, or -1 to -{} from the end)", what, *n,
                        input::quotedValue(name), count, what, count - 1, count));
      }
      return {int(k), int(k) + 1};
    };
    const auto [r0, r1] = range((*parts)[0], g.rows, "row");
    const auto [c0, c1] = range((*parts)[1], g.cols, "column");
    std::vector<Endpoint> out;
    for (int r = r0; r < r1; ++r)
      for (int c = c0; c < c1; ++c) out.push_back(Endpoint::ofParticle(g.at(r, c)));
    return out;
  }

  bad(fmt::format("unexpected {} after the name; expected {}", input::quotedValue(rest), kForms));
  return {};
}

}  // namespace

void NamedObjects::add(const Value& at, const std::string& name, Entry entry) {
  if (name.empty() || !isNameStart(name[0]) ||
      !std::all_of(name.begin(), name.end(), [](char c) { return isNameChar(c); })) {
    at.fail(fmt::format("{} is not a valid name: use letters, digits, '_' and '-', starting with a letter or '_'",
                        input::quotedValue(name)));
  }
  if (const Entry* previous = find(name)) {
    at.fail(fmt::format("duplicate name {}: already used by {}{}", input::quotedValue(name), kindName(previous->kind),
                        previous->line > 0 ? fmt::format(" on line {}", previous->line) : std::string()));
  }
  entries_.emplace(name, entry);
}

const NamedObjects::Entry* NamedObjects::find(const std::string& name) const {
  const auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

std::vector<std::string> NamedObjects::names() const {
  std::vector<std::string> out;
  for (const auto& [name, entry] : entries_) out.push_back(name);
  return out;
}

std::vector<Endpoint> resolvePoints(const Value& value, const NamedObjects& names, PointKind kind, bool allowList) {
  if (value.isSequence() && allowList) {
    std::vector<Endpoint> out;
    for (const Value& item : value.items()) {
      if (!item.isScalar()) item.fail(fmt::format("expected a reference ({}), {}", kForms, item.found()));
      const auto points = resolveOne(item, item.node().Scalar(), names, kind, true);
      out.insert(out.end(), points.begin(), points.end());
    }
    if (out.empty()) value.fail("expected at least one reference, got an empty list");
    return out;
  }
  if (!value.isScalar()) {
    value.fail(
        fmt::format("expected a reference ({}{}), {}", kForms, allowList ? ", or a list of them" : "", value.found()));
  }
  return resolveOne(value, value.node().Scalar(), names, kind, allowList);
}

long long countPoints(const YAML::Node& value, const std::map<std::string, GridIndices, std::less<>>& grids) {
  auto countOne = [&](const YAML::Node& item) -> long long {
    if (!item.IsDefined() || !item.IsScalar()) return 0;
    const std::string text = trim(item.Scalar());
    if (text.empty() || text[0] == '#' || !isNameStart(text[0])) return 1;
    const auto [name, rest] = splitName(text);
    const auto grid = grids.find(name);
    if (grid == grids.end()) return 1;
    const long long rows = grid->second.rows, cols = grid->second.cols;
    if (rest.empty()) return rows * cols;
    const auto parts = cellSelectors(rest);
    if (!parts) return 1;
    return ((*parts)[0] == "*" ? rows : 1) * ((*parts)[1] == "*" ? cols : 1);
  };
  if (!value.IsDefined() || !value.IsSequence()) return countOne(value);
  long long total = 0;
  for (const YAML::Node& item : value) total += countOne(item);
  return total;
}

}  // namespace particles::scenario::detail

namespace particles::scenario {

std::string pointName(const Model& model, int point) {
  const int n = model.layout.numParticles;
  if (point < n) {
    const std::string& name = model.particleNames[size_t(point)];
    return name.empty() ? fmt::format("#{}", point) : name;
  }
  const std::string& name = model.bodyNames[size_t(point - n)];
  return name.empty() ? fmt::format("body#{}", point - n) : name;
}

}  // namespace particles::scenario
