"""The wheel's `particles` console script (particles._command): it runs the program beside the
package in its own place, with the caller's arguments and exit status, and says what to run
where the package has no program (a source install)."""

import os
import pathlib
import shutil
import subprocess
import sys

import particles
import particles._command

COMMAND_SOURCE = pathlib.Path(particles._command.__file__)


def package_copy(tmp_path, with_program):
    """A package folder holding only _command.py (and a bin/particles that reports what it got)."""
    package = tmp_path / "wheel_like"
    package.mkdir()
    shutil.copyfile(COMMAND_SOURCE, package / "_command.py")
    (package / "__init__.py").write_text("")
    if with_program:
        (package / "bin").mkdir()
        program = package / "bin" / "particles"
        program.write_text('#!/bin/sh\necho "argv0=$0 args=$*"\nexit 7\n')
        program.chmod(0o755)
    return package


def run_console_script(tmp_path, *args):
    code = "import sys; from wheel_like._command import main; sys.exit(main())"
    return subprocess.run([sys.executable, "-c", code, *args], cwd=tmp_path, capture_output=True, text=True,
                          timeout=60, env={**os.environ, "PYTHONPATH": str(tmp_path)})


def test_the_console_script_runs_the_program_beside_the_package_with_its_arguments_and_status(tmp_path):
    package_copy(tmp_path, with_program=True)
    result = run_console_script(tmp_path, "render", "a file with spaces.yaml", "--quiet")
    assert result.returncode == 7, result.stderr
    assert "args=render a file with spaces.yaml --quiet" in result.stdout
    # The program itself was run (exec), not a shell named "particles" somewhere on the PATH.
    assert "argv0=" in result.stdout


def test_a_package_without_its_program_says_what_to_run_instead(tmp_path):
    package_copy(tmp_path, with_program=False)
    result = run_console_script(tmp_path, "--version")
    assert result.returncode == 2
    assert "installed without its program" in result.stderr
    assert "build tree's `particles`" in result.stderr


def test_the_program_is_looked_for_beside_the_package_that_was_imported():
    expected = pathlib.Path(particles.__file__).resolve().parent / "bin" / "particles"
    found = particles._command.program()
    assert found is None or found == expected
