// The house's sizes: no C++ file of the project is longer than 500 lines and no function longer
// than 100, so that a newcomer can hold a file, and a function, in their head. A file that grows
// past the limit is split by meaning (a file pair per concept), not cut at line 500; a function,
// into its stages.
//
// Exempt from the file limit: the test files (tests/test_*.cpp, one file per area, where an area's
// cases are read one at a time) and the benchmarks (bench/). Every function is held to its limit,
// tests and benchmarks included.
//
// A function's length runs from the first line of its declaration (its template line, if any) to
// its closing brace. Functions are found by a brace-matching scanner (houseFunctions) that skips
// comments, string and character literals (raw strings included) and preprocessor lines, and takes
// a `{` at namespace or class scope after a parameter list (with its qualifiers, trailing return
// type or a constructor's initialiser list) as a function's body; lambdas and local classes inside
// a function count toward it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr int kMaxHouseFileLines = 500;
constexpr int kMaxHouseFunctionLines = 100;

const fs::path kHouseCheckout = PARTICLES_SOURCE_DIR;

struct HouseFunction {
  std::string name;
  int firstLine = 0;  // of its declaration
  int lastLine = 0;   // of its closing brace
  int lines() const { return lastLine - firstLine + 1; }
};

bool isIdentifierChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// The position after the literal that opens at `at` and ends with `close` (a string's '"', a
// character's '\''), skipping escapes; a line break ends an unterminated one.
std::size_t houseLiteralEnd(std::string_view text, std::size_t at, char close) {
  std::size_t j = at + 1;
  while (j < text.size() && text[j] != close && text[j] != '\n') j += text[j] == '\\' ? 2 : 1;
  return std::min(j + 1, text.size());
}

// The position after the preprocessor line starting at `at`: to the end of the line, with its
// continuations and any block comment in it.
std::size_t houseDirectiveEnd(std::string_view text, std::size_t at) {
  std::size_t j = at;
  while (j < text.size() && text[j] != '\n') {
    if (text[j] == '\\' && j + 1 < text.size() && text[j + 1] == '\n') {
      j += 2;
    } else if (text.substr(j, 2) == "/*") {
      const std::size_t end = text.find("*/", j + 2);
      j = end == std::string_view::npos ? text.size() : end + 2;
    } else {
      ++j;
    }
  }
  return j;
}

// A '\'' that separates a number's digits (1'000'000, 0xFF'FF), not a character literal's quote.
bool isDigitSeparator(std::string_view text, std::size_t at) {
  if (at == 0 || !isIdentifierChar(text[at - 1])) return false;
  std::size_t start = at;
  while (start > 0 && (isIdentifierChar(text[start - 1]) || text[start - 1] == '\'' || text[start - 1] == '.')) --start;
  return std::isdigit(static_cast<unsigned char>(text[start])) != 0;
}

// The text with comments, string and character literals and preprocessor lines blanked (each of
// their characters a space, line breaks kept): what is left is code, at the same positions.
std::string houseCodeOnly(std::string_view text) {
  std::string code(text);
  const auto blank = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k) {
      if (code[k] != '\n') code[k] = ' ';
    }
  };
  bool lineStart = true;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    std::size_t end = i + 1;
    if (c == '\n' || (lineStart && (c == ' ' || c == '\t'))) {
      lineStart = c == '\n' || lineStart;
      ++i;
      continue;
    }
    const bool directive = lineStart && c == '#';
    lineStart = false;
    if (directive) {
      end = houseDirectiveEnd(text, i);
    } else if (text.substr(i, 2) == "//") {
      end = std::min(text.find('\n', i), text.size());
    } else if (text.substr(i, 2) == "/*") {
      const std::size_t close = text.find("*/", i + 2);
      end = close == std::string_view::npos ? text.size() : close + 2;
    } else if (c == '"') {
      std::size_t prefix = i;
      while (prefix > 0 && isIdentifierChar(text[prefix - 1])) --prefix;
      const std::string_view p = text.substr(prefix, i - prefix);
      if (p == "R" || p == "u8R" || p == "uR" || p == "UR" || p == "LR") {
        const std::size_t open = std::min(text.find('(', i), text.size());
        const std::string close = ")" + std::string(text.substr(i + 1, open - i - 1)) + "\"";
        const std::size_t at = text.find(close, open);
        end = at == std::string_view::npos ? text.size() : at + close.size();
      } else {
        end = houseLiteralEnd(text, i, '"');
      }
    } else if (c == '\'' && !isDigitSeparator(text, i)) {
      end = houseLiteralEnd(text, i, '\'');
    } else {
      ++i;
      continue;
    }
    blank(i, end);
    i = end;
  }
  return code;
}

