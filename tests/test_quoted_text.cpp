// input/printable_text.hpp: control bytes from files kept off the terminal, and a value quoted in
// a message at most kMostQuotedBytes long, with its size.
#include <doctest/doctest.h>

#include <string>

#include "input/printable_text.hpp"

using namespace particles::input;

TEST_CASE("printable text: control bytes from files are escaped, text is kept") {
  CHECK(printableText("plain name_t0.5\tand a\nline") == "plain name_t0.5\tand a\nline");
  CHECK(printableText("\x1b[2Jcleared") == "\\x1b[2Jcleared");
  CHECK(printableText("bell\a del\x7f") == "bell\\x07 del\\x7f");
  CHECK(printableText("caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x99\x82") == "caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x99\x82");
  CHECK(printableText("csi \xc2\x9b"
                      "31m") == "csi \\xc2\\x9b31m");        // a C1 control
  CHECK(printableText("bad \xff\xc3") == "bad \\xff\\xc3");  // not UTF-8, cut short
  CHECK(printableText("overlong \xc0\xaf") == "overlong \\xc0\\xaf");
}

TEST_CASE("quoted value: a short value whole, a long one cut at a character with its size") {
  CHECK(quotedValue("sepia") == "'sepia'");
  CHECK(quotedValue("") == "''");
  CHECK(quotedValue("a\x1b[2Jb") == "'a\\x1b[2Jb'");  // escaped, as printableText
  const std::string exact(kMostQuotedBytes, 'x');
  CHECK(quotedValue(exact) == "'" + exact + "'");
  const std::string huge(10 * 1024 * 1024, '7');
  const std::string quoted = quotedValue(huge);
  CHECK(quoted == "'" + std::string(kMostQuotedBytes, '7') + "…' (10485760 bytes)");
  // "é" is two bytes: a cut through the 80th byte keeps the character whole or leaves it out.
  std::string accents(kMostQuotedBytes - 1, 'a');
  accents += "\xc3\xa9\xc3\xa9";
  const std::string cut = quotedValue(accents);
  CHECK(cut == "'" + std::string(kMostQuotedBytes - 1, 'a') + "…' (" + std::to_string(accents.size()) + " bytes)");
  CHECK(cut.find("\\x") == std::string::npos);  // no half character shown as an escape
}
