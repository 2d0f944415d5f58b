#pragma once
// A table as CSV (RFC 4180: fields with commas, quotes or line breaks are quoted, quotes doubled),
// for the sweep's jobs.csv and results.csv.

#include <string>
#include <string_view>
#include <vector>

namespace particles::app {

std::string csvField(std::string_view field);
std::string csvRow(const std::vector<std::string>& fields);  // ends with '\n'

// The rows of a CSV text; throws InputError naming `file` and the line on a malformed row. When
// `rowLines` is given, it receives the line each row starts on (a quoted field may span lines).
std::vector<std::vector<std::string>> parseCsv(std::string_view text, const std::string& file,
                                               std::vector<int>* rowLines = nullptr);

}  // namespace particles::app
