// The report's text: see report_text.hpp.
#include "golden/report_text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <optional>

namespace particles::golden::report {

namespace {

constexpr char32_t kReplacement = 0xFFFD;

// The code point starting at text[i], advancing i past it; none for an invalid sequence, with i
// past its maximal subpart (Unicode 15, §3.9, "U+FFFD Substitution of Maximal Subparts": the
// WHATWG decoder's rule, so a browser shows what we wrote).
std::optional<char32_t> nextCodePoint(std::string_view text, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return std::uint8_t(text[k]); };
  const std::uint8_t lead = byte(i++);
  if (lead < 0x80) return lead;
  int length = 0;
  std::uint8_t low = 0x80, high = 0xBF;  // the range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;   // no overlong forms
    if (lead == 0xED) high = 0x9F;  // no surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;  // nothing past U+10FFFF
  } else {
    return std::nullopt;
  }
  char32_t code = lead & (0x7F >> length);
  for (int k = 1; k < length; ++k) {
    if (i >= text.size() || byte(i) < low || byte(i) > high) return std::nullopt;
    code = (code << 6) | (byte(i++) & 0x3F);
    low = 0x80, high = 0xBF;
  }
  return code;
}

void appendUtf8(std::string& out, char32_t code) {
  if (code < 0x80) {
    out += char(code);
  } else if (code < 0x800) {
    out += char(0xC0 | (code >> 6));
    out += char(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += char(0xE0 | (code >> 12));
    out += char(0x80 | ((code >> 6) & 0x3F));
    out += char(0x80 | (code & 0x3F));
  } else {
    out += char(0xF0 | (code >> 18));
    out += char(0x80 | ((code >> 12) & 0x3F));
    out += char(0x80 | ((code >> 6) & 0x3F));
    out += char(0x80 | (code & 0x3F));
  }
}

bool isForbiddenInMarkup(char32_t code) {
  const bool lineSpace = code == '\t' || code == '\n' || code == '\r';
  return (code < 0x20 && !lineSpace) || (code >= 0x7F && code <= 0x9F) || code == 0xFFFE || code == 0xFFFF;
}

std::string percentText(double share) {
  return fmt::format("{:.4g} %", 100.0 * share);
}

}  // namespace

std::string validUtf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) appendUtf8(out, nextCodePoint(text, i).value_or(kReplacement));
  return out;
}

std::string quotedExcerpt(std::string_view text, char quote) {
  constexpr std::string_view kEllipsis = "…";
  std::string inside;
  std::size_t keep = 0;  // the longest run of whole characters that leaves room for the ellipsis
  bool whole = true;
  for (std::size_t i = 0; i < text.size();) {
    const char32_t code = nextCodePoint(text, i).value_or(kReplacement);
    std::string piece;
    if (code == char32_t(quote) || code == '\\') {
      piece = {'\\', char(code)};
    } else if (code == '\n') {
      piece = "\\n";
    } else if (code == '\t') {
      piece = "\\t";
    } else if (code == '\r') {
      piece = "\\r";
    } else if (code < 0x20 || (code >= 0x7F && code <= 0x9F)) {
      piece = fmt::format("\\u{:04x}", unsigned(code));
    } else {
      appendUtf8(piece, code);
    }
    if (inside.size() + piece.size() > kMaxQuotedBytes) {
      whole = false;  // only the first kMaxQuotedBytes of a 20 MB value are ever looked at
      break;
    }
    inside += piece;
    if (inside.size() + kEllipsis.size() <= kMaxQuotedBytes) keep = inside.size();
  }
  if (whole) return fmt::format("{0}{1}{0}", quote, inside);
  inside.resize(keep);
  return fmt::format("{0}{1}{2}{0} ({3} bytes)", quote, inside, kEllipsis, text.size());
}

std::string escapeMarkup(std::string_view text, Markup where) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    char32_t code = nextCodePoint(text, i).value_or(kReplacement);
    if (isForbiddenInMarkup(code)) code = kReplacement;
    switch (code) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      case '\t':
      case '\n':
      case '\r':
        if (where == Markup::attribute) {
          out += fmt::format("&#{};", int(code));
        } else {
          out += char(code);
        }
        break;
      default: appendUtf8(out, code);
    }
  }
  return out;
}

std::string urlPath(std::string_view path) {
  std::string out;
  for (const char c : path) {
    const auto byte = std::uint8_t(c);
    const bool unreserved = (byte >= 'A' && byte <= 'Z') || (byte >= 'a' && byte <= 'z') ||
                            (byte >= '0' && byte <= '9') || c == '-' || c == '.' || c == '_' || c == '~';
    if (unreserved || c == '/') {
      out += c;
    } else {
      out += fmt::format("%{:02X}", byte);
    }
  }
  return out;
}

std::string shareText(const FrameNumbers& n) {
  return fmt::format("{:.4f} % ({} of {} px)", 100.0 * n.share, n.differing, n.pixels);
}

std::string toleranceText(const FrameNumbers& n) {
  return fmt::format("threshold {} of 255 per channel, max share {}", n.threshold, percentText(n.maxShare));
}

std::string largestText(const FrameNumbers& n) {
  return fmt::format("{} of 255", n.largest);
}

std::string boxText(const FrameNumbers& n) {
  if (!n.box) return "none";
  const auto [x0, y0, x1, y1] = *n.box;
  return fmt::format("x {}…{}, y {}…{} ({}×{} px, from the top left)", x0, x1, y0, y1, x1 - x0 + 1, y1 - y0 + 1);
}

std::string expectationText(const FrameResult& frame) {
  if (!frame.numbers) return frame.expectDiffer ? "control: must differ" : "must match";
  const std::string bound = percentText(frame.numbers->maxShare);
  if (frame.expectDiffer) return fmt::format("control: must differ (more than {} of the pixels)", bound);
  return fmt::format("must match (at most {} of the pixels differ)", bound);
}

std::string numberText(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);
}

std::string deviationText(const StateDeviation& d) {
  return fmt::format("t {}, {} {}: expected {}, actual {}, difference {}, tolerance {}", d.time, d.point, d.quantity,
                     numberText(d.expected), numberText(d.actual), numberText(d.difference), numberText(d.tolerance));
}

std::string secondsText(double seconds) {
  return fmt::format("{:.3f} s", seconds);
}

std::string countText(long count, std::string_view one, std::string_view many) {
  return fmt::format("{} {}", count, count == 1 ? one : many);
}

}  // namespace particles::golden::report
