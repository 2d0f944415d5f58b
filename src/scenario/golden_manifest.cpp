// Reading a golden manifest (golden_manifest.hpp): its keys, their types and ranges, and the names
// its checks take, checked before any scenario is opened. Whether a --set path exists in its
// scenario, or a theme or raster is one the renderer has, is the golden room's to say (src/golden/),
// at the positions kept here. Read like a sweep file (sweep_spec.cpp): the file's shape is bounded
// on the parser's events before a node is built, then Value and MapReader read the tree.
#include "scenario/golden_manifest.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <initializer_list>
#include <limits>
#include <map>
#include <numeric>

#include "input/printable_text.hpp"
#include "scenario/key_paths.hpp"
#include "scenario/scenario.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

using detail::MapReader;
using detail::Value;

// Values, keys and lists one manifest may hold: a list of times for every check, and room for the
// rest (as kMaxSweepNodes). Counted before any node is built, at ~900 bytes each once built.
constexpr std::uintmax_t kMaxGoldenNodes = 3 * kMaxGoldenChecks + 10'000;

constexpr std::string_view kNameCharsText = "letters, digits and . _ + -";

GoldenPosition goldenPositionOf(const Value& v) {
  const YAML::Mark m = v.mark();
  if (m.is_null()) return {0, 0, v.path()};
  return {m.line + 1, m.column + 1, v.path()};
}

// An optional setting: absent unless written, then read by `read` and kept with its position.
template <class T, class Read>
void readSetting(const MapReader& m, std::string_view key, std::optional<GoldenSetting<T>>& into, Read read) {
  if (auto v = m.optional(key)) into = GoldenSetting<T>{read(*v), goldenPositionOf(*v)};
}

std::filesystem::path resolvedAgainst(const std::filesystem::path& directory, const std::string& given) {
  const std::filesystem::path path = given;
  return path.is_absolute() ? path : directory / path;
}

// `320x240`, as `particles render --size` takes it; each side 1 … kMaxImageSide.
std::pair<int, int> frameSizeOf(const Value& v) {
  const std::string text = v.string();
  const size_t x = text.find_first_of("xX");
  auto side = [&](std::string_view digits) {
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos) {
      v.fail(fmt::format("expected a size WIDTHxHEIGHT in px, such as 320x240, got {}", input::quotedValue(text)));
    }
    long long n = kMaxImageSide + 1;  // also when the digits are past what a long long holds
    std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (n < 1 || n > kMaxImageSide) {
      v.fail(fmt::format("expected each side of the size from 1 to {} px, got {}", kMaxImageSide,
                         input::quotedValue(text)));
    }
    return int(n);
  };
  if (x == std::string::npos) side("");
  const std::string_view all = text;
  return {side(all.substr(0, x)), side(all.substr(x + 1))};
}

int sampleCountOf(const Value& v) {
  const long long n = v.integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
  if (std::find(std::begin(kGoldenSampleCounts), std::end(kGoldenSampleCounts), n) == std::end(kGoldenSampleCounts)) {
    v.fail(fmt::format("expected {} samples per pixel (1: off), got {}",
                       fmt::join(std::begin(kGoldenSampleCounts), std::end(kGoldenSampleCounts), ", "), n));
  }
  return int(n);
}

GoldenRenderSettings readGoldenRender(const Value& v) {
  const MapReader m(v, {"size", "msaa", "theme", "background", "raster"});
  auto text = [](const Value& x) { return x.string(); };
  GoldenRenderSettings r;
  readSetting(m, "size", r.size, frameSizeOf);
  readSetting(m, "msaa", r.msaa, sampleCountOf);
  readSetting(m, "theme", r.theme, text);
  readSetting(m, "background", r.background, text);
  readSetting(m, "raster", r.raster, text);
  return r;
}

GoldenFrameTolerance readFrameTolerance(const Value& v) {
  const MapReader m(v, {"threshold", "max_share"});
  GoldenFrameTolerance t;
  readSetting(m, "threshold", t.threshold, [](const Value& x) { return int(x.integer(0, 255)); });
  readSetting(m, "max_share", t.maxShare, [](const Value& x) { return x.inRange(0.0, 1.0); });
  return t;
}

GoldenStateTolerance readStateTolerance(const Value& v) {
  const MapReader m(v, {"position", "velocity", "angle", "omega"});
  auto nonNegative = [](const Value& x) { return x.nonNegative(); };
  GoldenStateTolerance t;
  readSetting(m, "position", t.position, nonNegative);
  readSetting(m, "velocity", t.velocity, nonNegative);
  readSetting(m, "angle", t.angle, nonNegative);
  readSetting(m, "omega", t.omega, nonNegative);
  return t;
}

