#!/usr/bin/python3
"""The checks of tests/golden/browser_test.py and junit_test.py: each prints `ok:` or `FAILED:` with
what it checked, and the script ends with the failed ones listed and exit 1, or exit 0."""
import sys

failures = []


def check(condition, what):
    """Records and prints one check; returns the condition, for checks that later ones depend on."""
    print(("ok:     " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)
    return condition


def finish(program, subject):
    """The exit code: 1 with the failed checks on stderr, 0 when every check passed."""
    if failures:
        print(f"{program}: {len(failures)} check(s) failed on {subject}:", file=sys.stderr)
        for what in failures:
            print(f"  {what}", file=sys.stderr)
        return 1
    print(f"{program}: every check passed on {subject}")
    return 0
