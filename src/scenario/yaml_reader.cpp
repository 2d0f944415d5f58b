#include "scenario/yaml_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "input/printable_text.hpp"
#include "input/closest_name.hpp"
#include "scenario/scenario_error.hpp"

namespace particles::scenario::detail {

namespace {

// yaml-cpp tags a quoted scalar "!" and a plain one "?": `mass: "1"` is a string, not a number.
bool isQuoted(const YAML::Node& node) {
  return node.Tag() == "!";
}

bool startsWithPath(const std::string& path, const std::string& prefix) {
  if (path.size() < prefix.size() || path.compare(0, prefix.size(), prefix) != 0) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}

// Where each document's first node starts, for the first two documents at most; and the nodes,
// counted as the parser reports them, refused past `limits` (NodeLimit) at the node that passes,
// before yaml-cpp builds any (about 900 bytes each).
class DocumentMarks final : public YAML::EventHandler {
 public:
  DocumentMarks(const std::string& file, const NodeLimit& limit) : file_(file), limit_(limit) {}
  std::vector<YAML::Mark> starts;
  bool aliases = false;  // whether a node is repeated by an alias (`*name`)

  void OnDocumentStart(const YAML::Mark&) override { wanted_ = true; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { node(m); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override {
    aliases = true;
    node(m);
  }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t, const std::string&) override { node(m); }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(m);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(m);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& m) {
    if (wanted_) starts.push_back(m);
    wanted_ = false;
    if (++nodes_ > limit_.maxNodes) throw ScenarioError(file_, m.line + 1, m.column + 1, "", limit_.tooMany);
  }
  bool wanted_ = false;
  const std::string& file_;
  const NodeLimit& limit_;
  std::uintmax_t nodes_ = 0;
};

// yaml-cpp's scanner keeps every token of a flow list (`[1, 2, 3]`) until the list ends, ~380
// bytes each, so a 2 MB line of 10⁶ values took 380 MB before the first event. This lexical pass
// counts the items of flow lists first, in constant memory: it follows quotes, comments and
// brackets only as far as needed to count commas at flow depth, and refuses a list with more
// than `maxItems` items at its opening bracket. (An unusual file may be counted high, never
// low: the exact count is ShapeCheck's, on the parser's events.)
void checkFlowListLengths(std::string_view text, const std::string& file, const ShapeLimits& limits) {
  struct Flow {
    int line, column;
    std::uintmax_t commas;
  };
  std::vector<Flow> open;
  int line = 1, column = 0;
  char quote = 0;
  char before = '\n';  // the last character that is not a space or tab
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
    if (quote) {
      if (quote == '"' && c == '\\') {
        ++i;
        ++column;
      } else if (c == quote) {
        if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
          ++i;
          ++column;
        } else {
          quote = 0;
          before = c;
        }
      }
      continue;
    }
    const bool startsNode = std::string_view("\n[{,:-?").find(before) != std::string_view::npos;
    if (c == '#' && (column == 1 || text[i - 1] == ' ' || text[i - 1] == '\t')) {
      const size_t end = text.find('\n', i);
      if (end == std::string_view::npos) break;
      i = end - 1;
      continue;
    }
    if ((c == '\'' || c == '"') && startsNode) {
      quote = c;
    } else if ((c == '[' || c == '{') && (startsNode || !open.empty())) {
      open.push_back({line, column, 0});
    } else if ((c == ']' || c == '}') && !open.empty()) {
      open.pop_back();
    } else if (c == ',' && !open.empty() && ++open.back().commas >= limits.maxListItems) {
      throw ScenarioError(file, open.back().line, open.back().column, "", limits.tooLongList);
    }
    if (c != ' ' && c != '\t') before = c;
  }
}

// The shape of a file, checked on the parser's events before any node is built: no list longer
// than limits.maxListItems, at most limits.maxNodes nodes in all, and no aliases (`*name` repeats
// a node as often as it is written, so a small file could stand for any number of values). A file
// past these is refused at the node that passes, in the time of reading up to it and in constant
// memory, where building its nodes first took a second and ~900 bytes per value. With
// limits.secondDocument, a second document is refused at its first node.
class ShapeCheck final : public YAML::EventHandler {
 public:
  ShapeCheck(const std::string& file, const ShapeLimits& limits) : file_(file), limits_(limits) {}

