// Reading a sweep file (sweep_spec.hpp): the keys, their types and the checks that can be made
// before any scenario is opened. Checks against the scenarios (does a --set key exist, is a value
// valid there) and against the command's options are the program's, which knows both.
#include "scenario/sweep_spec.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>

#include "input/printable_text.hpp"
#include "core/integrators.hpp"
#include "scenario/scenario.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

using detail::MapReader;
using detail::Value;

SweepPosition positionOf(const Value& v) {
  const YAML::Mark m = v.mark();
  if (m.is_null()) return {0, 0, v.path()};
  return {m.line + 1, m.column + 1, v.path()};
}

std::optional<double> numberOf(const YAML::Node& node) {
  double x = 0.0;
  if (node.IsScalar() && node.Tag() != "!" && YAML::convert<double>::decode(node, x) && std::isfinite(x)) return x;
  return std::nullopt;
}

// A number of a range, rounded to 12 significant digits so that 0.1 + 2 × 0.1 is written 0.3
// (a subnormal number, which the rounded text may not read back as, stays as it is).
double tidy(double x) {
  const std::string text = fmt::format("{:.12g}", x);
  double rounded = x;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), rounded);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(rounded) ? rounded : x;
}

std::vector<SweepValue> readRange(const Value& v, bool& logSpacing) {
  const MapReader r(v, {"from", "to", "count", "spacing"});
  const double from = r.required("from").number();
  const double to = r.required("to").number();
  const long long count = r.required("count").integer(1, static_cast<long long>(kMaxSweepJobs));
  std::string spacing = "linear";
  if (auto s = r.optional("spacing")) {
    spacing = s->string();
    if (spacing != "linear" && spacing != "log")
      s->fail(fmt::format("expected linear or log, got {}", input::quotedValue(spacing)));
  }
  logSpacing = spacing == "log";
  if (logSpacing && !(from > 0 && to > 0)) {
    v.fail(fmt::format("a log range needs from > 0 and to > 0, got from {} to {}", detail::formatNumber(from),
                       detail::formatNumber(to)));
  }
  if (count == 1 && from != to) v.fail("a range of one value needs from = to");
  std::vector<SweepValue> values;
  for (long long i = 0; i < count; ++i) {
    const double f = count == 1 ? 0.0 : double(i) / double(count - 1);
    double x = logSpacing ? from * std::pow(to / from, f) : from + (to - from) * f;
    if (i == count - 1) x = to;
    x = tidy(x);
    values.push_back({detail::formatNumber(x), x, positionOf(v)});
  }
  return values;
}

