"""The property test of the library's calls (api_sequences.py): random sequences of create, set,
step, advance, render, write, abort, finish, close, a second thread and fork(), each in a child
interpreter, so that a crash is its signal and a hang its timeout. PARTICLES_API_SEQUENCES (default
16) sequences, seeded 0, 1, …: the same calls on every run; a failure names its seed and call.
scripts/fuzz runs many more.
"""

import os
import pathlib
import subprocess
import sys

import pytest

SEQUENCES = int(os.environ.get("PARTICLES_API_SEQUENCES", "16"))
DRIVER = pathlib.Path(__file__).with_name("api_sequences.py")


@pytest.mark.parametrize("first", range(0, SEQUENCES, 4))
def test_random_call_sequences_never_crash_hang_or_leave_a_file(first, tmp_path):
    seeds = [str(s) for s in range(first, min(first + 4, SEQUENCES))]
    result = subprocess.run([sys.executable, str(DRIVER), str(tmp_path), *seeds], capture_output=True, text=True,
                            timeout=600, env={**os.environ, "PYTHONFAULTHANDLER": "1"})
    assert result.returncode == 0, f"seeds {seeds}: exit {result.returncode}\n{result.stderr[-3000:]}"
