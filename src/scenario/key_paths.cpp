#include "scenario/key_paths.hpp"

#include <fmt/format.h>

#include <charconv>

#include "input/printable_text.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

// A key path as an error names it: a path longer than a message quotes (a 10 MB one given by
// mistake) is shown cut, with its size (input::quotedValue).
std::string shownPath(const std::string& path) {
  return input::shownValue(path);
}

}  // namespace

namespace detail {

std::vector<PathSegment> splitPath(const Override& o, const std::string& file) {
  auto bad = [&](const std::string& why) {
    throw ScenarioError(file, 0, 0, shownPath(o.path), fmt::format("cannot use this key path: {}", why), o.origin);
  };
  auto indexSegment = [&](const std::string& digits) {
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) {
      bad(fmt::format("{} is not a list index", input::quotedValue(digits)));
    }
    size_t index = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (ec != std::errc() || end != digits.data() + digits.size()) {
      bad(fmt::format("list index {} is too large", digits.size() > 40 ? digits.substr(0, 40) + "…" : digits));
    }
    return PathSegment{digits, true, index};
  };
  std::vector<PathSegment> out;
  std::string key;
  size_t i = 0;
  const std::string& p = o.path;
  auto flushKey = [&] {
    if (key.empty()) bad("empty key");
    if (key.find_first_not_of("0123456789") == std::string::npos) {
      out.push_back(indexSegment(key));
    } else {
      out.push_back({key, false, 0});
    }
    key.clear();
  };
  while (i < p.size()) {
    const char c = p[i];
    if (c == '.') {
      if (!key.empty())
        flushKey();
      else if (out.empty() || !out.back().isIndex)
        bad("empty key");
      ++i;
    } else if (c == '[') {
      if (!key.empty()) flushKey();
      const size_t close = p.find(']', i);
      if (close == std::string::npos) bad("unclosed '['");
      out.push_back(indexSegment(p.substr(i + 1, close - i - 1)));
      i = close + 1;
    } else {
      key += c;
      ++i;
    }
  }
  if (!key.empty()) flushKey();
  if (out.empty()) bad("empty key path");
  return out;
}

void appendSegment(std::string& canonical, const PathSegment& s) {
  canonical += s.isIndex ? fmt::format("[{}]", s.index) : (canonical.empty() ? s.key : "." + s.key);
}

YAML::Node overrideValue(const Override& o, const std::string& file) {
  if (o.value.empty()) throw ScenarioError(file, 0, 0, shownPath(o.path), "expected a value after '='", o.origin);
  YAML::Node value;
  try {
    // Bounded as a scenario's text is (NodeLimit): a value is parsed before anything checks it.
    checkNodeCount(o.value, "the value", NodeLimit::scenario(std::uintmax_t(SceneLimits{}.nodes)));
    value = YAML::Load(o.value);
  } catch (const ScenarioError& e) {
    throw ScenarioError(file, 0, 0, shownPath(o.path),
                        fmt::format("cannot read the value {}: {}", input::quotedValue(o.value), e.message()),
                        o.origin);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(file, 0, 0, shownPath(o.path),
                        fmt::format("cannot read the value {}: {}", input::quotedValue(o.value), e.msg), o.origin);
  }
  if (value.IsNull()) {
    throw ScenarioError(file, 0, 0, shownPath(o.path), "expected a value after '='", o.origin);
  }
  return value;
}

