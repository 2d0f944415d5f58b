// libFuzzer harness for job records: the text of OUT/jobs/NNNNNN/record.txt, which
// `particles gather`, `particles sweep` and every job given --record read, parsed by
// parseJobRecord; nullopt is the normal outcome for anything that is not a record. The record's
// command line goes through splitCommandText, and what splits must quote back to the same words
// (but --force, which commandText leaves out).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "app/job_record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::app;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto record = parseJobRecord(text);
  // Whatever the text, the command-line reader either refuses it or gives words that round-trip.
  const std::string_view command = record ? std::string_view(record->command) : text;
  if (auto words = splitCommandText(command)) {
    std::erase(*words, "--force");  // commandText leaves it out: a forced rerun is the same job
    if (splitCommandText(commandText(*words)) != words) __builtin_trap();
  }
  return 0;
}