SweepParameter readParameter(const Value& v, std::vector<std::string>& names) {
  const MapReader m(v, {"key", "name", "values", "range", "scale"});
  SweepParameter p;
  p.at = positionOf(v);
  const Value key = m.required("key");
  p.key = key.string();
  if (p.key.find('=') != std::string::npos || p.key.find(' ') != std::string::npos) {
    key.fail(
        fmt::format("expected a key path such as simulation.dt or forces[1].ks, got {}", input::quotedValue(p.key)));
  }
  if (auto s = m.optional("scale")) p.scale = s->boolean();
  const auto values = m.optional("values");
  const auto range = m.optional("range");
  if (values && range) v.fail("give either 'values' or 'range', not both");
  if (!values && !range) v.fail("missing 'values' (a list) or 'range' ({from, to, count, spacing})");
  if (values) {
    const std::vector<Value> items = values->items();
    if (items.empty()) values->fail("an empty list: a parameter needs at least one value");
    for (const Value& item : items) {
      if (item.isNull()) item.fail("expected a value, got nothing");
      if (item.isMap()) item.fail("expected a value (a number, a name or a list), got a map");
      p.values.push_back({detail::commandLineText(item.node()), numberOf(item.node()), positionOf(item)});
    }
  } else {
    p.values = readRange(*range, p.logSpacing);
  }

  const bool shorthand = p.key == "integrator" || p.key == "dt" || p.key == "duration";
  for (size_t i = 0; i < p.values.size(); ++i) {
    const SweepValue& value = p.values[i];
    const Value at = values ? values->item(i) : *range;
    if (p.scale && !value.number)
      at.fail(fmt::format("a scale factor must be a number, got {}", input::quotedValue(value.text)));
    if (p.key == "integrator") {
      if (!integratorFromName(value.text)) {
        std::vector<std::string> known;
        for (Integrator k : allIntegrators()) known.emplace_back(integratorName(k));
        at.fail(fmt::format("unknown integrator {} (expected one of {})", input::quotedValue(value.text),
                            fmt::join(known, ", ")));
      }
    } else if (shorthand && !p.scale && !(value.number && *value.number > 0)) {
      at.fail(fmt::format("{} must be a number of seconds > 0, got {}", p.key, input::quotedValue(value.text)));
    }
  }
  if (p.scale && p.key == "integrator") v.fail("an integrator cannot be scaled");

  p.name = p.key;
  if (p.scale) p.name += " scale";
  if (auto n = m.optional("name")) p.name = n->string();
  if (p.name.find_first_of(",\"\n\r") != std::string::npos) {
    (m.optional("name") ? *m.optional("name") : key).fail("a parameter's name is a CSV column: no commas or quotes");
  }
  if (std::find(std::begin(kReservedColumns), std::end(kReservedColumns), p.name) != std::end(kReservedColumns)) {
    (m.optional("name") ? *m.optional("name") : key)
        .fail(fmt::format("{} names a column the sweep writes itself ({}); give the parameter another 'name'",
                          input::quotedValue(p.name), fmt::join(kReservedColumns, ", ")));
  }
  if (std::find(names.begin(), names.end(), p.name) != names.end()) {
    (m.optional("name") ? *m.optional("name") : key)
        .fail(fmt::format("a second parameter named {} (give each a different 'name')", input::quotedValue(p.name)));
  }
  names.push_back(p.name);
  return p;
}

std::string canonicalKey(const std::string& key) {
  return key == "dt" || key == "duration" || key == "integrator" ? "simulation." + key : key;
}

std::vector<SweepGroup> readParameters(const Value& v,
                                       const std::function<void(const std::vector<SweepGroup>&)>& checkCount) {
  std::vector<SweepGroup> groups;
  std::vector<std::string> names, keys;
  // The same key varied twice would give one job two values for it.
  auto add = [&](SweepGroup& g, const Value& item) {
    SweepParameter p = readParameter(item, names);
    const std::string key = canonicalKey(p.key);
    if (std::find(keys.begin(), keys.end(), key) != keys.end()) {
      item.fail(fmt::format("{} is varied twice (directly or through its shorthand)", input::quotedValue(key)));
    }
    keys.push_back(key);
    g.parameters.push_back(std::move(p));
  };
  const std::vector<Value> items = v.items();
  if (items.empty()) v.fail("an empty list: give at least one parameter, or leave 'parameters' out");
  for (const Value& item : items) {
    SweepGroup g;
    g.at = positionOf(item);
    if (item.isMap() && item.node()["zip"].IsDefined()) {
      const MapReader z(item, {"zip"});
      const Value list = z.required("zip");
      const std::vector<Value> members = list.items();
      if (members.empty()) list.fail("an empty list: a zip needs at least one parameter");
      g.zipped = true;
      for (const Value& member : members) add(g, member);
      for (size_t k = 1; k < g.parameters.size(); ++k) {
        if (g.parameters[k].values.size() != g.parameters[0].values.size()) {
          members[k].fail(
              fmt::format("zipped parameters take one value each per job, so they need lists of one "
                          "length: {} has {}, {} has {}",
                          input::quotedValue(g.parameters[0].name), g.parameters[0].values.size(),
                          input::quotedValue(g.parameters[k].name), g.parameters[k].values.size()));
        }
      }
    } else {
      add(g, item);
    }
    groups.push_back(std::move(g));
    checkCount(groups);
  }
  return groups;
}

