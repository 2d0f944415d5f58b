"""Fixtures of the Python module's tests (tests/python/, run by pytest: CTest's python:pytest and
scripts/test's installed-package stage).

PARTICLES_BINARY names the `particles` program the results are compared with and
PARTICLES_SOURCE_DIR the checkout (for scenarios/); both default to the tree this file is in.
`import particles` is whatever the interpreter finds: <build>/python on PYTHONPATH, or the
package pip installed.
"""

import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("PARTICLES_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = pathlib.Path(os.environ.get("PARTICLES_BINARY", SOURCE_DIR / "build" / "particles"))


def scenario_path(name):
    return str(SOURCE_DIR / "scenarios" / f"{name}.yaml")


@pytest.fixture
def run_particles(tmp_path):
    """Runs the `particles` program with a list of arguments (never a shell line) in tmp_path."""

    def run(*args):
        result = subprocess.run([str(BINARY), *map(str, args)], cwd=tmp_path, capture_output=True, text=True,
                                timeout=600)
        assert result.returncode == 0, result.stderr
        return result

    return run