// Distinct times in increasing order, each with its text as written, and their nodes in the same
// order; a time written twice is refused at its second place.
std::vector<GoldenTime> readTimes(const Value& v, std::vector<Value>& sortedItems) {
  const std::vector<Value> items = v.items();
  if (items.empty()) v.fail("an empty list: give at least one time, in seconds");
  std::vector<GoldenTime> times;
  for (const Value& item : items) {
    if (!item.isScalar()) item.fail(fmt::format("expected a time in seconds (a number ≥ 0), {}", item.found()));
    times.push_back({item.nonNegative(), item.node().Scalar(), "", goldenPositionOf(item)});
  }
  std::vector<size_t> order(times.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return times[a].seconds < times[b].seconds; });
  size_t repeat = times.size(), first = 0;
  for (size_t k = 1; k < order.size(); ++k) {
    if (times[order[k]].seconds == times[order[k - 1]].seconds && order[k] < repeat) {
      repeat = order[k];
      first = order[k - 1];
    }
  }
  if (repeat < times.size()) {
    items[repeat].fail(fmt::format("the time {} is listed twice (first as {} at line {}); each time is one check",
                                   times[repeat].text, times[first].text, times[first].at.line));
  }
  std::vector<GoldenTime> sorted;
  for (size_t i : order) {
    sorted.push_back(std::move(times[i]));
    sortedItems.push_back(items[i]);
  }
  return sorted;
}

// `set`: a map of key paths to values ({"grids[0].springs.structural.ks": [26.25, 1.05]}) or a list
// of `PATH=VALUE` texts, either way as --set takes them, in the order written.
void readSets(const Value& v, GoldenEntry& entry, const std::string& file) {
  auto add = [&](const std::string& path, const std::string& value, const Value& pathAt, const Value& at) {
    try {
      detail::splitPath(Override{path, value, ""}, file);
    } catch (const ScenarioError& e) {
      pathAt.fail(e.message());
    }
    if (value.empty()) at.fail(fmt::format("expected a value for {}", input::quotedValue(path)));
    for (const auto& [seen, ignored] : entry.sets) {
      if (seen == path) pathAt.fail(fmt::format("{} is set twice", input::quotedValue(path)));
    }
    entry.sets.emplace_back(path, value);
    entry.setsAt.push_back(goldenPositionOf(at));
  };
  if (v.isMap()) {
    for (auto it = v.node().begin(); it != v.node().end(); ++it) {
      const std::string path = it->first.IsScalar() ? it->first.Scalar() : "?";
      const Value key = v.child(it->first, v.path() + "." + path, it->first.Mark());
      const Value value = v.child(it->second, v.path() + "." + path, it->first.Mark());
      if (!it->first.IsScalar()) key.fail("expected a key path, got a list or map as key");
      if (value.isNull())
        value.fail(fmt::format("expected a value for --set (a number, a name, a list or a map), {}", value.found()));
      add(path, detail::overrideValueText(value.node()), key, value);
    }
  } else if (v.isSequence()) {
    for (const Value& item : v.items()) {
      const std::string text = item.string();
      const size_t eq = text.find('=');
      if (eq == std::string::npos || eq == 0) {
        item.fail(fmt::format("expected PATH=VALUE as --set takes it, such as simulation.dt=0.001, got {}",
                              input::quotedValue(text)));
      }
      add(text.substr(0, eq), text.substr(eq + 1), item, item);
    }
  } else {
    v.fail(fmt::format("expected a map of key paths and values, or a list of PATH=VALUE, {}", v.found()));
  }
}

// A name pattern split at its placeholders: text as written, the scenario's stem, the time's text.
struct NamePart {
  enum class From { pattern, scenario, time } from;
  std::string text;
};

