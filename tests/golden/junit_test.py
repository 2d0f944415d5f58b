#!/usr/bin/python3
"""Reads a golden report's junit.xml (src/golden/junit_xml.hpp) with an independent JUnit reader,
Debian's python3-junitparser, and checks each suite's counts of tests, failures and errors, both as
its attributes say and as its test cases are; and that the file is well-formed XML 1.0 (xmllint
--noout where libxml2-utils is installed, Python's expat always). Run by CTest's golden-report:junit
on the sample report (tests/test_golden_report.cpp).

usage: junit_test.py JUNIT_XML "SUITE=TESTS,FAILURES,ERRORS"…
  e.g. junit_test.py build/golden-sample-report/junit.xml "golden frames=5,2,1" "golden states=2,1,0"
Exit 0 when every check passes, 1 with one line per failed check, 2 when it cannot run.
"""
import shutil
import subprocess
import sys
import xml.parsers.expat

sys.dont_write_bytecode = True  # no __pycache__ in the source tree, whoever runs this
from checklist import check, finish  # noqa: E402  (after the line above)


def parse_expectations(arguments):
    expected = {}
    for argument in arguments:
        name, equals, counts = argument.rpartition("=")
        numbers = counts.split(",")
        if not equals or not name or len(numbers) != 3 or not all(n.isdigit() for n in numbers):
            sys.exit(f"junit_test: '{argument}' is not SUITE=TESTS,FAILURES,ERRORS")
        expected[name] = tuple(int(n) for n in numbers)
    return expected


def case_results(case):
    """The case's failure, error and skipped elements (junitparser 2.x gives a list, 1.x one or None)."""
    result = case.result
    if result is None:
        return []
    return list(result) if isinstance(result, list) else [result]


def main():
    if len(sys.argv) < 3:
        sys.exit('usage: junit_test.py JUNIT_XML "SUITE=TESTS,FAILURES,ERRORS"…')
    path, expected = sys.argv[1], parse_expectations(sys.argv[2:])
    try:
        from junitparser import Error, Failure, JUnitXml, Skipped
    except ImportError as e:
        print(f"junit_test: cannot import junitparser ({e}): install python3-junitparser (scripts/deps test)",
              file=sys.stderr)
        return 2

    with open(path, "rb") as f:
        data = f.read()
    try:
        xml.parsers.expat.ParserCreate().Parse(data, True)
        check(True, "expat: well-formed XML")
    except xml.parsers.expat.ExpatError as e:
        check(False, f"expat: well-formed XML ({e})")
    xmllint = shutil.which("xmllint")
    if xmllint:
        run = subprocess.run([xmllint, "--noout", path], capture_output=True, text=True, timeout=60)
        check(run.returncode == 0, "xmllint --noout: well-formed XML" + (f" ({run.stderr.strip()})" if run.returncode else ""))
    else:
        print("note:   no xmllint (Debian's libxml2-utils): checked with expat only")

    report = JUnitXml.fromfile(path)
    suites = {suite.name: suite for suite in report}
    check(sorted(suites) == sorted(expected), f"suites: {sorted(suites)} (expected {sorted(expected)})")
    total = [0, 0, 0]
    for name, (tests, failed, errors) in expected.items():
        suite = suites.get(name)
        if suite is None:
            continue
        cases = list(suite)
        results = [case_results(case) for case in cases]
        counted = (
            len(cases),
            sum(1 for r in results if any(isinstance(x, Failure) for x in r)),
            sum(1 for r in results if any(isinstance(x, Error) for x in r)),
        )
        skipped = sum(1 for r in results if any(isinstance(x, Skipped) for x in r))
        check(counted == (tests, failed, errors),
              f"{name}: its test cases: {counted} tests, failures, errors (expected {(tests, failed, errors)})")
        said = (suite.tests, suite.failures, suite.errors)
        check(said == (tests, failed, errors),
              f"{name}: its attributes: {said} tests, failures, errors (expected {(tests, failed, errors)})")
        check(skipped == 0 and suite.skipped == 0, f"{name}: nothing skipped ({skipped}, attribute {suite.skipped})")
        check(all(case.name and case.classname for case in cases), f"{name}: every case has a name and a classname")
        # Every failure and error says why: a message, and details for the CI's view.
        check(all(x.message for r in results for x in r), f"{name}: every failure and error has a message")
        total = [t + c for t, c in zip(total, counted)]
    root = (report.tests, report.failures, report.errors) if hasattr(report, "tests") else None
    if root is not None:
        check(root == tuple(total), f"<testsuites>: {root} tests, failures, errors (its suites add up to {tuple(total)})")

    return finish("junit_test", path)


if __name__ == "__main__":
    sys.exit(main())
