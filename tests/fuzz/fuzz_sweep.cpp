// libFuzzer harness for sweep files: text in, a SweepSpec or a ScenarioError with its
// file, line and key out, as `particles sweep` reads them before planning. Scenario files are not
// opened here (planning is the program's), so only the sweep file's own reader is fuzzed: its
// lexical count of flow lists, the event check of list lengths and aliases, and the key readers.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "scenario/scenario.hpp"
#include "scenario/sweep_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::scenario;
  try {
    const SweepSpec spec = loadSweepText(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.yaml");
    if (spec.combinations() > kMaxSweepJobs) __builtin_trap();  // the limit the reader promises
  } catch (const ScenarioError&) {
    // A bad sweep file, reported with its position.
  }
  return 0;
}