// Options the sweep writes itself into every job: giving them in `options` is a mistake.
constexpr std::string_view kSweepOwnedOptions[] = {"o",      "output", "stats",  "trace", "csv",     "plot",
                                                   "record", "force",  "frames", "at",    "scenario"};

void readOptions(const Value& v, SweepSpec& spec) {
  if (!v.isMap()) v.fail(fmt::format("expected a map of the command's options, {}", v.found()));
  std::vector<std::string> seen;
  for (auto it = v.node().begin(); it != v.node().end(); ++it) {
    const YAML::Node keyNode = it->first;
    const std::string name = keyNode.IsScalar() ? keyNode.Scalar() : "?";
    const std::string path = v.path() + "." + name;
    const Value key = v.child(keyNode, path, keyNode.Mark());
    const Value value = v.child(it->second, path, keyNode.Mark());
    if (!keyNode.IsScalar()) key.fail("expected an option name, got a list or map as key");
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      key.fail(fmt::format("duplicate key {}", input::quotedValue(name)));
    seen.push_back(name);
    const std::string bare =
        name.substr(name.find_first_not_of('-') == std::string::npos ? 0 : name.find_first_not_of('-'));
    if (std::find(std::begin(kSweepOwnedOptions), std::end(kSweepOwnedOptions), bare) != std::end(kSweepOwnedOptions)) {
      key.fail(fmt::format("{} is set by the sweep for each job (its outputs go under the output folder)",
                           input::quotedValue(bare)));
    }
    if (bare == "set" || value.isMap()) {
      if (bare != "set") value.fail("expected a value or a list, got a map");
      if (!value.isMap()) value.fail(fmt::format("expected a map of key paths and values, {}", value.found()));
      for (auto s = value.node().begin(); s != value.node().end(); ++s) {
        const Value setValue = value.child(s->second, path + "." + s->first.Scalar(), s->first.Mark());
        if (setValue.isNull() || setValue.isMap()) setValue.fail("expected a value for --set, got nothing or a map");
        spec.sets.emplace_back(s->first.Scalar(), detail::overrideValueText(s->second));
        spec.setsAt.push_back(positionOf(setValue));
      }
      continue;
    }
    SweepOption o{bare, "", false, positionOf(key)};
    if (value.isNull()) value.fail(fmt::format("{} needs a value (write true for a flag)", input::quotedValue(name)));
    if (value.isSequence()) {
      std::vector<std::string> parts;
      for (const Value& item : value.items()) {
        if (!item.isScalar()) item.fail("expected a list of values, got a nested list or map");
        parts.push_back(item.node().Scalar());
      }
      if (parts.empty()) value.fail("an empty list");
      o.value = fmt::format("{}", fmt::join(parts, ","));
    } else if (value.node().Tag() != "!" && (value.node().Scalar() == "true" || value.node().Scalar() == "false")) {
      if (value.node().Scalar() == "false") continue;  // a flag left off
      o.flag = true;
    } else {
      o.value = value.node().Scalar();
    }
    spec.options.push_back(std::move(o));
  }
}

// The jobs made by the scenarios, the split and `groups`, counted without overflow: stop as soon
// as the product passes the limit. Checked after each group is read, so a file with too many jobs
// is refused before the rest of its values are built.
void checkJobCount(const SweepSpec& spec, const std::vector<SweepGroup>& groups) {
  std::uintmax_t jobs = spec.scenarios.size() * std::uintmax_t(spec.split);
  std::vector<std::string> factors = {
      fmt::format("{} scenario{}", spec.scenarios.size(), spec.scenarios.size() == 1 ? "" : "s")};
  for (const SweepGroup& g : groups) {
    factors.push_back(fmt::format("{}", g.size()));
    jobs = jobs > kMaxSweepJobs ? jobs : jobs * g.size();
  }
  if (spec.split > 1) factors.push_back(fmt::format("{} segments", spec.split));
  if (jobs > kMaxSweepJobs) {
    failInSweep(spec, spec.parametersAt,
                fmt::format("{} make more than {} jobs; split the sweep into several files", fmt::join(factors, " × "),
                            kMaxSweepJobs));
  }
}

}  // namespace

