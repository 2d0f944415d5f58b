#include "input/printable_text.hpp"

#include <fmt/format.h>

namespace particles::input {

namespace {

// The length of the UTF-8 sequence starting at text[i] (2 … 4), or 0 when it is not one: a stray
// continuation byte, an overlong form, a surrogate, past U+10FFFF, or cut short.
size_t utf8Length(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  size_t n = 0;
  unsigned long code = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    n = 2, code = lead & 0x1Fu;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    n = 3, code = lead & 0x0Fu;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    n = 4, code = lead & 0x07u;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0u) != 0x80u) return 0;
    code = (code << 6) | (byte(i + k) & 0x3Fu);
  }
  const bool overlong = (n == 3 && code < 0x800) || (n == 4 && code < 0x10000);
  if (overlong || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) return 0;
  return n;
}

}  // namespace

std::string printableText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n' || c == '\t' || (c >= 0x20 && c < 0x7F)) {
      out += char(c);
      ++i;
      continue;
    }
    const size_t n = c >= 0x80 ? utf8Length(text, i) : 0;
    // A C1 control is U+0080 … U+009F: C2 80 … C2 9F in UTF-8.
    const bool c1 = n == 2 && c == 0xC2 && static_cast<unsigned char>(text[i + 1]) <= 0x9F;
    if (n > 0 && !c1) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    }
    const size_t shown = c1 ? 2 : 1;
    for (size_t k = 0; k < shown; ++k) out += fmt::format("\\x{:02x}", static_cast<unsigned char>(text[i + k]));
    i += shown;
  }
  return out;
}

namespace {

// The first kMostQuotedBytes of a longer value, cut at a character's start.
std::string_view quotedPart(std::string_view value) {
  size_t cut = kMostQuotedBytes;
  while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xC0u) == 0x80u) --cut;  // not inside a character
  return value.substr(0, cut);
}

}  // namespace

std::string quotedValue(std::string_view value) {
  if (value.size() <= kMostQuotedBytes) return fmt::format("'{}'", printableText(value));
  return fmt::format("'{}…' ({} bytes)", printableText(quotedPart(value)), value.size());
}

std::string shownValue(std::string_view value) {
  if (value.size() <= kMostQuotedBytes) return printableText(value);
  return fmt::format("{}… ({} bytes)", printableText(quotedPart(value)), value.size());
}

}  // namespace particles::input
