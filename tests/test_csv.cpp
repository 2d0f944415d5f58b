// CSV as the program writes it (src/output/csv_writer.hpp) and reads it back
// (src/input/csv_reader.hpp): a sweep's jobs.csv and results.csv, a golden state file. Fields that
// need quotes round-trip, each record's first line is counted across quoted line breaks, and text
// that is not CSV is refused at its line.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "input/csv_reader.hpp"
#include "output/csv_writer.hpp"

using particles::input::CsvError;
using particles::input::parseCsv;
using particles::output::csvField;
using particles::output::csvRow;

namespace {

// The refusal's line and message, or "accepted".
std::string refusal(const std::string& text) {
  try {
    parseCsv(text);
  } catch (const CsvError& e) {
    return std::to_string(e.line()) + ": " + e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("csv: fields with commas, quotes or line breaks are quoted, and read back with their lines") {
  CHECK(csvField("plain text") == "plain text");
  CHECK(csvField("a,b") == "\"a,b\"");
  CHECK(csvField("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csvField("two\nlines") == "\"two\nlines\"");
  CHECK(csvField("cr\r") == "\"cr\r\"");
  const std::vector<std::vector<std::string>> rows = {
      {"index", "command"}, {"0", "particles run 'a b.yaml' --set \"x=1,2\""}, {"1", "two\nlines\nhere"}, {"", ""}};
  std::string text;
  for (const auto& row : rows) text += csvRow(row);
  CHECK(text.substr(0, 14) == "index,command\n");
  std::vector<int> lines;
  CHECK(parseCsv(text, &lines) == rows);
  CHECK(lines == std::vector<int>{1, 2, 3, 6});
}

TEST_CASE("csv: CRLF, a lone CR and a missing last line break end records, and an empty line is one empty field") {
  CHECK(parseCsv("a,b\r\nc,d\re\n\nf") ==
        std::vector<std::vector<std::string>>{{"a", "b"}, {"c", "d"}, {"e"}, {""}, {"f"}});
  CHECK(parseCsv("").empty());
}

TEST_CASE("csv: a quote that does not close, or inside an unquoted field, is refused at its line") {
  CHECK(refusal("a,b\n1,\"open\n2,3\n") == "2: a quoted field is not closed");
  CHECK(refusal("a,b\n\"x\ny\",1\n2,ab\"c\n") == "4: a quote inside an unquoted field");
  CHECK(refusal("\"closed\" later,1\n") == "accepted");  // text after the closing quote joins the field
}
