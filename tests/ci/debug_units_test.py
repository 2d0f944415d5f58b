#!/usr/bin/python3
"""Checks tests/ci/debug_units_to_check.py on two small trees made here, as scripts/test's Debug
tree and build/ would be: compile_commands.json files naming sources compiled by the C++ compiler
given (the one the project's trees use). It must print exactly the Debug units whose compile can
warn otherwise than the Release one's:

  - same.cpp, the same code both ways (it includes <cassert>, whose assert it does not use), and a
    unity batch of it generated in each tree: not printed;
  - asserts.cpp (an assert in its own code), ndebug.cpp (`#ifdef NDEBUG`), optimise.cpp
    (`__OPTIMIZE__`), a unity batch of asserts.cpp, header.cpp (an assert in a project header it
    includes), flags.cpp (compiled without -Wextra in the Release tree) and only_debug.cpp (not
    compiled in the Release tree): printed.

usage: debug_units_test.py CXX
Exit 0 when it prints those and only those, 1 otherwise.
"""
import json
import pathlib
import shlex
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "golden"))
from checklist import check, finish  # noqa: E402

SCRIPT = pathlib.Path(__file__).resolve().parent / "debug_units_to_check.py"

SOURCES = {
    "same.cpp": "#include <cassert>\nint same(int x) { return x + 1; }\n",
    "asserts.cpp": "#include <cassert>\nint asserts(int x) {\n  assert(x > 0);\n  return x;\n}\n",
    "ndebug.cpp": "int ndebug() {\n#ifdef NDEBUG\n  return 1;\n#else\n  return 2;\n#endif\n}\n",
    "optimise.cpp": "int optimise() {\n#ifdef __OPTIMIZE__\n  return 1;\n#endif\n  return 0;\n}\n",
    "checked.hpp": "#pragma once\n#include <cassert>\ninline int checked(int x) {\n  assert(x);\n  return x;\n}\n",
    "header.cpp": "#include \"checked.hpp\"\nint header(int x) { return checked(x); }\n",
    "flags.cpp": "int flags() { return 3; }\n",
    "only_debug.cpp": "int onlyDebug() { return 4; }\n",
}


def commands(cxx, tree, src, options, names, unity, lacking=None):
    """compile_commands.json entries for `names` compiled in `tree` with `options` (less the one
    option `lacking` names for a file), and for each unity batch (a file generated in the tree that
    includes a source) of `unity`."""
    lacking = lacking or {}
    entries = []
    for name in names:
        obj = f"obj/{name}.o"
        own = [o for o in options if o != lacking.get(name)]
        entries.append({"directory": str(tree), "file": str(src / name),
                        "command": shlex.join([cxx, *own, "-I", str(src), "-o", obj, "-c", str(src / name)])})
    for name in unity:
        batch = tree / "unity" / f"{name}.cxx"
        batch.parent.mkdir(parents=True, exist_ok=True)
        batch.write_text(f'#include "{src / name}"\n')
        obj = f"unity/{name}.cxx.o"
        entries.append({"directory": str(tree), "file": str(batch),
                        "command": shlex.join([cxx, *options, "-I", str(src), "-o", obj, "-c", str(batch)])})
    (tree / "compile_commands.json").write_text(json.dumps(entries))


def main():
    cxx = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="particles-debug-units-") as scratch:
        scratch = pathlib.Path(scratch)
        src, debug, release = scratch / "src", scratch / "build-debug", scratch / "build"
        for folder in (src, debug, release):
            folder.mkdir()
        for name, text in SOURCES.items():
            (src / name).write_text(text)
        units = [n for n in SOURCES if n.endswith(".cpp")]
        warnings = ["-Wall", "-Wextra", "-Wpedantic", "-Werror", "-std=c++20"]
        commands(cxx, debug, src, ["-O0", *warnings, f"-I{debug}/include"], units, ["same.cpp", "asserts.cpp"])
        # flags.cpp: the Release tree compiled it without -Wextra.
        commands(cxx, release, src, ["-O3", "-DNDEBUG", "-g1", *warnings, f"-I{release}/include"],
                 [n for n in units if n != "only_debug.cpp"], ["same.cpp", "asserts.cpp"], {"flags.cpp": "-Wextra"})

        result = subprocess.run([sys.executable, str(SCRIPT), str(debug), str(release), "--jobs", "2"],
                                capture_output=True, text=True)
        print(result.stderr, end="")
        check(result.returncode == 0, f"the script exits 0 ({result.returncode})")
        printed = sorted(result.stdout.split())
        expected = sorted(["obj/asserts.cpp.o", "obj/ndebug.cpp.o", "obj/optimise.cpp.o", "obj/header.cpp.o",
                           "obj/flags.cpp.o", "obj/only_debug.cpp.o", "unity/asserts.cpp.cxx.o"])
        check(printed == expected, f"it prints the units that differ ({printed}, expected {expected})")
        check("other options than build/'s: -Wextra" in result.stderr, "it names the option flags.cpp lacks")

        # A tree without compile_commands.json: exit 2, nothing printed.
        (release / "compile_commands.json").unlink()
        result = subprocess.run([sys.executable, str(SCRIPT), str(debug), str(release)], capture_output=True, text=True)
        check(result.returncode == 2 and not result.stdout, f"no compile_commands.json: exit 2 ({result.returncode})")
    return finish("debug_units_test.py", "tests/ci/debug_units_to_check.py")


if __name__ == "__main__":
    sys.exit(main())
