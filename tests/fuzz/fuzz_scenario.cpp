// libFuzzer harness for the scenario loader: text in, a System or a ScenarioError out. A small
// system is also stepped a few times with its own integrator and dt, where the core's explosion
// guard (SimulationError) is a normal outcome too. Any other exception escapes and any crash
// aborts: both are findings. How to run it: tests/fuzz/README.md.
//
// Lines at the top of the form `#set PATH=VALUE` (YAML comments, so the rest reads the same) are
// applied as `--set PATH=VALUE` overrides, so the fuzzer also reaches key paths and override values.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/solver.hpp"
#include "scenario/runner.hpp"
#include "scenario/scenario.hpp"

namespace {

using namespace particles;

// The scene budget (SceneLimits) well below the program's defaults: a scene at these limits loads
// in well under libFuzzer's 2 s per input under ASan, so a timeout or out-of-memory report means
// something grows faster than the budget accounts for, not merely a large scene.
constexpr scenario::SceneLimits kLimits{.particles = 20'000,
                                        .springs = 200'000,
                                        .constraints = 20'000,
                                        .endpoints = 400'000,
                                        .entries = 20'000};

// Stepping is for systems whose steps cost microseconds: the loader is what is fuzzed, and a step
// of a 1000-particle cloth would cut the executions per second by orders of magnitude.
constexpr int kMaxSteppedParticles = 200;
constexpr std::size_t kMaxSteppedSprings = 1000;
constexpr std::size_t kMaxSteppedConstraints = 200;
constexpr int kSteps = 5;

std::vector<scenario::Override> leadingOverrides(std::string_view text) {
  constexpr std::string_view kPrefix = "#set ";
  std::vector<scenario::Override> overrides;
  while (text.starts_with(kPrefix)) {
    const std::size_t eol = text.find('\n');
    overrides.push_back(scenario::parseOverride(text.substr(kPrefix.size(), eol - kPrefix.size())));
    if (eol == std::string_view::npos) break;
    text.remove_prefix(eol + 1);
  }
  return overrides;
}

void step(scenario::Scenario& s) {
  const System& system = s.system;
  if (system.layout().numPoints() > kMaxSteppedParticles || scenario::springCount(system) > kMaxSteppedSprings ||
      system.constraints().size() > kMaxSteppedConstraints) {
    return;
  }
  Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
  for (int k = 0; k < kSteps; ++k) stepper.step();
  // What `run --stats` and the renderer read of a stepped system.
  (void)scenario::sampleOf(system);
  (void)system.draw();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<scenario::Override> overrides = leadingOverrides(text);
    scenario::Scenario s = scenario::loadScenarioText(text, "fuzz.yaml", overrides, kLimits);
    step(s);
  } catch (const scenario::ScenarioError&) {
    // Bad input, reported with its place: the expected outcome for most inputs.
  } catch (const SimulationError&) {
    // The explosion guard stopped a run: a normal outcome of arbitrary physics.
  }
  return 0;
}
