// libFuzzer harness for a sweep's job table: the text of OUT/jobs.csv, which
// `particles job` and `particles gather` read, through parseJobTable; InputError with the file and
// line is the normal outcome for a table that is not one the sweep wrote. A table that is accepted
// must hold what its readers rely on: every row as wide as the header, its folder its own.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "app/job_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::app;
  try {
    const JobTable table = parseJobTable(std::string_view(reinterpret_cast<const char*>(data), size), "jobs.csv");
    for (size_t i = 0; i < table.rows.size(); ++i) {
      const auto& row = table.rows[i];
      if (row.size() != table.commandColumn() + 1 || row[table.dirColumn()] != jobFolder(i) ||
          !splitCommandText(row[table.commandColumn()])) {
        __builtin_trap();
      }
    }
  } catch (const InputError&) {
    // Not a job table, reported with its line.
  }
  return 0;
}