std::string applyOverride(YAML::Node root, const Override& o, const std::string& file) {
  const std::vector<PathSegment> segments = splitPath(o, file);
  const YAML::Node value = overrideValue(o, file);
  std::string canonical;
  YAML::Node cur = root;
  for (size_t k = 0; k < segments.size(); ++k) {
    const PathSegment& s = segments[k];
    const bool last = k + 1 == segments.size();
    auto fail = [&](const std::string& why) {
      throw ScenarioError(file, 0, 0, canonical.empty() ? shownPath(o.path) : canonical, why, o.origin);
    };
    if (s.isIndex) {
      if (!cur.IsSequence()) fail(fmt::format("cannot index [{}]: this is not a list", s.index));
      if (s.index >= cur.size())
        fail(fmt::format("index {} is out of range: the list has {} entries", s.index, cur.size()));
      appendSegment(canonical, s);
      if (last) {
        cur[s.index] = value;
      } else {
        YAML::Node next = cur[s.index];
        cur.reset(next);
      }
    } else {
      if (!(cur.IsMap() || cur.IsNull() || !cur.IsDefined())) {
        fail(fmt::format("cannot set key {}: this is not a map", input::quotedValue(s.key)));
      }
      appendSegment(canonical, s);
      if (last) {
        cur[s.key] = value;
      } else {
        YAML::Node next = cur[s.key];
        cur.reset(next);
      }
    }
  }
  return canonical;
}

InPlaceOverrides::InPlaceOverrides(YAML::Node root, std::string file)
    : root_(std::move(root)), file_(std::move(file)), saved_(YAML::NodeType::Sequence) {}

std::optional<YAML::Node> parentInPlace(const YAML::Node& root, const std::vector<PathSegment>& segments) {
  // Walked read-only: a const node's operator[] adds nothing to the tree.
  YAML::Node parent = root;
  for (size_t k = 0; k + 1 < segments.size(); ++k) {
    const PathSegment& s = segments[k];
    const YAML::Node& here = parent;
    const YAML::Node next = s.isIndex ? (here.IsSequence() && s.index < here.size() ? here[s.index] : YAML::Node())
                                      : (here.IsMap() ? here[s.key] : YAML::Node());
    if (!next.IsDefined() || !(next.IsMap() || next.IsSequence())) return std::nullopt;
    parent.reset(next);
  }
  const PathSegment& last = segments.back();
  const bool reachable = last.isIndex ? parent.IsSequence() && last.index < parent.size() : parent.IsMap();
  return reachable ? std::optional<YAML::Node>(parent) : std::nullopt;
}

std::optional<std::string> InPlaceOverrides::apply(const std::vector<PathSegment>& segments, const YAML::Node& value) {
  const std::optional<YAML::Node> found = parentInPlace(root_, segments);
  if (!found) return std::nullopt;
  YAML::Node parent = *found;
  std::string canonical;
  for (const PathSegment& s : segments) appendSegment(canonical, s);
  const PathSegment& last = segments.back();
  const YAML::Node& here = parent;
  const bool present = last.isIndex || here[last.key].IsDefined();
  Change change{parent, last, !present, 0};
  if (present) {
    change.slot = changes_.size();
    while (saved_.size() <= change.slot) saved_.push_back(YAML::Node(YAML::NodeType::Null));
    if (last.isIndex) {
      saved_[change.slot] = parent[last.index];
      parent[last.index] = value;
    } else {
      saved_[change.slot] = parent[last.key];
      parent[last.key] = value;
    }
  } else {
    parent[last.key] = value;
  }
  changes_.push_back(std::move(change));
  return canonical;
}

void InPlaceOverrides::undo() {
  for (auto c = changes_.rbegin(); c != changes_.rend(); ++c) {
    if (c->added) {
      c->parent.remove(c->segment.key);
    } else if (c->segment.isIndex) {
      c->parent[c->segment.index] = saved_[c->slot];
    } else {
      c->parent[c->segment.key] = saved_[c->slot];
    }
  }
  changes_.clear();
}

}  // namespace detail

Override parseOverride(std::string_view text) {
  const std::string origin = fmt::format("--set {}", input::shownValue(text));
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw ScenarioError("command line", 0, 0, "",
                        fmt::format("expected --set path.to.key=value, as in --set simulation.dt=0.005; got {}",
                                    input::quotedValue(text)));
  }
  return Override{std::string(text.substr(0, eq)), std::string(text.substr(eq + 1)), origin};
}

}  // namespace particles::scenario
