#pragma once
// Text from files (a name in a results.json, a path, a message quoting a value) on its way to a
// terminal. An ESC byte there is an instruction to the terminal, not a character: it can move the
// cursor, rewrite what was printed before or set the window's title. So every control character
// but the line break and the tab is shown as an escape (\x1b), as are C1 controls (U+0080 …
// U+009F, which some terminals obey too) and bytes that are not UTF-8. The report files have
// escapes of their own (HTML, XML, JSON); this is for stdout and stderr.

#include <cstddef>
#include <string>
#include <string_view>

namespace particles::input {

std::string printableText(std::string_view text);

// The most of a value that a message quotes: a 10 MB value given where a number belongs makes a
// message of a line, not of 10 MB.
inline constexpr std::size_t kMostQuotedBytes = 80;

// A value as a message quotes it, between single quotes: printable (above), and at most
// kMostQuotedBytes of it, cut at a character's start, with its size when cut:
// 'abc' or 'xxxxxxxx…' (10485760 bytes).
std::string quotedValue(std::string_view value);
// The same without the quotes, for text a message shows as it is (a key path, `--set` as given):
// printable, and a longer one cut with its size: xxxxxxxx… (10485760 bytes).
std::string shownValue(std::string_view value);

}  // namespace particles::input
