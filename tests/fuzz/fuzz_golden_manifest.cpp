// libFuzzer harness for golden manifests: text in, a GoldenManifest or a ScenarioError with its
// file, line and key out, as `particles golden check` reads them before anything is rendered.
// Scenarios and references are not opened here (that is the golden room's), so only the
// manifest's own reader is fuzzed: the bounded shape (flow lists, nodes, aliases, a second
// document), the key readers, the times and the names made from them.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "scenario/golden_manifest.hpp"
#include "scenario/scenario_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::scenario;
  try {
    const GoldenManifest m =
        loadGoldenManifestText(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.yaml", "dir");
    // What the reader promises: something to check, at most kMaxGoldenChecks, names that are file
    // names and differ across frames and states, times distinct and increasing.
    std::set<std::string> names;
    auto named = [&](const std::string& name) {
      const bool fileName =
          !name.empty() && name.size() <= kMaxGoldenNameLength && name[0] != '.' &&
          name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._+-") ==
              std::string::npos;
      if (!fileName || !names.insert(name).second) __builtin_trap();
    };
    for (const GoldenEntry& e : m.frames) {
      for (size_t i = 0; i < e.times.size(); ++i) {
        if (!(e.times[i].seconds >= 0) || (i > 0 && !(e.times[i - 1].seconds < e.times[i].seconds))) __builtin_trap();
        named(e.times[i].frameName);
      }
    }
    for (const GoldenEntry& e : m.states) named(e.stateName);
    if (names.empty() || names.size() > kMaxGoldenChecks) __builtin_trap();
  } catch (const ScenarioError&) {
    // A bad manifest, reported with its position.
  }
  return 0;
}