std::string trimmed(std::string_view s) {
  const std::size_t first = s.find_first_not_of(" \t\n");
  if (first == std::string_view::npos) return "";
  return std::string(s.substr(first, s.find_last_not_of(" \t\n") - first + 1));
}

// A declaration's head without what does not say its kind: attributes, `template <…>`, and an
// access label before it (`public:`).
std::string houseHeadCore(std::string_view head) {
  std::string h = trimmed(head);
  for (bool changed = true; changed;) {
    changed = false;
    for (std::string_view label : {"public", "private", "protected"}) {
      const std::string rest = h.substr(std::min(h.size(), label.size()));
      if (h.starts_with(label) && trimmed(rest).starts_with(':') && !trimmed(rest).starts_with("::")) {
        h = trimmed(trimmed(rest).substr(1));
        changed = true;
      }
    }
    if (h.starts_with("[[")) {
      h = trimmed(h.substr(std::min(h.size(), h.find("]]") + 2)));
      changed = true;
    }
    if (h.starts_with("template") && !isIdentifierChar(h.size() > 8 ? h[8] : ' ')) {
      int depth = 0;
      std::size_t k = h.find('<');
      for (; k < h.size(); ++k) {
        if (h[k] == '<') ++depth;
        if (h[k] == '>' && --depth == 0) break;
      }
      h = k < h.size() ? trimmed(h.substr(k + 1)) : "";
      changed = true;
    }
  }
  return h;
}

bool startsWithWord(const std::string& s, std::string_view word) {
  return s.starts_with(word) && (s.size() == word.size() || !isIdentifierChar(s[word.size()]));
}

enum class HouseScope { space, type, function, other };

// What the `{` after `head` opens, at namespace or class scope: a namespace (or extern "C"), a
// class, a function's body (a parameter list at the head's top level), or anything else (an enum,
// an initialiser).
HouseScope houseScopeOf(std::string_view head) {
  const std::string h = houseHeadCore(head);
  if (startsWithWord(h, "namespace") || startsWithWord(h, "extern")) return HouseScope::space;
  if (startsWithWord(h, "class") || startsWithWord(h, "struct") || startsWithWord(h, "union")) return HouseScope::type;
  if (startsWithWord(h, "enum")) return HouseScope::other;
  const std::size_t paren = h.find('(');
  if (paren == std::string::npos) return HouseScope::other;
  // A variable's initialiser (`const Table kRows = {`), unless it is a lambda (`auto f = [](…) {`).
  if (const std::size_t equals = h.find(" = "); equals < paren && trimmed(h.substr(equals + 3)).front() != '[') {
    return HouseScope::other;
  }
  // In a constructor's initialiser list, a member's braces (`: a_{1}`) are not the body, which
  // follows the last initialiser's `)` or `}`.
  int depth = 0;
  std::size_t close = paren;
  for (; close < h.size(); ++close) {
    depth += h[close] == '(' ? 1 : h[close] == ')' ? -1 : 0;
    if (depth == 0) break;
  }
  for (std::size_t k = close + 1; k < h.size(); ++k) {
    if (h[k] == ':' && (k + 1 == h.size() || h[k + 1] != ':') && h[k - 1] != ':') {
      return h.back() == ')' || h.back() == '}' ? HouseScope::function : HouseScope::other;
    }
  }
  return HouseScope::function;
}

