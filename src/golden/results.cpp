// What a golden run found: see results.hpp.
#include "golden/results.hpp"

#include "core/name_table.hpp"

namespace particles::golden {

namespace {

constexpr NameTableRow<Outcome> kOutcomeNames[] = {
    {Outcome::passed, "passed"}, {Outcome::failed, "failed"}, {Outcome::missing, "missing"}, {Outcome::error, "error"}};

}  // namespace

std::string_view outcomeName(Outcome outcome) {
  return nameOf(kOutcomeNames, outcome, "error");
}

std::optional<Outcome> outcomeFromName(std::string_view name) {
  return valueNamed(kOutcomeNames, name);
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

std::set<std::string> reportFiles(const GoldenResults& results) {
  std::set<std::string> files = {std::string(kReportHtml), std::string(kJunitXml), std::string(kResultsJson)};
  auto add = [&files](const KeptFiles& kept) {
    for (const std::string* f : {&kept.actual, &kept.expected, &kept.diff}) {
      if (!f->empty()) files.insert(*f);
    }
  };
  for (const FrameResult& f : results.frames) add(f.files);
  for (const StateResult& s : results.states) add(s.files);
  return files;
}

}  // namespace particles::golden
