#pragma once
// Internal to the golden room: a JSON text read for results.json (results_json.hpp), within a
// nesting limit, and its values read with checks. Every error is std::invalid_argument naming the
// file and where: "FILE: not JSON: parse error at line 1, column 13: …", "FILE: line 1, column 12:
// number overflow parsing '1e500'", "FILE: frames[3].files.actual: is not a string". Messages quote
// at most report::kMaxQuotedBytes of a value.

#include <cstddef>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace particles::golden {

// The text parsed, once arrays and objects nested deeper than maxDepth are refused (nlohmann's
// parser keeps its stack on the heap, but what walks a parsed value recurses).
nlohmann::json parseJsonText(std::string_view text, const std::string& file, int maxDepth);

// A value as a message names it: a number, true, false or null as written, a string quoted (at
// most report::kMaxQuotedBytes of it), an array or object by its size (its text may be megabytes).
std::string valueText(const nlohmann::json& value);

// A value of the file being read, with its JSON path ("frames[3].files.actual") for messages.
struct JsonAt {
  const nlohmann::json& value;
  std::string path;
  const std::string& file;

  [[noreturn]] void fail(std::string_view what) const;

  // The object's member `name`; the object must have exactly `names` (a misspelt key is an error,
  // not a default).
  JsonAt member(std::string_view name) const;
  void requireObject(std::initializer_list<std::string_view> names) const;
  std::size_t arraySize() const;
  JsonAt element(std::size_t i) const;

  std::string text() const;
  bool boolean() const;
  long integer(long low = 0, long high = std::numeric_limits<long>::max()) const;
  // A number, or the strings "nan", "inf" and "-inf" (results.json's numbers that are not finite).
  double number() const;
  double number(double low, double high) const;
};

}  // namespace particles::golden
