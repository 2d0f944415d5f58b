"""pip's build backend for this checkout (pyproject.toml): setuptools' own, after a check that the
Python pip runs has what building the module takes.

Without the check, a Python that lacks a piece fails far from the cause: setuptools older than 70.1
without the wheel package stops with "error: invalid command 'bdist_wheel'", a missing pybind11 or
Python.h is a CMake error, a missing numpy sends pip to a package index an offline machine cannot
reach. A venv made from a pyenv or python.org Python sees none of Debian's packages, even with
--system-site-packages: /usr/lib/python3/dist-packages belongs to /usr/bin/python3 alone. With the
check, every missing piece is named in one line, with the command that adds it, before setuptools
or CMake start.

The check runs in the hooks that build (prepare_metadata_for_build_wheel, build_wheel and their
editable twins); the others are setuptools' own. It imports setuptools only after the check: a
venv of Python 3.12 or later has none.
"""

import importlib.metadata
import importlib.util
import os
import pathlib
import re
import shutil
import sys
import sysconfig
from typing import NamedTuple, Optional

ROOT = pathlib.Path(__file__).resolve().parents[1]

# No __pycache__ in the checkout, whoever runs pip (the tests' rule too). The import that loaded this
# file has written its bytecode before running it, so that goes again.
sys.dont_write_bytecode = True
try:
    pathlib.Path(importlib.util.cache_from_source(__file__)).unlink()
    pathlib.Path(importlib.util.cache_from_source(__file__)).parent.rmdir()
except OSError:
    pass

# The command of the README, which gives Debian's Python everything below (scripts/deps python).
README_COMMAND = (
    "scripts/deps python && /usr/bin/python3 -m venv --system-site-packages .venv"
    " && .venv/bin/pip install --no-build-isolation ."
)

SETUPTOOLS_MIN = (61,)  # [project] in pyproject.toml
SETUPTOOLS_WITH_BDIST_WHEEL = (70, 1)  # before it, the wheel package provides bdist_wheel
PYBIND11_MIN = (2, 10)  # python/CMakeLists.txt: find_package(pybind11 2.10 CONFIG)
NUMPY_MIN = (1, 21)  # pyproject.toml's dependencies


class Missing(NamedTuple):
    name: str  # as the message names it
    why: str  # what was seen, for the message; "" when "lacks" says it all
    pip: Optional[str]  # what `pip install` takes to add it, or None when pip cannot


def version_tuple(text):
    """(2, 10, 3) of "2.10.3" or "2.10.3.dev1"; () when text has no leading number."""
    match = re.match(r"\d+(\.\d+)*", text or "")
    return tuple(int(part) for part in match.group(0).split(".")) if match else ()


def installed_version(name):
    """The version of the distribution `name` that this Python imports, "" when it has no metadata
    (then any version passes), None when it has not the module at all."""
    if importlib.util.find_spec(name) is None:
        return None
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return ""


def requirement(name, minimum):
    """A Missing for the package `name` when this Python lacks it or has one older than minimum."""
    version = installed_version(name)
    wanted = name + " >= " + ".".join(map(str, minimum))
    spec = f"'{name}>={'.'.join(map(str, minimum))}'"
    if version is None:
        return Missing(wanted, "", spec)
    if version and version_tuple(version) < minimum:
        return Missing(wanted, f"it has {version}", spec)
    return None


def build_dir():
    """CMake's tree for the module: PARTICLES_BUILD_DIR, or the checkout's build/."""
    return pathlib.Path(os.environ.get("PARTICLES_BUILD_DIR") or ROOT / "build").resolve()


def cached(tree, key):
    """The value of `key` in tree's CMakeCache.txt, or None."""
    try:
        cache = (tree / "CMakeCache.txt").read_text(encoding="utf-8", errors="replace")
    except FileNotFoundError:
        return None
    match = re.search(r"^" + re.escape(key) + r":[A-Z]+=(.*)$", cache, re.MULTILINE)
    return match.group(1) if match else None


def pybind11_package_cmake_dir():
    """The CMake folder of the pybind11 Python package (PyPI's), when this Python has one new
    enough; None otherwise."""
    version = installed_version("pybind11")
    if version is None or (version and version_tuple(version) < PYBIND11_MIN):
        return None
    import pybind11

    try:
        return pybind11.get_cmake_dir()
    except ImportError:  # its words for a package without its CMake files
        return None


def cmake_prefixes():
    """The prefixes CMake's find_package(CONFIG) searches, in its documented order less the package
    registries: <name>_ROOT and CMAKE_PREFIX_PATH from the environment, the PATH's folders (one
    ending in bin/ or sbin/ as its parent), then the system's /usr/local, /usr and /."""
    prefixes = []
    for variable in ("pybind11_ROOT", "CMAKE_PREFIX_PATH"):
        prefixes += [entry for entry in os.environ.get(variable, "").split(os.pathsep) if entry]
    for entry in os.environ.get("PATH", "").split(os.pathsep):
        if entry:
            path = pathlib.Path(entry)
            prefixes.append(str(path.parent if path.name in ("bin", "sbin") else path))
    return prefixes + ["/usr/local", "/usr", "/"]


def config_version(folder):
    """The version in folder's pybind11ConfigVersion.cmake, "" when it says none (any passes), None
    when folder has no pybind11Config.cmake."""
    folder = pathlib.Path(folder)
    if not any((folder / name).is_file() for name in ("pybind11Config.cmake", "pybind11-config.cmake")):
        return None
    for name in ("pybind11ConfigVersion.cmake", "pybind11-config-version.cmake"):
        try:
            text = (folder / name).read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue
        match = re.search(r'set\(PACKAGE_VERSION "([^"]*)"\)', text)
        if match:
            return match.group(1)
    return ""


