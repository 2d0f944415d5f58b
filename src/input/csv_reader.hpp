#pragma once
// Reading CSV text (RFC 4180): records end at a line break (CRLF, LF or a lone CR), fields are
// separated by commas, and a field in quotes may hold commas, line breaks and doubled quotes. A
// quote inside a field that did not start with one, and a quoted field that does not close, are
// refused. For a sweep's jobs.csv (app/job_table) and a golden state file (golden/state_table),
// which output/csv_writer.hpp writes; each wraps CsvError in its own error with the file's name.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace particles::input {

// A text that is not CSV: what is wrong, in words that follow "FILE:LINE: ", and the line.
class CsvError : public std::runtime_error {
 public:
  CsvError(int line, const std::string& message) : std::runtime_error(message), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

// The records of a CSV text, each its fields (an empty line is one empty field); throws CsvError.
// When `recordLines` is given, it receives the line each record starts on, from 1 (a quoted field
// may span lines).
std::vector<std::vector<std::string>> parseCsv(std::string_view text, std::vector<int>* recordLines = nullptr);

}  // namespace particles::input
