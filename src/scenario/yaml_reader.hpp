#pragma once
// Reading YAML (internal to the scenario loader): a file's one document, and typed, validating
// access to its tree. A Value is a node together with its key path (`forces[2].ks`) and position,
// so that every failure can name the file, line, column and key, and say what was expected and
// what was found.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/kind.hpp"
#include "core/state.hpp"

namespace particles::scenario::detail {

// The one document of a scenario's text, which must not be empty; throws ScenarioError at the
// second document or at a syntax error. Works around yaml-cpp 0.7's LoadAll, which never returns
// on some malformed input (https://github.com/jbeder/yaml-cpp/issues/1040). With `aliases`, sets it to whether
// the document repeats a node by an alias (`*name`): its tree then holds that node at two key paths.
// The document holds at most limit.maxNodes nodes (values, keys and lists; a list's items count
// one each, an alias one): past that, ScenarioError with limit.tooMany at the node that passes,
// before yaml-cpp builds any, in the time of reading up to it and in constant memory.
struct NodeLimit {
  std::uintmax_t maxNodes = 0;
  std::string tooMany;
  // A scenario's, with --limit nodes=N's words (SceneLimits::nodes).
  static NodeLimit scenario(std::uintmax_t maxNodes);
};
// An empty document is refused as "the file is empty; expected " + `expected`.
YAML::Node loadOneDocument(const std::string& text, const std::string& file, bool* aliases, const NodeLimit& limit,
                           std::string_view expected = "a scenario (a map with at least 'name')");
// The same count alone, for text that is parsed otherwise (a --set value): ScenarioError past it.
void checkNodeCount(const std::string& text, const std::string& file, const NodeLimit& limit);

// The most a file read whole may hold, checked before any of its nodes is built (a sweep file, a
// golden manifest): each limit's message is the file's own, since it says how to split the file.
struct ShapeLimits {
  std::uintmax_t maxNodes = 0;      // values, keys and lists in all
  std::uintmax_t maxListItems = 0;  // items of one list
  std::string tooManyNodes;         // the message at the node past maxNodes,
  std::string tooLongList;          // at the list past maxListItems,
  std::string alias;                // at an alias (`*name`),
  std::string secondDocument;       // and at a second document's first node (empty: not read)
};

// The first document of `text` (null when it has none), after its flow lists are counted in the
// text and its nodes on the parser's events: a file past `limits` is refused at the node that
// passes, in constant memory. Throws ScenarioError there, at an alias, at a syntax error, and
// (when limits.secondDocument is given) at a second document.
YAML::Node loadBoundedDocument(std::string_view text, const std::string& file, const ShapeLimits& limits);

// A YAML node as it goes on a command line (--set, a sweep's values): a scalar as written,
// anything else in flow form.
std::string commandLineText(const YAML::Node& node);
// The text of a `--set` value that reads back as `node` (a manifest's or sweep's map of sets): as
// commandLineText, but a scalar quoted in the file whose plain text YAML would read otherwise (a
// colon or a # in it, brackets, nothing) keeps double quotes: "Pendulum: RK4", "#ff0000".
std::string overrideValueText(const YAML::Node& node);

// Where the tree came from: the file, the key paths that --set replaced (errors in those name
// the option instead of a line of the file), and those a style file gave (`render --style`): their
// nodes keep that file's marks, so errors there name it with its own line and column.
struct Source {
  std::string file;
  std::vector<std::pair<std::string, std::string>> overridden;  // canonical key path, origin
  std::vector<std::pair<std::string, std::string>> fromFiles;   // canonical key path, that file
};

class Value {
 public:
  Value(const Source& source, YAML::Node node, std::string path, YAML::Mark fallback);

  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  bool isNull() const { return !node_.IsDefined() || node_.IsNull(); }
  bool isMap() const { return node_.IsMap(); }
  bool isSequence() const { return node_.IsSequence(); }
  bool isScalar() const { return node_.IsScalar(); }
  // Where the value is written: its node's mark, else its key's (null values have no mark).
  YAML::Mark mark() const { return isNull() || node_.Mark().is_null() ? fallback_ : node_.Mark(); }

  // Throws ScenarioError at this value's position and key path.
  [[noreturn]] void fail(const std::string& message) const;
  // "got 'abc'", "got a list", "got a map", "got nothing".
  std::string found() const;

  double number() const;                       // any finite number
  double positive() const;                     // > 0
  double nonNegative() const;                  // ≥ 0
  double inRange(double lo, double hi) const;  // lo ≤ x ≤ hi
  // Any finite number within the bounds (each optional, inclusive or not); the message states
  // the condition as boundsText does.
  double bounded(const std::optional<Bound>& min, const std::optional<Bound>& max) const;
  long long integer(long long lo, long long hi) const;
  bool boolean() const;
  std::string string() const;        // a non-empty scalar
  Vec2 vec2() const;                 // [x, y]
  Vec2 positiveVec2() const;         // [x, y], both > 0
  std::vector<Value> items() const;  // the elements of a sequence (fails otherwise)
  Value item(size_t i) const;
  // Another node of the same tree.
  Value child(YAML::Node node, std::string path, YAML::Mark fallback) const;

 private:
  const Source* source_;
  YAML::Node node_;
  std::string path_;
  YAML::Mark fallback_;  // the key's position: yaml-cpp gives null values no reliable mark
};

// A map with a fixed set of allowed keys. The constructor rejects anything but a map, unknown
// keys (suggesting the closest allowed one) and duplicate keys.
class MapReader {
 public:
  MapReader(const Value& value, std::initializer_list<std::string_view> allowed)
      : MapReader(value, std::vector<std::string_view>(allowed)) {}
  MapReader(const Value& value, const std::vector<std::string_view>& allowed);

  const Value& self() const { return value_; }
  bool has(std::string_view key) const;
  std::optional<Value> optional(std::string_view key) const;  // absent or null: nothing
  Value required(std::string_view key) const;

 private:
  Value value_;
  std::vector<std::pair<std::string, Value>> entries_;
};

std::string formatNumber(double x);  // shortest round-trip form
// "> 0", "≥ 0", "from 0.001 to 1000", "> 0 and ≤ 1": the condition on a bounded number; empty
// when there is none.
std::string boundsText(const std::optional<Bound>& min, const std::optional<Bound>& max);

}  // namespace particles::scenario::detail