def pybind11_config_dirs(prefixes):
    """The folders under prefixes where CMake looks for pybind11Config.cmake (its search procedure
    on Unix, <prefix>/(lib/<arch>|lib*|share)/cmake/<name>*/ and its other forms), and the folders
    named by pybind11_DIR in the environment and in the build tree's cache."""
    folders = [os.environ.get("pybind11_DIR"), cached(build_dir(), "pybind11_DIR")]
    arch = sysconfig.get_config_var("MULTIARCH")
    libs = ([f"lib/{arch}"] if arch else []) + ["lib", "lib64", "lib32", "libx32", "share"]
    for prefix in map(pathlib.Path, prefixes):
        folders += [prefix, prefix / "cmake", prefix / "CMake"]
        for lib in libs:
            folders += prefix.glob(f"{lib}/cmake/pybind11*")
            folders += prefix.glob(f"{lib}/pybind11*")
            folders += prefix.glob(f"{lib}/pybind11*/cmake")
        folders += prefix.glob("pybind11*")
        folders += prefix.glob("pybind11*/cmake")
    return [folder for folder in folders if folder]


def pybind11_found(prefixes):
    """Whether CMake can find a pybind11 >= 2.10: the Python package's (setup.py passes its folder as
    pybind11_DIR) or a pybind11Config.cmake under prefixes (Debian's pybind11-dev in /usr)."""
    if pybind11_package_cmake_dir() is not None:
        return True
    for folder in pybind11_config_dirs(prefixes):
        version = config_version(folder)
        if version is not None and (not version or version_tuple(version) >= PYBIND11_MIN):
            return True
    return False


def missing_pieces(prefixes=None):
    """What building the module with this Python lacks, as a list of Missing (empty: nothing).

    prefixes: where to look for pybind11's CMake config; cmake_prefixes() when None.
    """
    missing = []
    setuptools = requirement("setuptools", SETUPTOOLS_MIN)
    if setuptools:
        missing.append(setuptools)
    setuptools_version = installed_version("setuptools")
    has_bdist_wheel = setuptools_version and version_tuple(setuptools_version) >= SETUPTOOLS_WITH_BDIST_WHEEL
    if not has_bdist_wheel and installed_version("wheel") is None:
        why = f"setuptools {setuptools_version} has no bdist_wheel of its own" if setuptools_version else ""
        missing.append(Missing("wheel", why, "wheel"))
    if not pybind11_found(cmake_prefixes() if prefixes is None else prefixes):
        missing.append(Missing("pybind11 >= 2.10", "neither its Python package nor a pybind11Config.cmake CMake finds",
                               "'pybind11>=2.10'"))
    # numpy is the module's to run, not to build. A frontend that isolates the build installs
    # pyproject.toml's build requirements, pybind11's Python package among them, and leaves numpy
    # to the install; without that package the build is not isolated, and installs into this very
    # Python, which must have numpy already where no package index is reachable.
    if installed_version("pybind11") is None:
        numpy = requirement("numpy", NUMPY_MIN)
        if numpy:
            missing.append(numpy)
    if shutil.which("cmake") is None:
        missing.append(Missing("CMake", "no cmake on PATH", None))
    headers = pathlib.Path(sysconfig.get_paths()["include"]) / "Python.h"
    if not headers.is_file():
        missing.append(Missing("Python's headers", f"no {headers}", None))
    return missing


def interpreter():
    """This Python as a user would name it: sys.executable, and the Python a venv was made from."""
    base = getattr(sys, "_base_executable", None)
    if sys.prefix != sys.base_prefix and base:
        return f"{sys.executable} (a venv of {os.path.realpath(base)})"
    return sys.executable


def message(missing):
    """The one line that names what is missing and the commands that add it."""
    names = [f"{piece.name} ({piece.why})" if piece.why else piece.name for piece in missing]
    listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
    readme = f"install as the README does: `{README_COMMAND}`"
    if all(piece.pip for piece in missing):
        pip = " ".join(piece.pip for piece in missing)
        fix = f"run `{sys.executable} -m pip install {pip}` (from PyPI), or {readme}"
    else:
        fix = readme
    return f"particles: {interpreter()} lacks {listed}, which installing the module needs: {fix}"


def check(prefixes=None):
    """Exits with message() on stderr when this Python lacks a piece; returns otherwise."""
    missing = missing_pieces(prefixes)
    if missing:
        print(message(missing), file=sys.stderr, flush=True)
        raise SystemExit(1)


def setuptools_backend():
    from setuptools import build_meta

    return build_meta


def checked(hook):
    def run(*args, **kwargs):
        check()
        return getattr(setuptools_backend(), hook)(*args, **kwargs)

    run.__name__ = hook
    return run


prepare_metadata_for_build_wheel = checked("prepare_metadata_for_build_wheel")
build_wheel = checked("build_wheel")
prepare_metadata_for_build_editable = checked("prepare_metadata_for_build_editable")
build_editable = checked("build_editable")


def __getattr__(name):
    """The other hooks (get_requires_for_build_*, build_sdist) as setuptools has them."""
    if name.startswith("__"):
        raise AttributeError(name)
    return getattr(setuptools_backend(), name)