std::vector<NamePart> parseNamePattern(const std::string& pattern, const Value& at, bool frames) {
  const std::string known = frames ? "{scenario}, {time}" : "{scenario}";
  std::vector<NamePart> parts;
  size_t i = 0;
  while (i < pattern.size()) {
    const size_t open = std::min(pattern.find('{', i), pattern.size());
    if (open > i) parts.push_back({NamePart::From::pattern, pattern.substr(i, open - i)});
    if (open == pattern.size()) break;
    const size_t close = pattern.find('}', open);
    if (close == std::string::npos)
      at.fail(fmt::format("the name {} opens a '{{' it does not close", input::quotedValue(pattern)));
    const std::string placeholder = pattern.substr(open, close - open + 1);
    if (placeholder == "{scenario}") {
      parts.push_back({NamePart::From::scenario, ""});
    } else if (placeholder == "{time}" && frames) {
      parts.push_back({NamePart::From::time, ""});
    } else if (placeholder == "{time}") {
      at.fail("a state's name cannot hold {time}: one state file (NAME.csv) holds all of the entry's times");
    } else {
      at.fail(fmt::format("unknown placeholder {} in the name (known: {})", input::quotedValue(placeholder), known));
    }
    i = close + 1;
  }
  return parts;
}

// The pattern with its placeholders filled, checked as a file name. A fault is reported where it
// comes from: the pattern's own text at `name` (the scenario when no name is written), the
// scenario's stem at `scenario`, a time's text at the time.
std::string expandName(const std::vector<NamePart>& parts, const Value& name, const Value& scenario,
                       const std::string& stem, const Value* time) {
  std::string expanded;
  std::vector<std::pair<std::string_view, const Value*>> pieces;
  for (const NamePart& part : parts) {
    if (part.from == NamePart::From::pattern) pieces.emplace_back(part.text, &name);
    if (part.from == NamePart::From::scenario) pieces.emplace_back(stem, &scenario);
    if (part.from == NamePart::From::time) pieces.emplace_back(time->node().Scalar(), time);
  }
  for (const auto& [text, from] : pieces) expanded += text;
  auto bad = [&](const Value& at, const std::string& why) {
    const std::string fix = &at == time        ? "; write the time another way or change the name"
                            : &at == &scenario ? "; give the entry a name"
                                               : "";
    at.fail(fmt::format("the name {} is not a file name: {}{}", input::quotedValue(expanded), why, fix));
  };
  for (const auto& [text, from] : pieces) {
    const bool fileChars = std::all_of(text.begin(), text.end(), [](char c) {
      return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
             std::string_view("._+-").find(c) != std::string_view::npos;
    });
    if (!fileChars) bad(*from, fmt::format("only {} may be in one", kNameCharsText));
  }
  if (expanded.empty()) bad(name, "it is empty");
  const auto first = std::find_if(pieces.begin(), pieces.end(), [](const auto& p) { return !p.first.empty(); });
  if (expanded[0] == '.') bad(*first->second, "it starts with a dot");
  if (expanded.size() > kMaxGoldenNameLength) {
    size_t fromTime = 0;  // the time's share of the name: the time is at fault when the rest fits
    for (const auto& [text, from] : pieces) fromTime += from == time ? text.size() : 0;
    const bool timeTooLong = fromTime > 0 && expanded.size() - fromTime <= kMaxGoldenNameLength;
    bad(timeTooLong ? *time : name, fmt::format("it is longer than {} characters", kMaxGoldenNameLength));
  }
  return expanded;
}

// A check's name and where a clash with another is reported: the name if written, else what
// makes it (a frame's time, a state's scenario). A position, not a Value: assigning a YAML::Node
// (as sorting does) rewrites the node it referred to.
struct CheckName {
  std::string name;
  GoldenPosition at;
};

