"""The `particles` console script of the wheel: runs the program the wheel carries
(particles/bin/particles), with this process's arguments, in this process's place.

A package installed from the sources (`pip install .`) has no program beside it: the build tree's
`particles` is the one to run then, and the message says so.
"""

import os
import pathlib
import sys


def program():
    """The path of the `particles` program that came with this package, or None."""
    path = pathlib.Path(__file__).resolve().parent / "bin" / "particles"
    return path if os.access(path, os.X_OK) else None


def main():
    path = program()
    if path is None:
        sys.stderr.write("particles: this package was installed without its program (the wheel and the "
                         "release archive carry it); run the build tree's `particles` instead\n")
        return 2
    # exec, not a child process: the program's exit status, signals and terminal are the caller's.
    os.execv(path, ["particles"] + sys.argv[1:])
    return 127  # not reached: execv returns only by raising OSError