// A function's name from its head: the (qualified) name before its parameter list; for a lambda
// bound to a name at namespace scope, that name; for a macro (TEST_CASE("…")), the macro with its
// first argument, from the original text.
std::string houseFunctionName(std::string_view code, std::string_view text, std::size_t headStart,
                              std::size_t headEnd) {
  const std::string_view head = code.substr(headStart, headEnd - headStart);
  const std::size_t paren = head.find('(');
  std::size_t end = head.find_last_not_of(" \t\n", paren == 0 ? 0 : paren - 1);
  if (const std::size_t equals = head.find(" = "); equals != std::string_view::npos && equals < paren) {
    end = head.find_last_not_of(" \t\n", equals);
  }
  std::size_t start = end + 1;
  while (start > 0 && (isIdentifierChar(head[start - 1]) || head[start - 1] == ':' || head[start - 1] == '~')) --start;
  const std::string name(head.substr(start, end + 1 - start));
  const bool macro = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isupper(static_cast<unsigned char>(c)) != 0 || c == '_';
  });
  if (!macro) return name.empty() ? "a lambda" : name;
  const std::size_t close = head.find(')', paren);
  std::string call(text.substr(headStart + paren, std::min<std::size_t>(close - paren + 1, 80)));
  std::replace(call.begin(), call.end(), '\n', ' ');
  return name + call;
}

// Every function of a C++ text, in the order they end.
std::vector<HouseFunction> houseFunctions(std::string_view text) {
  struct Open {
    HouseScope scope;
    int headLine;
    std::string name;
  };
  const std::string code = houseCodeOnly(text);
  std::vector<HouseFunction> functions;
  std::vector<Open> open;
  std::size_t headStart = std::string::npos;  // where the declaration in progress starts
  int headLine = 0, parens = 0, line = 1;
  const auto atOuterScope = [&] {
    return open.empty() || open.back().scope == HouseScope::space || open.back().scope == HouseScope::type;
  };
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    if (c == '\n') ++line;
    if (!atOuterScope()) {
      if (c == '{') open.push_back({HouseScope::other, 0, ""});
      if (c == '}') {
        const Open closed = open.back();
        open.pop_back();
        if (closed.scope == HouseScope::function) functions.push_back({closed.name, closed.headLine, line});
        if (atOuterScope() && closed.scope == HouseScope::function) headStart = std::string::npos;
      }
      continue;
    }
    if (c == '{') {
      const std::string_view head =
          headStart == std::string::npos ? std::string_view() : std::string_view(code).substr(headStart, i - headStart);
      const HouseScope scope = parens > 0 ? HouseScope::other : houseScopeOf(head);
      const bool function = scope == HouseScope::function;
      open.push_back({scope, headStart == std::string::npos ? line : headLine,
                      function ? houseFunctionName(code, text, headStart, i) : ""});
      if (scope != HouseScope::other) headStart = std::string::npos, parens = 0;
    } else if (c == '}') {
      if (!open.empty()) open.pop_back();
      headStart = std::string::npos, parens = 0;
    } else if (c == ';') {
      headStart = std::string::npos, parens = 0;
    } else if (!std::isspace(static_cast<unsigned char>(c))) {
      if (headStart == std::string::npos) headStart = i, headLine = line;
      parens += c == '(' ? 1 : c == ')' ? -1 : 0;
    }
  }
  return functions;
}

int houseLineCount(std::string_view text) {
  return int(std::count(text.begin(), text.end(), '\n')) + (text.empty() || text.back() == '\n' ? 0 : 1);
}

