// libFuzzer harness for a golden report's results.json: text in, through
// parseResultsJson, as `golden report` and `golden update --from` read it (the folder's own check,
// kept files behind symbolic links, needs files and is not fuzzed). std::invalid_argument naming
// the file is the normal outcome for a text that is not a results file. Beside not crashing:
//   - nothing nested deeper than report::kMaxResultsDepth is accepted: nlohmann's own depth, seen
//     through its parser callback, checks the reader's count of brackets;
//   - a message quotes at most report::kMaxQuotedBytes of a value, so none is long;
//   - results accepted are written back by resultsJson and read again as the same results.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "golden/results.hpp"
#include "golden/results_json.hpp"

namespace {

// The longest message: "results.json: not JSON: parse error at line L, column C: syntax error
// while parsing object key - " and nlohmann's longest reason (about 80 bytes), then "; last read:
// " with a quoted token (report::kMaxQuotedBytes and its length) and "; expected …": about 330.
constexpr std::size_t kMaxMessageBytes = 400;

// The deepest level of arrays and objects nlohmann's parser reaches in `text` before it stops (the
// top-level value is level 1).
int parserDepth(std::string_view text) {
  using Json = nlohmann::json;
  int deepest = 0;
  const Json::parser_callback_t count = [&](int depth, Json::parse_event_t event, Json&) {
    if (event == Json::parse_event_t::object_start || event == Json::parse_event_t::array_start) {
      deepest = std::max(deepest, depth + 1);
    }
    return true;
  };
  (void)Json::parse(text, count, /*allow_exceptions=*/false);
  return deepest;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::golden;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const bool tooDeep = parserDepth(text) > report::kMaxResultsDepth;
  try {
    const GoldenResults results = parseResultsJson(text, "results.json");
    if (tooDeep) __builtin_trap();
    const std::string written = report::resultsJson(results);
    if (report::resultsJson(parseResultsJson(written, "written.json")) != written) __builtin_trap();
  } catch (const std::invalid_argument& e) {
    if (std::strlen(e.what()) > kMaxMessageBytes) __builtin_trap();
    if (tooDeep && std::string_view(e.what()).find("nested more than") == std::string_view::npos) __builtin_trap();
  }
  return 0;
}
