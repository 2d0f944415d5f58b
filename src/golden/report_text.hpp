#pragma once
// The report's text (results.hpp): strings made safe for HTML, XML and JSON, file paths made safe
// for links, and the words the report and junit.xml both say of a frame's numbers and a state's
// deviation. Internal to src/golden/.
//
// Names, messages and commands hold whatever bytes the manifest, a scenario or a shell put there:
// invalid UTF-8 becomes U+FFFD (one per maximal subpart of an invalid sequence, the Unicode
// standard's practice and the WHATWG decoder's), in every file, so each is valid UTF-8.

#include <cstddef>
#include <string>
#include <string_view>

#include "golden/results.hpp"

namespace particles::golden::report {

// `text` with every invalid UTF-8 sequence replaced by U+FFFD; control characters kept (JSON
// escapes them).
std::string validUtf8(std::string_view text);

// The most bytes a message quotes of a value read from a file, between the quotes: a 20 MB string
// in results.json once made a 20 MB message.
inline constexpr std::size_t kMaxQuotedBytes = 80;

// `text` as a message quotes it: between `quote`s, valid UTF-8, a backslash, the quote and the
// control characters (C0, DEL, C1: a terminal acts on them) escaped as JSON writes them ("\n",
// "\u001b"), whole when that takes at most kMaxQuotedBytes, else cut at a character before that
// with "…" and followed by the whole length: `"aaaa…" (20000000 bytes)`.
std::string quotedExcerpt(std::string_view text, char quote = '"');

// Where escaped text goes: an element's content, or an attribute value in double quotes, where
// tab and line breaks are written as character references (an XML parser turns them into spaces).
enum class Markup { text, attribute };

// `text` for HTML or XML 1.0: valid UTF-8, & < > " ' as references, and the characters XML 1.0
// forbids (C0 controls but tab and line breaks, U+FFFE, U+FFFF) and HTML calls parse errors (DEL,
// C1 controls) replaced by U+FFFD.
std::string escapeMarkup(std::string_view text, Markup where = Markup::text);

// A file path relative to the report for href and src: every byte outside RFC 3986's unreserved
// characters and '/' percent-encoded (so a file named with any bytes is still the file linked).
std::string urlPath(std::string_view path);

// "0.1234 % (95 of 76800 px)"
std::string shareText(const FrameNumbers& numbers);
// "threshold 16 of 255 per channel, max share 0.02 %"
std::string toleranceText(const FrameNumbers& numbers);
// "54 of 255"
std::string largestText(const FrameNumbers& numbers);
// "x 10…20, y 5…9 (11×5 px, from the top left)", or "none"
std::string boxText(const FrameNumbers& numbers);
// "passes when more than 0.02 % of the pixels differ" for a control, else "…at most…"
std::string expectationText(const FrameResult& frame);
// "t 1.5, cloth[3][4] x: expected 0.25, actual 0.2625, difference 0.0125, tolerance 0.001"
std::string deviationText(const StateDeviation& deviation);
// A number as the report prints a state's values: the shortest text that reads back as it.
std::string numberText(double value);
// "0.123 s"
std::string secondsText(double seconds);
// "1 frame", "3 frames": the count and the word for it.
std::string countText(long count, std::string_view one, std::string_view many);

}  // namespace particles::golden::report