std::string houseFileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The project's C++ sources and headers, relative to the checkout, in a fixed order.
std::vector<fs::path> houseSources() {
  const std::set<std::string> extensions = {".cpp", ".hpp", ".h", ".cc"};
  std::vector<fs::path> out;
  for (const char* folder : {"src", "render", "plot", "include", "python/src", "tests", "bench", "examples"}) {
    if (!fs::is_directory(kHouseCheckout / folder)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(kHouseCheckout / folder)) {
      if (entry.is_regular_file() && extensions.count(entry.path().extension().string()) == 1) {
        out.push_back(entry.path().lexically_relative(kHouseCheckout));
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Exempt from the file limit (see the top of this file).
bool exemptFromFileLimit(const fs::path& relative) {
  const std::string name = relative.filename().string();
  const bool testFile = relative.parent_path() == "tests" && name.starts_with("test_") && name.ends_with(".cpp");
  return testFile || *relative.begin() == "bench";
}

// A function of `lines` lines whose body is plain statements.
std::string houseFunctionOfLines(const std::string& name, int lines) {
  std::string text = "int " + name + "(int x) {\n";
  for (int k = 0; k < lines - 2; ++k) text += "  x += " + std::to_string(k) + ";\n";
  return text + "}\n";
}

}  // namespace

TEST_CASE("the sizes scanner reports a 101-line function and not a 100-line one") {
  const std::string text = houseFunctionOfLines("fits", 100) + houseFunctionOfLines("tooLong", 101);
  const std::vector<HouseFunction> found = houseFunctions(text);
  REQUIRE(found.size() == 2);
  CHECK(found[0].name == "fits");
  CHECK(found[0].lines() == 100);
  CHECK(found[1].name == "tooLong");
  CHECK(found[1].firstLine == 101);
  CHECK(found[1].lines() == 101);
  std::vector<std::string> tooLong;
  for (const HouseFunction& f : found) {
    if (f.lines() > kMaxHouseFunctionLines) tooLong.push_back(f.name);
  }
  CHECK(tooLong == std::vector<std::string>{"tooLong"});
}

TEST_CASE("the sizes scanner skips braces in comments, literals and directives, and counts lambdas in") {
  const std::string text = R"x(#include <string>
#define OPEN {
namespace outer {
// a comment's { is no brace
/* nor a block comment's { */
template <class T>
struct Holder : Base<T> {
  int get() const noexcept { return 1'000 + '{'; }
  Holder() : a_{1}, b_(2) {
    const char* s = "}{";
  }
  enum class Kind { one, two };
 private:
  int a_, b_;
};
auto run(int x) -> int {
  auto f = [&](int y) {
    return R"raw(}{)raw"[0] + y;
  };
  return f(x);
}
const auto kLambda = [](int z) {
  return z;
};
}  // namespace outer
TEST_CASE("a case's name (with a paren") {
  CHECK(true);
}
)x";
  const std::vector<HouseFunction> found = houseFunctions(text);
  REQUIRE(found.size() == 5);
  CHECK(found[0].name == "get");
  CHECK(found[0].firstLine == 8);
  CHECK(found[0].lines() == 1);
  CHECK(found[1].name == "Holder");
  CHECK(found[1].lines() == 3);
  CHECK(found[2].name == "run");
  CHECK(found[2].firstLine == 16);
  CHECK(found[2].lines() == 6);  // the lambda inside counts toward run
  CHECK(found[3].name == "kLambda");
  CHECK(found[4].name == "TEST_CASE(\"a case's name (with a paren\")");
  CHECK(found[4].lines() == 3);
}

TEST_CASE("no C++ file of the project is longer than 500 lines, tests and benchmarks aside") {
  int checked = 0;
  for (const fs::path& relative : houseSources()) {
    if (exemptFromFileLimit(relative)) continue;
    ++checked;
    const int lines = houseLineCount(houseFileText(kHouseCheckout / relative));
    CHECK_MESSAGE(lines <= kMaxHouseFileLines, relative.string()
                                                   << ": " << lines << " lines, more than " << kMaxHouseFileLines);
  }
  CHECK(checked > 300);
}

TEST_CASE("no function of the project's C++ is longer than 100 lines") {
  int checked = 0;
  for (const fs::path& relative : houseSources()) {
    for (const HouseFunction& f : houseFunctions(houseFileText(kHouseCheckout / relative))) {
      ++checked;
      CHECK_MESSAGE(f.lines() <= kMaxHouseFunctionLines,
                    relative.string() << ":" << f.firstLine << ": " << f.name << " is " << f.lines()
                                      << " lines, more than " << kMaxHouseFunctionLines);
    }
  }
  CHECK(checked > 2000);
}
