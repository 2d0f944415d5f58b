// A sweep's job table: see job_table.hpp.
#include "app/job_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <set>

#include "input/printable_text.hpp"
#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "input/csv_reader.hpp"
#include "input/text_file.hpp"

namespace particles::app {

std::string jobFolder(size_t index) {
  return fmt::format("jobs/{:06}", index);
}

std::vector<std::string> jobTableHeader(const std::vector<std::string>& parameters) {
  std::vector<std::string> header = {"index", "stage", "scenario"};
  header.insert(header.end(), parameters.begin(), parameters.end());
  header.insert(header.end(), {"segment", "dir", "command"});
  return header;
}

JobTable parseJobTable(std::string_view text, const std::string& file) {
  JobTable table;
  table.file = file;
  std::vector<int> lines;
  std::vector<std::vector<std::string>> rows;
  try {
    rows = input::parseCsv(text, &lines);
  } catch (const input::CsvError& e) {
    throw InputError(fmt::format("{}:{}: {}", file, e.line(), e.what()));
  }
  if (rows.empty()) throw InputError(fmt::format("{}: empty; expected a sweep's job table", file));
  const std::vector<std::string>& header = rows.front();
  const auto expected = "index, stage, scenario, the parameters, segment, dir, command";
  if (header.size() < 6 || header[0] != "index" || header[1] != "stage" || header[2] != "scenario" ||
      header[header.size() - 3] != "segment" || header[header.size() - 2] != "dir" ||
      header[header.size() - 1] != "command") {
    throw InputError(fmt::format("{}:1: expected the columns {}; is this a sweep's job table?", file, expected));
  }
  std::set<std::string_view> seen;
  for (const std::string& name : header) {
    if (!seen.insert(name).second) {
      throw InputError(fmt::format("{}:1: the column {} appears twice; a job table names each column once", file,
                                   input::quotedValue(name)));
    }
  }
  table.parameters.assign(header.begin() + 3, header.end() - 3);

  for (size_t r = 1; r < rows.size(); ++r) {
    std::vector<std::string>& row = rows[r];
    const int line = lines[r];
    if (row.size() != header.size()) {
      throw InputError(fmt::format("{}:{}: {} fields, the header has {}", file, line, row.size(), header.size()));
    }
    const size_t index = r - 1;
    if (row[JobTable::kIndex] != std::to_string(index)) {
      throw InputError(fmt::format("{}:{}: index {} where job {} belongs; the rows are jobs 0, 1, 2, … in order", file,
                                   line, input::quotedValue(row[JobTable::kIndex]), index));
    }
    const std::string& stage = row[JobTable::kStage];
    if (stage != "run" && stage != "render" && stage != "stability" && stage != "segment" && stage != "concat") {
      throw InputError(fmt::format("{}:{}: unknown stage {} (expected run, render, stability, segment or concat)", file,
                                   line, input::quotedValue(stage)));
    }
    if (row[table.dirColumn()] != jobFolder(index)) {
      throw InputError(fmt::format("{}:{}: job {}'s folder is {}, not {}", file, line, index,
                                   input::quotedValue(row[table.dirColumn()]), jobFolder(index)));
    }
    const auto words = splitCommandText(row[table.commandColumn()]);
    if (!words || words->size() < 2) {
      throw InputError(fmt::format("{}:{}: job {}'s command is not a command line the sweep wrote", file, line, index));
    }
    table.rows.push_back(std::move(row));
    table.rowLines.push_back(line);
  }
  return table;
}

JobTable readJobTable(const std::filesystem::path& outDir, std::uintmax_t maxInputMiB) {
  const std::filesystem::path file = outDir / "jobs.csv";
  std::string text;
  try {
    text = input::readTextFile(file, maxInputMiB, input::Accept::regularOnly);
  } catch (const input::ReadError& e) {
    throw InputError(
        fmt::format("{}: {} (is {} the output folder of a sweep?)", file.string(), e.what(), outDir.string()));
  }
  return parseJobTable(text, file.string());
}

}  // namespace particles::app
