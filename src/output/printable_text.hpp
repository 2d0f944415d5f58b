#pragma once
// Text from files (a name in a results.json, a path, a message quoting a value) on its way to a
// terminal. An ESC byte there is an instruction to the terminal, not a character: it can move the
// cursor, rewrite what was printed before or set the window's title. So every control character
// but the line break and the tab is shown as an escape (\x1b), as are C1 controls (U+0080 …
// U+009F, which some terminals obey too) and bytes that are not UTF-8. The report files have
// escapes of their own (HTML, XML, JSON); this is for stdout and stderr.

#include <string>
#include <string_view>

namespace particles::output {

std::string printableText(std::string_view text);

}  // namespace particles::output