  void OnDocumentStart(const YAML::Mark&) override { ++documents_; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { node(m); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override {
    if (documents_ > 1) node(m);  // the second document's message first
    fail(m, limits_.alias);
  }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t, const std::string&) override { node(m); }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(m);
    open_.push_back({m, 0, true});
  }
  void OnSequenceEnd() override { open_.pop_back(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(m);
    open_.push_back({m, 0, false});
  }
  void OnMapEnd() override { open_.pop_back(); }

 private:
  struct Open {
    YAML::Mark at;
    std::uintmax_t items;
    bool sequence;
  };
  [[noreturn]] void fail(const YAML::Mark& m, const std::string& message) const {
    throw ScenarioError(file_, m.line + 1, m.column + 1, "", message);
  }
  void node(const YAML::Mark& m) {
    if (documents_ > 1) {
      // yaml-cpp 0.7 reports document after document at a lone ',' without reading on (as in
      // loadOneDocument): a second document that starts where the first did is a syntax error.
      const bool movedOn = !first_ || m.pos > first_->pos;
      fail(m,
           movedOn ? limits_.secondDocument : "YAML syntax error: cannot read on from here (a stray ',' or bracket?)");
    }
    if (!first_) first_ = m;
    if (++nodes_ > limits_.maxNodes) fail(m, limits_.tooManyNodes);
    if (!open_.empty() && open_.back().sequence && ++open_.back().items > limits_.maxListItems) {
      fail(open_.back().at, limits_.tooLongList);
    }
  }

  const std::string& file_;
  const ShapeLimits& limits_;
  int documents_ = 0;
  std::optional<YAML::Mark> first_;  // the first document's first node
  std::uintmax_t nodes_ = 0;
  std::vector<Open> open_;
};

}  // namespace

// The file's one document. yaml-cpp 0.7's LoadAll never returns on some malformed input (a lone
// ',': the parser reports document after document without reading on,
// https://github.com/jbeder/yaml-cpp/issues/1040), so the documents are counted through the event parser, two at
// most, and the first is loaded alone.
NodeLimit NodeLimit::scenario(std::uintmax_t maxNodes) {
  return {maxNodes, fmt::format("more than {} values, keys and lists (YAML nodes) in one scenario; a large system is "
                                "a grid, not a list of its points, or raise the limit with --limit nodes=N",
                                maxNodes)};
}

namespace {

// The flow lists' count before the parser's (checkFlowListLengths) for a NodeLimit: no list has
// more items than the document has nodes.
ShapeLimits flowLimits(const NodeLimit& limit) {
  ShapeLimits flow;
  flow.maxListItems = limit.maxNodes;
  flow.tooLongList = limit.tooMany;
  return flow;
}

// The first two documents' starts in `text`, its nodes counted against `limit` on the way (the
// flow lists' items first, in the text: yaml-cpp's scanner holds a flow list's tokens until the
// list ends).
DocumentMarks markedDocuments(const std::string& text, const std::string& file, const NodeLimit& limit) {
  checkFlowListLengths(text, file, flowLimits(limit));
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentMarks marks(file, limit);
  for (int i = 0; i < 2 && parser.HandleNextDocument(marks); ++i) {
  }
  return marks;
}

}  // namespace

void checkNodeCount(const std::string& text, const std::string& file, const NodeLimit& limit) {
  try {
    markedDocuments(text, file, limit);
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(file, e.mark.line + 1, e.mark.column + 1, "", fmt::format("YAML syntax error: {}", e.msg));
  }
}

YAML::Node loadOneDocument(const std::string& text, const std::string& file, bool* aliases, const NodeLimit& limit,
                           std::string_view expected) {
  try {
    const DocumentMarks marks = markedDocuments(text, file, limit);
    if (marks.starts.size() > 1) {
      const YAML::Mark first = marks.starts[0], second = marks.starts[1];
      const bool movedOn = second.pos > first.pos;
      throw ScenarioError(file, second.line + 1, second.column + 1, "",
                          movedOn ? "the file holds more than one YAML document; expected one scenario"
                                  : "YAML syntax error: cannot read on from here (a stray ',' or bracket?)");
    }
    if (aliases) *aliases = marks.aliases;
    YAML::Node root = YAML::Load(text);
    if (marks.starts.empty() || root.IsNull()) {
      throw ScenarioError(file, 1, 1, "", fmt::format("the file is empty; expected {}", expected));
    }
    return root;
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(file, e.mark.line + 1, e.mark.column + 1, "", fmt::format("YAML syntax error: {}", e.msg));
  } catch (const YAML::Exception& e) {
    throw ScenarioError(file, 0, 0, "", fmt::format("cannot read YAML: {}", e.msg));
  }
}

