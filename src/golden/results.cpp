// What a golden run found: see results.hpp.
#include "golden/results.hpp"

#include <array>

namespace particles::golden {

namespace {

constexpr std::array<std::pair<Outcome, std::string_view>, 4> kOutcomeNames = {
    {{Outcome::passed, "passed"}, {Outcome::failed, "failed"}, {Outcome::missing, "missing"}, {Outcome::error, "error"}}};

}  // namespace

std::string_view outcomeName(Outcome outcome) {
  for (const auto& [o, name] : kOutcomeNames) {
    if (o == outcome) return name;
  }
  return "error";
}

std::optional<Outcome> outcomeFromName(std::string_view name) {
  for (const auto& [o, n] : kOutcomeNames) {
    if (n == name) return o;
  }
  return std::nullopt;
}

GoldenResults::Counts GoldenResults::counts() const {
  Counts c;
  auto add = [&c](Outcome o) {
    switch (o) {
      case Outcome::passed: ++c.passed; break;
      case Outcome::failed: ++c.failed; break;
      case Outcome::missing: ++c.missing; break;
      case Outcome::error: ++c.error; break;
    }
  };
  for (const FrameResult& f : frames) add(f.outcome);
  for (const StateResult& s : states) add(s.outcome);
  return c;
}

}  // namespace particles::golden
