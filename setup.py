"""Builds particles._particles with CMake for `pip install .` (pyproject.toml, README.md).

The module is CMake's target particles_python (python/CMakeLists.txt), built in the checkout's
build/ tree, or in PARTICLES_BUILD_DIR when set: a tree scripts/demo or scripts/test made already
compiles only the module's own files. A new tree is configured as Release, without tests.
pip runs this file through python/build_backend.py, which has checked that this Python has what the
build takes.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT / "python"))
from build_backend import build_dir, cached, pybind11_package_cmake_dir  # noqa: E402 (after the path)


def cmake_version():
    """The version in CMakeLists.txt's project(): the library's, the headers' and this package's."""
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"^project\(particles VERSION (\d+\.\d+\.\d+)", text, re.MULTILINE)
    if not match:
        raise RuntimeError("setup.py: CMakeLists.txt has no project(particles VERSION x.y.z)")
    return match.group(1)


def pybind11_option(tree):
    """-Dpybind11_DIR= for the pybind11 Python package (PyPI's, in an isolated build), whose CMake
    folder CMake does not search; [] when there is none, or when the tree keeps the pybind11 it
    found (Debian's), which outlives an isolated build's, deleted after it."""
    folder = pybind11_package_cmake_dir()
    kept = cached(tree, "pybind11_DIR")
    if folder is None or (kept and (pathlib.Path(kept) / "pybind11Config.cmake").is_file()):
        return []
    return ["-Dpybind11_DIR=" + folder]


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        tree = build_dir()
        # The interpreter the module is for: this one's base (a venv's python is a link to it), so
        # that a tree configured for /usr/bin/python3 is not reconfigured for each venv.
        python = os.path.realpath(getattr(sys, "_base_executable", None) or sys.executable)
        configure = ["cmake", "-S", str(ROOT), "-B", str(tree), "-DPARTICLES_PYTHON=ON"]
        cached_python = cached(tree, "Python_EXECUTABLE")
        if cached_python is None or os.path.realpath(cached_python) != python:
            configure.append("-DPython_EXECUTABLE=" + python)
        configure += pybind11_option(tree)
        if not (tree / "CMakeCache.txt").exists():
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            configure += ["-DCMAKE_BUILD_TYPE=Release", "-DPARTICLES_TESTS=OFF", "-DPARTICLES_BENCH=OFF"]
        jobs = str(len(os.sched_getaffinity(0)))
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(tree), "--target", "particles_python", "-j", jobs], check=True)
        built = tree / "python" / "particles" / ("_particles" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            raise RuntimeError(f"setup.py: CMake built no {built} (is {tree} configured for another Python?)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


# setuptools' own scratch in CMake's tree, beside CMake's files, not over them.
SCRATCH = build_dir() / "setuptools"
SCRATCH.mkdir(parents=True, exist_ok=True)
setup(
    version=cmake_version(),
    ext_modules=[Extension("particles._particles", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(SCRATCH)}, "egg_info": {"egg_base": str(SCRATCH)}},
)
