// junit.xml: see junit_xml.hpp.
#include "golden/junit_xml.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <iterator>

#include "golden/report_text.hpp"

namespace particles::golden::report {

namespace {

std::string attribute(std::string_view text) {
  return escapeMarkup(text, Markup::attribute);
}

// JUnit's time: seconds, without a unit.
std::string junitSeconds(double seconds) {
  return fmt::format("{:.3f}", std::isfinite(seconds) && seconds > 0 ? seconds : 0.0);
}

// The lines common to a frame's and a state's details: kept files and reproduce commands.
void appendKeptAndReproduce(std::string& out, const KeptFiles& files, const std::vector<std::string>& reproduce) {
  for (const auto& [what, path] :
       {std::pair{"actual", &files.actual}, std::pair{"expected", &files.expected}, std::pair{"diff", &files.diff}}) {
    if (!path->empty()) out += fmt::format("{} (in the report folder): {}\n", what, *path);
  }
  if (!reproduce.empty()) {
    out += "reproduce:\n";
    for (const std::string& command : reproduce) out += fmt::format("  {}\n", command);
  }
}

std::string frameDetails(const FrameResult& f) {
  std::string out = f.message.empty() ? std::string() : f.message + "\n";
  out += fmt::format("scenario {} at t = {}; reference {}\n", f.scenario, f.time, f.reference);
  out += fmt::format("expects: {}\n", expectationText(f));
  if (f.numbers) {
    const FrameNumbers& n = *f.numbers;
    out += fmt::format("differing: {}\n", shareText(n));
    out += fmt::format("tolerance: {}\n", toleranceText(n));
    out += fmt::format("largest channel difference: {}\n", largestText(n));
    out += fmt::format("box: {}\n", boxText(n));
  }
  appendKeptAndReproduce(out, f.files, f.reproduce);
  return out;
}

std::string stateDetails(const StateResult& s) {
  std::string out = s.message.empty() ? std::string() : s.message + "\n";
  out += fmt::format("scenario {} at t = {}; reference {}\n", s.scenario, fmt::join(s.times, ", "), s.reference);
  if (s.firstBeyond) out += fmt::format("first beyond tolerance: {}\n", deviationText(*s.firstBeyond));
  if (s.largest) out += fmt::format("largest deviation: {}\n", deviationText(*s.largest));
  out += fmt::format("values compared: {}\n", s.values);
  appendKeptAndReproduce(out, s.files, s.reproduce);
  return out;
}

// One <testcase>, with its <failure> or <error> when it did not pass.
void appendTestcase(std::string& out, std::string_view classname, std::string_view name, double seconds,
                    Outcome outcome, std::string_view message, const std::string& details) {
  out += fmt::format(R"(    <testcase classname="{}" name="{}" time="{}")", classname, attribute(name),
                     junitSeconds(seconds));
  if (outcome == Outcome::passed) {
    out += "/>\n";
    return;
  }
  const std::string line = message.empty() ? std::string(outcomeName(outcome)) : std::string(message);
  const char* element = outcome == Outcome::error ? "error" : "failure";
  const char* type = outcome == Outcome::missing ? "missing-reference"
                     : outcome == Outcome::error ? "golden-error"
                                                 : "golden";
  out += fmt::format(">\n      <{0} message=\"{1}\" type=\"{2}\">{3}</{0}>\n    </testcase>\n", element,
                     attribute(line), type, escapeMarkup(details));
}

struct SuiteCounts {
  long tests = 0, failures = 0, errors = 0;
  double seconds = 0.0;
  void add(Outcome outcome, double s) {
    ++tests;
    failures += outcome == Outcome::failed || outcome == Outcome::missing;  // a missing reference fails CI
    errors += outcome == Outcome::error;
    if (std::isfinite(s) && s > 0) seconds += s;
  }
};

std::string properties(const std::vector<RunFacts>& runs) {
  std::string out = "    <properties>\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunFacts& run = runs[i];
    // One run's facts by their names; merged runs' as run1.manifest, run2.manifest, ….
    const std::string prefix = runs.size() == 1 ? std::string() : fmt::format("run{}.", i + 1);
    for (const auto& [name, value] : {std::pair{"manifest", &run.manifest}, std::pair{"program", &run.program},
                                      std::pair{"gl", &run.gl}, std::pair{"LP_NUM_THREADS", &run.lpNumThreads},
                                      std::pair{"overrides", &run.overrides}, std::pair{"shard", &run.shard}}) {
      out += fmt::format("      <property name=\"{}{}\" value=\"{}\"/>\n", prefix, name, attribute(*value));
    }
  }
  return out + "    </properties>\n";
}

std::string suite(std::string_view name, const SuiteCounts& counts, const std::string& props,
                  const std::string& testcases) {
  return fmt::format(
      "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"{}\" skipped=\"0\" time=\"{}\">\n{}{}  "
      "</testsuite>\n",
      name, counts.tests, counts.failures, counts.errors, junitSeconds(counts.seconds), props, testcases);
}

}  // namespace

std::string junitXml(const GoldenResults& results) {
  SuiteCounts frameCounts, stateCounts;
  std::string frameCases, stateCases;
  for (const FrameResult& f : results.frames) {
    frameCounts.add(f.outcome, f.seconds);
    appendTestcase(frameCases, "golden.frames", f.name, f.seconds, f.outcome, f.message, frameDetails(f));
  }
  for (const StateResult& s : results.states) {
    stateCounts.add(s.outcome, s.seconds);
    appendTestcase(stateCases, "golden.states", s.name, s.seconds, s.outcome, s.message, stateDetails(s));
  }
  const std::string props = results.runs.empty() ? std::string() : properties(results.runs);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += fmt::format(
      "<testsuites name=\"particles golden\" tests=\"{}\" failures=\"{}\" errors=\"{}\" skipped=\"0\" "
      "time=\"{}\">\n",
      frameCounts.tests + stateCounts.tests, frameCounts.failures + stateCounts.failures,
      frameCounts.errors + stateCounts.errors, junitSeconds(frameCounts.seconds + stateCounts.seconds));
  out += suite("golden frames", frameCounts, props, frameCases);
  out += suite("golden states", stateCounts, props, stateCases);
  return out + "</testsuites>\n";
}

}  // namespace particles::golden::report
