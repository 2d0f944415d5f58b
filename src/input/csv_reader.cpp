// Reading CSV text: see csv_reader.hpp.
#include "input/csv_reader.hpp"

#include <algorithm>

namespace particles::input {

std::vector<std::vector<std::string>> parseCsv(std::string_view text, std::vector<int>* recordLines) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, fieldStarted = false;
  int line = 1, rowLine = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      continue;
    }
    if (c == '"') {
      if (fieldStarted) throw CsvError(line, "a quote inside an unquoted field");
      quoted = true;
      fieldStarted = true;
    } else if (c == ',') {
      row.push_back(std::move(field));
      field.clear();
      fieldStarted = false;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      row.push_back(std::move(field));
      field.clear();
      fieldStarted = false;
      rows.push_back(std::move(row));
      if (recordLines) recordLines->push_back(rowLine);
      row.clear();
      rowLine = ++line;
    } else {
      // The rest of an unquoted field at once: a long field costs one append, not one per byte.
      const size_t end = std::min(text.find_first_of(",\"\n\r", i), text.size());
      field.append(text.substr(i, end - i));
      i = end - 1;
      fieldStarted = true;
    }
  }
  if (quoted) throw CsvError(rowLine, "a quoted field is not closed");
  if (fieldStarted || !row.empty()) {
    row.push_back(std::move(field));
    rows.push_back(std::move(row));
    if (recordLines) recordLines->push_back(rowLine);
  }
  return rows;
}

}  // namespace particles::input