GoldenEntry readGoldenEntry(const Value& v, bool frames, const std::filesystem::path& directory,
                            const std::string& file, std::vector<CheckName>& names) {
  const MapReader m =
      frames ? MapReader(v, {"scenario", "times", "name", "set", "render", "tolerance", "expect", "reference"})
             : MapReader(v, {"scenario", "times", "name", "set", "state_tolerance"});
  GoldenEntry entry;
  entry.at = goldenPositionOf(v);
  const Value scenario = m.required("scenario");
  entry.scenarioGiven = scenario.string();
  entry.scenario = resolvedAgainst(directory, entry.scenarioGiven);
  entry.scenarioAt = goldenPositionOf(scenario);
  std::vector<Value> timeItems;
  entry.times = readTimes(m.required("times"), timeItems);
  if (auto s = m.optional("set")) readSets(*s, entry, file);
  if (frames) {
    if (auto r = m.optional("render")) entry.render = readGoldenRender(*r);
    if (auto t = m.optional("tolerance")) entry.tolerance = readFrameTolerance(*t);
    if (auto e = m.optional("expect")) {
      const std::string expect = e->string();
      if (expect != "match" && expect != "differ")
        e->fail(fmt::format("expected match or differ, got {}", input::quotedValue(expect)));
      entry.expectDiffer = expect == "differ";
    }
    if (auto r = m.optional("reference")) {
      const std::string reference = r->string();
      entry.reference = GoldenSetting<std::string>{reference, goldenPositionOf(*r)};
      if (entry.times.size() != 1) {
        r->fail(fmt::format("a frame compared with another's reference has one time, not {}", entry.times.size()));
      }
      const NamePart literal{NamePart::From::pattern, reference};
      expandName({literal}, *r, scenario, "", nullptr);  // a file name, as a frame's
    }
  } else if (auto t = m.optional("state_tolerance")) {
    entry.stateTolerance = readStateTolerance(*t);
  }

  const std::optional<Value> written = m.optional("name");
  const std::string pattern = written ? written->string() : frames ? "{scenario}_t{time}" : "{scenario}";
  const Value& nameValue = written ? *written : scenario;
  entry.nameAt = written ? goldenPositionOf(*written) : entry.at;
  const std::vector<NamePart> parts = parseNamePattern(pattern, nameValue, frames);
  const std::string stem = std::filesystem::path(entry.scenarioGiven).stem().string();
  if (!frames) {
    entry.stateName = expandName(parts, nameValue, scenario, stem, nullptr);
    names.push_back({entry.stateName, goldenPositionOf(nameValue)});
    return entry;
  }
  const bool withTime =
      std::any_of(parts.begin(), parts.end(), [](const NamePart& p) { return p.from == NamePart::From::time; });
  if (!withTime && entry.times.size() > 1) {
    nameValue.fail(
        fmt::format("the name {} has no {{time}}, so the entry's {} frames would share it: add {{time}} "
                    "to the name",
                    input::quotedValue(pattern), entry.times.size()));
  }
  for (size_t i = 0; i < entry.times.size(); ++i) {
    entry.times[i].frameName = expandName(parts, nameValue, scenario, stem, &timeItems[i]);
    names.push_back({entry.times[i].frameName, written ? entry.nameAt : entry.times[i].at});
  }
  return entry;
}

// Frames and states share report and JUnit names, so every check's name differs from every
// other's; a clash is reported at the later of the two in the file.
void checkNamesDiffer(std::vector<CheckName>& names, const std::string& file) {
  auto position = [](const CheckName& c) { return std::pair(c.at.line, c.at.column); };
  std::stable_sort(names.begin(), names.end(),
                   [&](const CheckName& a, const CheckName& b) { return position(a) < position(b); });
  std::map<std::string_view, const CheckName*> seen;
  for (const CheckName& c : names) {
    const auto [it, added] = seen.emplace(c.name, &c);
    if (!added) {
      const GoldenPosition& first = it->second->at;
      throw ScenarioError(file, c.at.line, c.at.column, c.at.keyPath,
                          fmt::format("a second check named {} (the first is {} at line {}): frames and states "
                                      "share report names, so each needs its own; give one of them a name",
                                      input::quotedValue(c.name), first.keyPath, first.line));
    }
  }
}

// The first of `settings` that is set, or an absent one.
template <class T>
std::optional<GoldenSetting<T>> firstSet(std::initializer_list<const std::optional<GoldenSetting<T>>*> settings) {
  for (const auto* setting : settings) {
    if (*setting) return *setting;
  }
  return std::nullopt;
}

// Settings whose `keys` are each the first of `own`, `commandLine` and `fallback` to set it.
template <class Settings, auto... keys>
Settings laidOver(const Settings& own, const Settings& commandLine, const Settings& fallback) {
  Settings laid;
  ((laid.*keys = firstSet({&(own.*keys), &(commandLine.*keys), &(fallback.*keys)})), ...);
  return laid;
}

}  // namespace

std::vector<GoldenCheck> goldenChecks(const GoldenManifest& manifest) {
  std::vector<GoldenCheck> checks;
  for (size_t i = 0; i < manifest.frames.size(); ++i) {
    const std::vector<GoldenTime>& times = manifest.frames[i].times;
    for (size_t t = 0; t < times.size(); ++t) checks.push_back({GoldenCheck::Kind::frame, i, t, times[t].frameName});
  }
  for (size_t i = 0; i < manifest.states.size(); ++i) {
    checks.push_back({GoldenCheck::Kind::state, i, 0, manifest.states[i].stateName});
  }
  return checks;
}

GoldenRenderSettings renderSettingsOf(const GoldenManifest& manifest, const GoldenEntry& entry,
                                      const GoldenRenderSettings& commandLine) {
  using R = GoldenRenderSettings;
  return laidOver<R, &R::size, &R::msaa, &R::theme, &R::background, &R::raster>(entry.render, commandLine,
                                                                                manifest.defaultRender);
}

