#!/usr/bin/python3
"""Validates scenario files against `particles schema` with an independent validator (Debian's
python3-jsonschema, draft 7): every file in scenarios/ must pass, every file in tests/schema/bad/
must fail it (each bad file's first line says why), and the loader must reject those too
(`particles check` exits 2), so the schema and the loader agree on both sides.

usage: validate_scenarios.py PARTICLES SOURCE_DIR
"""
import glob
import json
import os
import subprocess
import sys

import jsonschema
import yaml


def main():
    particles, source = sys.argv[1], sys.argv[2]
    schema = json.loads(subprocess.run([particles, "schema"], check=True, capture_output=True, text=True).stdout)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    failures = []
    passed = 0

    good = sorted(glob.glob(os.path.join(source, "scenarios", "*.yaml")))
    bad = sorted(glob.glob(os.path.join(source, "tests", "schema", "bad", "*.yaml")))
    if not good or not bad:
        failures.append(f"no files found ({len(good)} scenarios, {len(bad)} bad files)")
    for path in good:
        with open(path, encoding="utf-8") as f:
            document = yaml.safe_load(f)
        errors = sorted(validator.iter_errors(document), key=lambda e: list(e.path))
        if errors:
            failures.append(f"{path}: fails the schema: {errors[0].message} at {list(errors[0].path)}")
        else:
            passed += 1
    for path in bad:
        with open(path, encoding="utf-8") as f:
            document = yaml.safe_load(f)
        if validator.is_valid(document):
            failures.append(f"{path}: passes the schema, but should fail it")
            continue
        check = subprocess.run([particles, "check", "--quiet", path], capture_output=True, text=True)
        if check.returncode != 2:
            failures.append(f"{path}: fails the schema but `particles check` exits {check.returncode}, not 2")
            continue
        passed += 1

    for failure in failures:
        print(failure)
    print(f"schema: {passed} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
