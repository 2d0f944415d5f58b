// A JSON text read within limits, and its values read with checks: see json_reader.hpp.
#include "golden/json_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "golden/report_text.hpp"

namespace particles::golden {

namespace {

// "line 3, column 17" of a byte offset into `text`, counted as nlohmann counts (bytes, lines
// ending in '\n'; both from 1).
std::string lineColumn(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const std::string_view before = text.substr(0, offset);
  const std::size_t lastBreak = before.rfind('\n');
  const std::size_t lineStart = lastBreak == std::string_view::npos ? 0 : lastBreak + 1;
  return fmt::format("line {}, column {}", std::count(before.begin(), before.end(), '\n') + 1, offset - lineStart + 1);
}

// Refuses arrays and objects nested deeper than maxDepth before nlohmann parses the text.
// Its parser keeps its stack on the heap, but what walks a parsed value recurses (dump(): a
// "version" of 200,000 nested arrays overflowed the stack, exit 139). One pass counting brackets
// outside strings: where the text is JSON this is the parser's own depth, and where it is not the
// parser stops at the first mistake, never deeper than the brackets counted up to it.
void checkNesting(std::string_view text, const std::string& file, int maxDepth) {
  int depth = 0;
  bool inString = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > maxDepth) {
        throw std::invalid_argument(fmt::format("{}: {}: arrays and objects nested more than {} deep, the limit", file,
                                                lineColumn(text, i), maxDepth));
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// Where nlohmann's parser stopped, and its message. The message quotes the token it stopped in
// whole ("last read: '…'", "number overflow parsing '…'"): for a string without its closing quote
// that is the rest of the file. Its SAX interface hands that token over apart from the message,
// so a text that failed is read once more, building nothing, to find the token and cut it.
class ParseFailure final : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::size_t position = 0;
  int id = 0;
  std::string message, token;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t at, const std::string& lastToken, const nlohmann::json::exception& e) override {
    position = at;
    id = e.id;
    message = e.what();
    token = lastToken;
    return false;
  }
};

// The message for a text nlohmann::json::parse refused: "FILE: not JSON: parse error at line 1,
// column 13: …", or for a number past a double "FILE: line 1, column 12: number overflow parsing
// '1e500'", the token quoted by at most report::kMaxQuotedBytes.
std::string notJsonMessage(std::string_view text, const std::string& file) {
  ParseFailure failure;
  nlohmann::json::sax_parse(text, &failure);
  std::string what = failure.message;
  // "[json.exception.parse_error.101] parse error at line 1, column 1: …" without its tag.
  if (const std::size_t tag = what.find("] "); what.starts_with("[json.exception.") && tag != std::string::npos) {
    what.erase(0, tag + 2);
  }
  const std::string quotedToken = "'" + failure.token + "'";
  if (const std::size_t at = what.find(quotedToken); at != std::string::npos) {
    what.replace(at, quotedToken.size(), report::quotedExcerpt(failure.token, '\''));
  }
  const bool parseError = failure.id / 100 == 1;  // nlohmann's ids: 1xx parse_error, 4xx out_of_range
  if (parseError) return fmt::format("{}: not JSON: {}", file, what);
  return fmt::format("{}: {}: {}", file, lineColumn(text, failure.position), what);
}

}  // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& file, int maxDepth) {
  checkNesting(text, file, maxDepth);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    // parse_error, or out_of_range for a number past a double (1e500).
    throw std::invalid_argument(notJsonMessage(text, file));
  }
}

std::string valueText(const nlohmann::json& value) {
  if (value.is_string()) return report::quotedExcerpt(value.get_ref<const std::string&>());
  if (value.is_array()) return "an array of " + report::countText(long(value.size()), "value", "values");
  if (value.is_object()) return "an object of " + report::countText(long(value.size()), "key", "keys");
  return value.dump();
}

void JsonAt::fail(std::string_view what) const {
  if (path.empty()) throw std::invalid_argument(fmt::format("{}: {}", file, what));
  throw std::invalid_argument(fmt::format("{}: {}: {}", file, path, what));
}

JsonAt JsonAt::member(std::string_view name) const {
  const auto it = value.find(name);
  if (it == value.end()) fail(fmt::format("has no \"{}\"", name));
  return {*it, path.empty() ? std::string(name) : fmt::format("{}.{}", path, name), file};
}

void JsonAt::requireObject(std::initializer_list<std::string_view> names) const {
  if (!value.is_object()) fail("is not an object");
  for (const auto& [key, ignored] : value.items()) {
    bool known = false;
    for (std::string_view name : names) known = known || key == name;
    if (!known) fail(fmt::format("has an unknown key {}", report::quotedExcerpt(key)));
  }
  for (std::string_view name : names) member(name);
}

std::size_t JsonAt::arraySize() const {
  if (!value.is_array()) fail("is not an array");
  return value.size();
}

JsonAt JsonAt::element(std::size_t i) const {
  return {value[i], fmt::format("{}[{}]", path, i), file};
}

std::string JsonAt::text() const {
  if (!value.is_string()) fail("is not a string");
  return value.get<std::string>();
}

bool JsonAt::boolean() const {
  if (!value.is_boolean()) fail("is not true or false");
  return value.get<bool>();
}

long JsonAt::integer(long low, long high) const {
  if (!value.is_number_integer()) fail("is not an integer");
  const bool fits = !value.is_number_unsigned() ||
                    value.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<std::int64_t>::max());
  if (!fits || value.get<std::int64_t>() < low || value.get<std::int64_t>() > high) {
    fail(fmt::format("is not an integer from {} to {}", low, high));
  }
  return long(value.get<std::int64_t>());
}

double JsonAt::number() const {
  if (value.is_number()) return value.get<double>();
  if (value.is_string()) {
    const std::string s = value.get<std::string>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  fail("is not a number (nor \"nan\", \"inf\" or \"-inf\")");
}

double JsonAt::number(double low, double high) const {
  const double x = number();
  if (!(x >= low && x <= high)) fail(fmt::format("is not a number from {} to {}", low, high));
  return x;
}

}  // namespace particles::golden
