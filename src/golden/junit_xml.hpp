#pragma once
// junit.xml (results.hpp): the results for CI test views (GitHub's action-junit-report, GitLab's
// test reports, Jenkins' junit step), which all read the JUnit XML of Ant's and Maven Surefire's
// schema: one <testsuites>, holding <testsuite name="golden frames"> and <testsuite name="golden
// states"> (tests, failures, errors, skipped and time on each, the run's facts as <properties>),
// one <testcase classname="golden.frames" name="NAME" time="S"> per result. A failed result is a
// <failure type="golden">, a missing reference a <failure type="missing-reference"> (it must fail
// CI), an error an <error type="golden-error">; the element's message attribute is its one line,
// its text the numbers, kept files and the commands that reproduce it. No timestamp or host name:
// the same results give the same bytes.

#include <string>

#include "golden/results.hpp"

namespace particles::golden::report {

// The text of junit.xml: XML 1.0 in UTF-8 (report_text.hpp: escapeMarkup), ending in a line break.
std::string junitXml(const GoldenResults& results);

}  // namespace particles::golden::report
