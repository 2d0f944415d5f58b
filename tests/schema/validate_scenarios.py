#!/usr/bin/python3
"""Validates scenario files against `particles schema` with an independent validator (Debian's
python3-jsonschema, draft 7): every file in scenarios/ must pass, every file in tests/schema/bad/
must fail it (each bad file's first line says why), and the loader must reject those too
(`particles check` exits 2), so the schema and the loader agree on both sides.

Golden manifests the same way against `particles schema --golden`: tests/schema/golden/*.yaml and
golden/*.yaml (the project's) pass,
tests/schema/golden/bad/*.yaml fail (the loader's side of both is tests/test_golden_manifest.cpp's,
as no command reads a manifest alone).

usage: validate_scenarios.py PARTICLES SOURCE_DIR
"""
import glob
import json
import os
import subprocess
import sys

import jsonschema
import yaml


def validator_of(particles, *options):
    schema = json.loads(
        subprocess.run([particles, "schema", *options], check=True, capture_output=True, text=True).stdout)
    jsonschema.Draft7Validator.check_schema(schema)
    return jsonschema.Draft7Validator(schema)


def check(validator, good, bad, failures, loader_refuses=None):
    """How many files of `good` pass the schema and of `bad` fail it (and the loader); the rest go to failures."""
    passed = 0
    if not good or not bad:
        failures.append(f"no files found ({len(good)} good, {len(bad)} bad files)")
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
        why = loader_refuses(path) if loader_refuses else None
        if why:
            failures.append(f"{path}: fails the schema but {why}")
            continue
        passed += 1
    return passed


def main():
    particles, source = sys.argv[1], sys.argv[2]
    failures = []

    def check_refuses(path):
        check = subprocess.run([particles, "check", "--quiet", path], capture_output=True, text=True)
        return None if check.returncode == 2 else f"`particles check` exits {check.returncode}, not 2"

    passed = check(validator_of(particles), sorted(glob.glob(os.path.join(source, "scenarios", "*.yaml"))),
                   sorted(glob.glob(os.path.join(source, "tests", "schema", "bad", "*.yaml"))), failures,
                   check_refuses)
    golden = os.path.join(source, "tests", "schema", "golden")
    # The project's own manifests too (golden/golden.yaml, golden/controls.yaml).
    manifests = sorted(glob.glob(os.path.join(golden, "*.yaml")) + glob.glob(os.path.join(source, "golden", "*.yaml")))
    passed += check(validator_of(particles, "--golden"), manifests,
                    sorted(glob.glob(os.path.join(golden, "bad", "*.yaml"))), failures)

    for failure in failures:
        print(failure)
    print(f"schema: {passed} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