GoldenFrameTolerance frameToleranceOf(const GoldenManifest& manifest, const GoldenEntry& entry,
                                      const GoldenFrameTolerance& commandLine) {
  using T = GoldenFrameTolerance;
  return laidOver<T, &T::threshold, &T::maxShare>(entry.tolerance, commandLine, manifest.defaultTolerance);
}

GoldenStateToleranceValues stateToleranceOf(const GoldenManifest& manifest, const GoldenEntry& entry) {
  const GoldenStateTolerance& own = entry.stateTolerance;
  const GoldenStateTolerance& fallback = manifest.defaultStateTolerance;
  GoldenStateToleranceValues laid = kDefaultGoldenStateTolerance;
  auto lay = [](double& into, const auto& ownSetting, const auto& fallbackSetting) {
    if (const auto setting = firstSet({&ownSetting, &fallbackSetting})) into = setting->value;
  };
  lay(laid.position, own.position, fallback.position);
  lay(laid.velocity, own.velocity, fallback.velocity);
  lay(laid.angle, own.angle, fallback.angle);
  lay(laid.omega, own.omega, fallback.omega);
  return laid;
}

void failInManifest(const GoldenManifest& manifest, const GoldenPosition& at, const std::string& message) {
  throw ScenarioError(manifest.file, at.line, at.column, at.keyPath, message);
}

GoldenManifest loadGoldenManifestText(std::string_view text, const std::string& file,
                                      const std::filesystem::path& directory) {
  const YAML::Node root = detail::loadBoundedDocument(
      text, file,
      {.maxNodes = kMaxGoldenNodes,
       .maxListItems = kMaxGoldenChecks,
       .tooManyNodes = fmt::format("more than {} values, keys and lists in one manifest; split it into several files",
                                   kMaxGoldenNodes),
       .tooLongList = fmt::format("a list of more than {} items: a manifest makes at most {} checks, so no list "
                                  "needs more; split it into several files",
                                  kMaxGoldenChecks, kMaxGoldenChecks),
       .alias = "an alias (*name): a manifest writes each value out; anchors and aliases are not read here",
       .secondDocument = "the file holds more than one YAML document; expected one golden manifest"});
  if (!root.IsDefined() || root.IsNull()) {
    throw ScenarioError(file, 1, 1, "", "the file is empty; expected a golden manifest (frames: and/or states:)");
  }
  const detail::Source source{file, {}, {}};
  const Value top(source, root, "", root.Mark());
  const MapReader m(top, {"references", "defaults", "frames", "states"});

  GoldenManifest manifest;
  manifest.file = file;
  manifest.references = directory;
  if (auto r = m.optional("references")) manifest.references = resolvedAgainst(directory, r->string());
  if (auto d = m.optional("defaults")) {
    const MapReader defaults(*d, {"render", "tolerance", "state_tolerance"});
    if (auto r = defaults.optional("render")) manifest.defaultRender = readGoldenRender(*r);
    if (auto t = defaults.optional("tolerance")) manifest.defaultTolerance = readFrameTolerance(*t);
    if (auto t = defaults.optional("state_tolerance")) manifest.defaultStateTolerance = readStateTolerance(*t);
  }

  std::vector<CheckName> names;
  std::uintmax_t checks = 0;
  for (const bool frames : {true, false}) {
    const std::optional<Value> list = m.optional(frames ? "frames" : "states");
    if (!list) continue;
    for (const Value& item : list->items()) {
      GoldenEntry entry = readGoldenEntry(item, frames, directory, file, names);
      checks += frames ? entry.times.size() : 1;
      if (checks > kMaxGoldenChecks) {
        item.fail(
            fmt::format("more than {} checks (frames' times and states) in one manifest; split it into "
                        "several files",
                        kMaxGoldenChecks));
      }
      (frames ? manifest.frames : manifest.states).push_back(std::move(entry));
    }
  }
  if (manifest.frames.empty() && manifest.states.empty()) {
    top.fail("a manifest with nothing to check: give at least one entry under frames: or states:");
  }
  checkNamesDiffer(names, file);
  return manifest;
}

GoldenManifest loadGoldenManifestFile(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  const std::string text = readScenarioText(file, maxInputMiB);  // any text file, within the limit
  const std::filesystem::path directory = file.parent_path().empty() ? "." : file.parent_path();
  return loadGoldenManifestText(text, file.string(), directory);
}

}  // namespace particles::scenario