YAML::Node loadBoundedDocument(std::string_view text, const std::string& file, const ShapeLimits& limits) {
  try {
    checkFlowListLengths(text, file, limits);
    const std::string whole(text);
    {
      std::istringstream in(whole);
      YAML::Parser parser(in);
      ShapeCheck shape(file, limits);
      parser.HandleNextDocument(shape);
      if (!limits.secondDocument.empty()) parser.HandleNextDocument(shape);
    }
    return YAML::Load(whole);
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(file, e.mark.line + 1, e.mark.column + 1, "", fmt::format("YAML syntax error: {}", e.msg));
  } catch (const YAML::Exception& e) {
    throw ScenarioError(file, 0, 0, "", fmt::format("cannot read YAML: {}", e.msg));
  }
}

std::string commandLineText(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

std::string overrideValueText(const YAML::Node& node) {
  if (!node.IsScalar() || node.Tag() != "!") return commandLineText(node);  // "!": quoted in the file
  const std::string& text = node.Scalar();
  bool readsBack = false;
  try {
    const YAML::Node plain = YAML::Load(text);
    readsBack = !text.empty() && plain.IsScalar() && plain.Scalar() == text;
  } catch (const YAML::Exception&) {
  }
  if (readsBack) return text;
  YAML::Emitter out;
  out << YAML::DoubleQuoted << text;
  return out.c_str();
}

std::string formatNumber(double x) {
  return fmt::format("{}", x);
}

Value::Value(const Source& source, YAML::Node node, std::string path, YAML::Mark fallback)
    : source_(&source), node_(std::move(node)), path_(std::move(path)), fallback_(fallback) {}

void Value::fail(const std::string& message) const {
  for (const auto& [overridden, origin] : source_->overridden) {
    if (startsWithPath(path_, overridden)) throw ScenarioError(source_->file, 0, 0, path_, message, origin);
  }
  std::string file = source_->file;
  for (const auto& [given, otherFile] : source_->fromFiles) {
    if (startsWithPath(path_, given)) file = otherFile;
  }
  YAML::Mark mark = fallback_;
  if (!isNull() && !node_.Mark().is_null()) mark = node_.Mark();
  if (mark.is_null()) throw ScenarioError(file, 0, 0, path_, message);
  throw ScenarioError(file, mark.line + 1, mark.column + 1, path_, message);
}

std::string Value::found() const {
  if (isNull()) return "got nothing";
  if (isMap()) return "got a map";
  if (isSequence()) return fmt::format("got a list of {}", node_.size());
  return fmt::format("got {}", input::quotedValue(node_.Scalar()));
}

double Value::number() const {
  if (isScalar() && !isQuoted(node_)) {
    double x = 0.0;
    if (YAML::convert<double>::decode(node_, x)) {
      if (!std::isfinite(x)) fail(fmt::format("expected a finite number, {}", found()));
      return x;
    }
  }
  fail(fmt::format("expected a number, {}", found()));
}

double Value::positive() const { return bounded(Bound{0.0, false}, std::nullopt); }

double Value::nonNegative() const { return bounded(Bound{0.0, true}, std::nullopt); }

double Value::inRange(double lo, double hi) const { return bounded(Bound{lo, true}, Bound{hi, true}); }

double Value::bounded(const std::optional<Bound>& min, const std::optional<Bound>& max) const {
  const double x = number();
  const bool aboveMin = !min || (min->inclusive ? x >= min->value : x > min->value);
  const bool belowMax = !max || (max->inclusive ? x <= max->value : x < max->value);
  if (!aboveMin || !belowMax) fail(fmt::format("expected a number {}, got {}", boundsText(min, max), formatNumber(x)));
  return x;
}

std::string boundsText(const std::optional<Bound>& min, const std::optional<Bound>& max) {
  if (min && max && min->inclusive && max->inclusive) {
    return fmt::format("from {} to {}", formatNumber(min->value), formatNumber(max->value));
  }
  std::string text;
  if (min) text = fmt::format("{} {}", min->inclusive ? "≥" : ">", formatNumber(min->value));
  if (max) text += fmt::format("{}{} {}", text.empty() ? "" : " and ", max->inclusive ? "≤" : "<", formatNumber(max->value));
  return text;
}

long long Value::integer(long long lo, long long hi) const {
  long long n = 0;
  if (!isScalar() || isQuoted(node_) || !YAML::convert<long long>::decode(node_, n)) {
    fail(fmt::format("expected a whole number, {}", found()));
  }
  if (n < lo || n > hi) fail(fmt::format("expected a whole number from {} to {}, got {}", lo, hi, n));
  return n;
}

bool Value::boolean() const {
  bool b = false;
  if (!isScalar() || isQuoted(node_) || !YAML::convert<bool>::decode(node_, b)) {
    fail(fmt::format("expected true or false, {}", found()));
  }
  return b;
}

std::string Value::string() const {
  if (!isScalar() || node_.Scalar().empty()) fail(fmt::format("expected a text, {}", found()));
  return node_.Scalar();
}

Vec2 Value::vec2() const {
  if (!isSequence() || node_.size() != 2) fail(fmt::format("expected a pair [x, y], {}", found()));
  return {item(0).number(), item(1).number()};
}

Vec2 Value::positiveVec2() const {
  if (!isSequence() || node_.size() != 2) fail(fmt::format("expected a pair [x, y], {}", found()));
  return {item(0).positive(), item(1).positive()};
}

std::vector<Value> Value::items() const {
  if (!isSequence()) fail(fmt::format("expected a list, {}", found()));
  std::vector<Value> out;
  for (size_t i = 0; i < node_.size(); ++i) out.push_back(item(i));
  return out;
}

Value Value::item(size_t i) const {
  const YAML::Mark mark = node_.Mark().is_null() ? fallback_ : node_.Mark();
  return child(node_[i], fmt::format("{}[{}]", path_, i), mark);
}

Value Value::child(YAML::Node node, std::string path, YAML::Mark fallback) const {
  return Value(*source_, std::move(node), std::move(path), fallback);
}

MapReader::MapReader(const Value& value, const std::vector<std::string_view>& allowed) : value_(value) {
  if (!value.isMap()) value.fail(fmt::format("expected a map of keys, {}", value.found()));
  std::vector<std::string> allowedNames(allowed.begin(), allowed.end());
  const std::string prefix = value.path().empty() ? "" : value.path() + ".";
  for (auto it = value.node().begin(); it != value.node().end(); ++it) {
    const YAML::Node key = it->first;
    const std::string name = key.IsScalar() ? key.Scalar() : std::string("?");
    const Value keyValue = value.child(key, prefix + name, key.Mark());
    Value entry = value.child(it->second, prefix + name, key.Mark());
    if (!key.IsScalar()) keyValue.fail("expected a key name, got a list or map as key");
    if (std::find(allowedNames.begin(), allowedNames.end(), name) == allowedNames.end()) {
      const std::string suggestion = input::closestName(name, allowedNames);
      std::string message = fmt::format("unknown key {}", input::quotedValue(name));
      if (!suggestion.empty()) message += fmt::format("; did you mean {}?", input::quotedValue(suggestion));
      message += fmt::format(" (valid keys here: {})", fmt::join(allowedNames, ", "));
      keyValue.fail(message);
    }
    for (const auto& [seen, seenValue] : entries_) {
      if (seen == name) keyValue.fail(fmt::format("duplicate key {}", input::quotedValue(name)));
    }
    entries_.emplace_back(name, std::move(entry));
  }
}

bool MapReader::has(std::string_view key) const {
  return std::any_of(entries_.begin(), entries_.end(),
                     [&](const auto& e) { return e.first == key && !e.second.isNull(); });
}

std::optional<Value> MapReader::optional(std::string_view key) const {
  for (const auto& [name, v] : entries_) {
    if (name == key && !v.isNull()) return v;
  }
  return std::nullopt;
}

Value MapReader::required(std::string_view key) const {
  for (const auto& [name, v] : entries_) {
    if (name == key) {
      if (v.isNull()) v.fail(fmt::format("{} needs a value", input::quotedValue(key)));
      return v;
    }
  }
  const std::string path = value_.path().empty() ? std::string(key) : value_.path() + "." + std::string(key);
  value_.child(value_.node(), path, YAML::Mark::null_mark())
      .fail(fmt::format("missing required key {}", input::quotedValue(key)));
}

}  // namespace particles::scenario::detail
