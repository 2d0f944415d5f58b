// One source for every number a user reads: a message or help text that writes a named
// limit as a literal ("from 1 to 1000" next to kMaxFps = 1000) goes stale the day the constant
// changes. Messages format the constant instead. This test reads the rooms' sources, collects the
// named integer constants (`constexpr … kName = N;`, N ≥ kSmallestLimit) and fails on any string
// literal that holds one of their values as a number of its own, unless the list below says why
// that number is something else.
#include <doctest/doctest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Values below this are too common to mean one constant (a 2 in a message is rarely kMinSides).
constexpr long kSmallestLimit = 50;

struct StringLiteral {
  int line;
  std::string text;  // between the quotes, escapes as written
};

// The string literals of C++ source text, skipping comments and character literals. Raw strings are
// read as ordinary ones (none of the rooms' messages is one).
std::vector<StringLiteral> stringLiterals(const std::string& source) {
  std::vector<StringLiteral> out;
  int line = 1;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const char c = source[i];
    if (c == '\n') {
      ++line;
    } else if (c == '/' && i + 1 < source.size() && source[i + 1] == '/') {
      while (i < source.size() && source[i] != '\n') ++i;
      --i;  // the newline is counted above
    } else if (c == '/' && i + 1 < source.size() && source[i + 1] == '*') {
      for (i += 2; i + 1 < source.size() && !(source[i] == '*' && source[i + 1] == '/'); ++i) line += source[i] == '\n';
      ++i;
    } else if (c == '\'' && !(i > 0 && std::isalnum(static_cast<unsigned char>(source[i - 1])))) {
      // A character literal ('"'); a quote after a digit is a digit separator (10'000).
      for (++i; i < source.size() && source[i] != '\''; ++i) i += source[i] == '\\';
    } else if (c == '"') {
      StringLiteral literal{line, ""};
      for (++i; i < source.size() && source[i] != '"'; ++i) {
        if (source[i] == '\\' && i + 1 < source.size()) literal.text += source[i++];
        literal.text += source[i];
      }
      out.push_back(std::move(literal));
    }
  }
  return out;
}

// The whole numbers written in a text: digit runs with no letter, digit, '.', '_' or '\' on either
// side ("1 to 1000" holds 1 and 1000; "x264", "1e500", "0.25" and "\n16" hold none).
std::vector<long> numbersIn(const std::string& text) {
  std::vector<long> out;
  const auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_'; };
  for (std::size_t i = 0; i < text.size();) {
    if (!std::isdigit(static_cast<unsigned char>(text[i]))) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    const bool alone = (i == 0 || (!part(text[i - 1]) && text[i - 1] != '\\')) && (end == text.size() || !part(text[end]));
    if (alone && end - i < 16) out.push_back(std::stol(text.substr(i, end - i)));
    i = end;
  }
  return out;
}

// Named integer constants of source text: value → names.
void collectConstants(const std::string& source, std::map<long, std::set<std::string>>& constants) {
  static const std::regex constant(R"(\bconstexpr\s[^=;(){}]*?\b(k[A-Z]\w*)\s*=\s*([0-9][0-9']*)(\.0*)?\s*;)");
  for (auto it = std::sregex_iterator(source.begin(), source.end(), constant); it != std::sregex_iterator(); ++it) {
    std::string digits = (*it)[2];
    std::erase(digits, '\'');
    if (digits.size() > 15) continue;
    const long value = std::stol(digits);
    if (value >= kSmallestLimit) constants[value].insert((*it)[1]);
  }
}

struct Repetition {
  std::string where;  // file:line
  long value;
  std::string constants, literal;
};

// Each literal of `sources` (name → text) holding a value of `constants`, but for `allowed`
// (file name → values there that are not the constants').
std::vector<Repetition> repeatedLimits(const std::map<std::string, std::string>& sources,
                                       const std::map<long, std::set<std::string>>& constants,
                                       const std::map<std::string, std::set<long>>& allowed) {
  std::vector<Repetition> out;
  for (const auto& [name, text] : sources) {
    const auto exempt = allowed.find(name);
    for (const StringLiteral& literal : stringLiterals(text)) {
      for (const long value : numbersIn(literal.text)) {
        const auto named = constants.find(value);
        if (named == constants.end() || (exempt != allowed.end() && exempt->second.count(value))) continue;
        std::ostringstream names;
        for (const std::string& n : named->second) names << (names.tellp() > 0 ? ", " : "") << n;
        out.push_back({name + ":" + std::to_string(literal.line), value, names.str(), literal.text});
      }
    }
  }
  return out;
}

std::string readWhole(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("message literals: the scanner finds a limit written out in a message, and nothing else") {
  std::map<long, std::set<std::string>> constants;
  collectConstants("inline constexpr int kMaxFps = 1000;\nconstexpr double kMaxKeyintSeconds = 3600.0;\n"
                   "constexpr size_t kBig = 10'000;\nconstexpr int kSmall = 4;\nconstexpr double kHalf = 0.5;\n",
                   constants);
  CHECK(constants == std::map<long, std::set<std::string>>{{1000, {"kMaxFps"}}, {3600, {"kMaxKeyintSeconds"}},
                                                           {10000, {"kBig"}}});
  const std::map<std::string, std::string> sources = {
      {"a.cpp",
       "throw E(\"fps out of range (1 to 1000)\");\n"
       "// a comment may say 1000 and \"3600\"\n"
       "/* so may \"1000\" here */ auto s = fmt::format(\"{} to {}\", 1, kMaxFps);\n"
       "char q = '\"'; auto t = \"at most 3600 s, x1000, 1000.5, 1e1000\\n\";\n"},
      {"b.cpp", "auto u = \"10000 rows\"; auto v = \"1000\";\n"},
  };
  const auto found = repeatedLimits(sources, constants, {{"b.cpp", {1000}}});
  REQUIRE(found.size() == 3);
  CHECK(found[0].where == "a.cpp:1");
  CHECK(found[0].value == 1000);
  CHECK(found[0].constants == "kMaxFps");
  CHECK(found[1].where == "a.cpp:4");
  CHECK(found[1].value == 3600);
  CHECK(found[2].where == "b.cpp:1");
  CHECK(found[2].value == 10000);
}

TEST_CASE("message literals: no message or help text writes out a named limit") {
  const fs::path root = PARTICLES_SOURCE_DIR;
  std::map<std::string, std::string> sources;
  std::map<long, std::set<std::string>> constants;
  for (const char* room : {"src", "render", "plot"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / room)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      const std::string name = fs::relative(entry.path(), root).generic_string();
      sources[name] = readWhole(entry.path());
      collectConstants(sources[name], constants);
    }
  }
  REQUIRE(constants.size() > 10);  // the scan found the constants at all
  // Numbers that only look like a constant's: what each is instead.
  const std::map<std::string, std::set<long>> allowed = {
      {"render/gl_backend.hpp", {256}},    // llvmpipe's vector width, in an example renderer name
      {"render/video/gif_writer.cpp", {256}},    // a GIF palette's colours, an option of libav's filter
      {"src/golden/references.hpp", {200}},  // a pixel difference, in an example message
  };
  for (const Repetition& r : repeatedLimits(sources, constants, allowed)) {
    FAIL_CHECK(r.where << ": the literal \"" << r.literal << "\" writes " << r.value << ", the value of "
                           << r.constants << ": format the constant instead (or, when the number means "
                           << "something else, add it to this test's list with why)");
  }
}
