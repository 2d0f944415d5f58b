#include "output/shell_words.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string_view>

namespace particles::output {

bool isPlainShellChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) ||
         std::string_view("_./=:,+-@%^").find(c) != std::string_view::npos;
}

namespace {

bool isControlChar(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

}  // namespace

// Three forms, each read back by splitCommandText: plain words as they are; anything else in
// single quotes, where the shell takes every byte literally but the quote itself ('\'' closes,
// adds an escaped quote and reopens); and words with control characters (a newline above all) in
// bash's $'…', so that a command line is always one line of text.
std::string shellQuote(const std::string& arg) {
  if (!arg.empty() && std::all_of(arg.begin(), arg.end(), isPlainShellChar)) return arg;
  if (std::none_of(arg.begin(), arg.end(), isControlChar)) {
    std::string out = "'";
    for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
  }
  std::string out = "$'";
  for (char c : arg) {
    switch (c) {
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      case '\\': out += "\\\\"; break;
      case '\'': out += "\\'"; break;
      default: out += isControlChar(c) ? fmt::format("\\x{:02x}", static_cast<unsigned char>(c)) : std::string(1, c);
    }
  }
  return out + "'";
}

std::string shellCommand(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += ' ';
    out += shellQuote(w);
  }
  return out;
}

}  // namespace particles::output
