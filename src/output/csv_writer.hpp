#pragma once
// Writing CSV text (RFC 4180): a field holding a comma, a quote or a line break goes in quotes,
// its quotes doubled. For a sweep's jobs.csv and results.csv and a golden state file's names;
// input/csv_reader.hpp reads them back.

#include <string>
#include <string_view>
#include <vector>

namespace particles::output {

std::string csvField(std::string_view field);
std::string csvRow(const std::vector<std::string>& fields);  // ends with '\n'

}  // namespace particles::output
