#!/usr/bin/python3
"""Which of the Debug tree's compile units can warn otherwise than the Release tree's: scripts/test
checks the Debug tree for warnings (build-debug/, -fsyntax-only) only where its compile differs
from build/'s, which was compiled with the same warnings as errors. Prints the Debug tree's object
files to compile, one per line (ninja's targets, relative to the Debug tree), and on stderr each
unit's verdict.

    debug_units_to_check.py DEBUG_BUILD RELEASE_BUILD [--jobs N]

Both trees' compile_commands.json (CMAKE_EXPORT_COMPILE_COMMANDS) are read. A Debug unit needs no
compile of its own when build/ compiled the same file (the trees' own paths aside)
  - with the same options, but for the optimisation (-O…), the debug information (-g…) and -DNDEBUG,
  - and the project's own code in it (every line the preprocessor writes from a file that is not a
    system header: the sources, the project's headers, the unity batch) is the same text once
    preprocessed both ways: no assert, `#ifdef NDEBUG` or `__OPTIMIZE__` in it reads otherwise.
Then the front end reads the same project code with the same warning flags in both, and the Debug
tree's warnings (front-end ones: -fsyntax-only has no optimiser) are build/'s. The system headers
do read otherwise (Eigen's and the C++ library's assertions), and their warnings are not shown in
either. Any other unit (one build/ did not compile, other options, other text) is printed.
Exit 0, or 2 when a tree has no compile_commands.json or the Debug tree lists no unit.
"""
import argparse
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys

LINE_MARKER = re.compile(rb'^# \d+ "((?:[^"\\]|\\.)*)"((?: \d)*)$')


def load(build_dir):
    path = os.path.join(build_dir, "compile_commands.json")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        print(f"debug_units_to_check: cannot read {path}: {e}", file=sys.stderr)
        sys.exit(2)


def parse(entry, build_dir):
    """The entry's compiler and options with its own tree's path written <build>, without the
    optimisation, the debug information, NDEBUG, the output and the input; its object file; its
    input (<build>/… when generated in the tree); the options to preprocess it as it is."""
    build = os.path.realpath(build_dir)
    args = shlex.split(entry["command"])
    kept, compared, obj, source = [], [], None, entry["file"]
    i = 0
    while i < len(args):
        a = args[i]
        if a in ("-o", "-c") and i + 1 < len(args):
            if a == "-o":
                obj = args[i + 1]
            i += 2
            continue
        i += 1
        kept.append(a)
        if a.startswith("-O") or a.startswith("-g") or a == "-DNDEBUG":
            continue
        compared.append(a.replace(build, "<build>"))
    key = os.path.realpath(os.path.join(entry["directory"], source)).replace(build, "<build>")
    return {"compared": compared, "object": obj, "key": key, "kept": kept, "source": source,
            "directory": entry["directory"]}


def project_text(unit):
    """The lines the preprocessor writes from files that are not system headers, blank lines left
    out; or None when the unit does not preprocess."""
    result = subprocess.run(unit["kept"] + ["-E", unit["source"]], cwd=unit["directory"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    if result.returncode != 0:
        return None
    lines, own = [], True
    for line in result.stdout.split(b"\n"):
        marker = LINE_MARKER.match(line)
        if marker:
            name, flags = marker.group(1), marker.group(2).split()
            own = b"3" not in flags and not name.startswith(b"<")
        elif own and line.strip():
            lines.append(line)
    return lines


def verdict(debug, release):
    """Why the Debug unit must be compiled, or None when build/'s compile covers it."""
    if release is None:
        return "build/ did not compile it"
    if debug["compared"] != release["compared"]:
        only = sorted(set(debug["compared"]) ^ set(release["compared"]))
        return "other options than build/'s: " + " ".join(only[:6]) if only else "its options in another order"
    mine, theirs = project_text(debug), project_text(release)
    if mine is None or theirs is None:
        return "it does not preprocess"
    if mine != theirs:
        first = next((i for i, (a, b) in enumerate(zip(mine, theirs)) if a != b), min(len(mine), len(theirs)))
        line = mine[first] if first < len(mine) else theirs[first]
        return "its own code reads otherwise in Debug: " + line.decode("utf-8", "replace").strip()[:100]
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("debug_build")
    parser.add_argument("release_build")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()
    debug = [parse(e, args.debug_build) for e in load(args.debug_build)]
    release = {u["key"]: u for u in (parse(e, args.release_build) for e in load(args.release_build))}
    if not debug or any(u["object"] is None for u in debug):
        print(f"debug_units_to_check: {args.debug_build}/compile_commands.json lists no unit with its object file",
              file=sys.stderr)
        return 2
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        reasons = list(pool.map(lambda u: verdict(u, release.get(u["key"])), debug))
    for unit, reason in zip(debug, reasons):
        if reason:
            print(unit["object"])
        print(f"  {unit['object']}: " + (f"to compile: {reason}" if reason else "as build/ compiled it"), file=sys.stderr)
    count = sum(1 for r in reasons if r)
    print(f"debug_units_to_check: {count} of {len(debug)} units to compile; the others are build/'s code "
          "with build/'s warning options", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