std::uintmax_t SweepSpec::combinations() const {
  std::uintmax_t n = scenarios.size();
  for (const SweepGroup& g : groups) n *= g.size();
  return n;
}

void failInSweep(const SweepSpec& spec, const SweepPosition& at, const std::string& message) {
  throw ScenarioError(spec.file, at.line, at.column, at.keyPath, message);
}

SweepSpec loadSweepText(std::string_view text, const std::string& file) {
  // One parameter with more than kMaxSweepJobs values makes more jobs than any sweep may.
  const YAML::Node root = detail::loadBoundedDocument(
      text, file,
      {.maxNodes = kMaxSweepNodes,
       .maxListItems = kMaxSweepJobs,
       .tooManyNodes = fmt::format(
           "more than {} values, keys and lists in one sweep file; split the sweep into several files", kMaxSweepNodes),
       .tooLongList = fmt::format("a list of more than {} items: a sweep makes at most {} jobs, so no list needs "
                                  "more; split the sweep into several files",
                                  kMaxSweepJobs, kMaxSweepJobs),
       .alias = "an alias (*name): a sweep file writes each value out; anchors and aliases are not read here",
       .secondDocument = {}});  // not read
  if (!root.IsDefined() || root.IsNull()) {
    throw ScenarioError(file, 1, 1, "", "the file is empty; expected a sweep (a map with scenarios and command)");
  }
  const detail::Source source{file, {}, {}};
  const Value top(source, root, "", root.Mark());
  const MapReader m(top, {"name", "scenarios", "command", "options", "parameters", "split", "slurm"});

  SweepSpec spec;
  spec.file = file;
  spec.name = std::filesystem::path(file).stem().string();
  if (auto n = m.optional("name")) {
    spec.name = n->string();
    if (spec.name.find_first_of("/\\ \t\n") != std::string::npos)
      n->fail("a name is used in file names: no slashes or spaces");
  }

  const Value scenarios = m.required("scenarios");
  const std::vector<Value> scenarioItems = scenarios.isScalar() ? std::vector<Value>{scenarios} : scenarios.items();
  if (scenarioItems.empty()) scenarios.fail("an empty list: name at least one scenario file");
  const std::filesystem::path folder = std::filesystem::path(file).parent_path();
  for (const Value& s : scenarioItems) {
    const std::filesystem::path given = s.string();
    spec.scenarios.push_back({given.string(), given.is_absolute() ? given : folder / given, positionOf(s)});
  }

  const Value command = m.required("command");
  spec.command = command.string();
  spec.commandAt = positionOf(command);
  if (spec.command != "run" && spec.command != "render" && spec.command != "stability") {
    command.fail(fmt::format("expected run, render or stability, got {}", input::quotedValue(spec.command)));
  }
  if (auto o = m.optional("options")) readOptions(*o, spec);

  if (auto s = m.optional("split")) {
    spec.split = int(s->integer(1, 1000));
    spec.splitAt = positionOf(*s);
    if (spec.command != "render" && spec.split > 1) s->fail("only a render can be split into segments");
  }

  if (auto p = m.optional("parameters")) {
    spec.parametersAt = positionOf(*p);
    spec.groups = readParameters(*p, [&](const std::vector<SweepGroup>& groups) { checkJobCount(spec, groups); });
  } else {
    spec.parametersAt = positionOf(top);
  }
  if (auto s = m.optional("slurm")) {
    for (const Value& line : s->items()) {
      const std::string option = line.string();
      const bool control = std::any_of(option.begin(), option.end(),
                                       [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
      if (option.rfind("--", 0) != 0 || control) {
        line.fail(fmt::format("expected an sbatch option such as --time=00:10:00, got {}", input::quotedValue(option)));
      }
      spec.slurm.push_back(option);
    }
  }

  checkJobCount(spec, spec.groups);
  return spec;
}

SweepSpec loadSweepFile(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  const std::string text = readScenarioText(file, maxInputMiB);  // any text file, within the limit
  return loadSweepText(text, file.string());
}

}  // namespace particles::scenario
