"""Builds particles._particles with CMake for `pip install --no-build-isolation .` (pyproject.toml).

The module is CMake's target particles_python (python/CMakeLists.txt), built in the checkout's
build/ tree, or in PARTICLES_BUILD_DIR when set: a tree scripts/demo or scripts/test made already
compiles only the module's own files. A new tree is configured as Release, without tests.
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


def cmake_version():
    """The version in CMakeLists.txt's project(): the library's, the headers' and this package's."""
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"^project\(particles VERSION (\d+\.\d+\.\d+)", text, re.MULTILINE)
    if not match:
        raise RuntimeError("setup.py: CMakeLists.txt has no project(particles VERSION x.y.z)")
    return match.group(1)


def cached_python(build_dir):
    """The interpreter the tree's CMake cache builds the module for, or None."""
    try:
        cache = (build_dir / "CMakeCache.txt").read_text(encoding="utf-8", errors="replace")
    except FileNotFoundError:
        return None
    match = re.search(r"^Python_EXECUTABLE:[A-Z]+=(.*)$", cache, re.MULTILINE)
    return match.group(1) if match else None


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = pathlib.Path(os.environ.get("PARTICLES_BUILD_DIR") or ROOT / "build").resolve()
        # The interpreter the module is for: this one's base (a venv's python is a link to it), so
        # that a tree configured for /usr/bin/python3 is not reconfigured for each venv.
        python = os.path.realpath(getattr(sys, "_base_executable", None) or sys.executable)
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DPARTICLES_PYTHON=ON"]
        cached = cached_python(build_dir)
        if cached is None or os.path.realpath(cached) != python:
            configure.append("-DPython_EXECUTABLE=" + python)
        if not (build_dir / "CMakeCache.txt").exists():
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            configure += ["-DCMAKE_BUILD_TYPE=Release", "-DPARTICLES_TESTS=OFF", "-DPARTICLES_BENCH=OFF"]
        jobs = str(len(os.sched_getaffinity(0)))
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "particles_python", "-j", jobs], check=True)
        built = build_dir / "python" / "particles" / ("_particles" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            raise RuntimeError(f"setup.py: CMake built no {built} (is {build_dir} configured for another Python?)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


(ROOT / "build" / "setuptools").mkdir(parents=True, exist_ok=True)
setup(
    version=cmake_version(),
    ext_modules=[Extension("particles._particles", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own scratch beside CMake's, not over it.
    options={"build": {"build_base": str(pathlib.Path("build") / "setuptools")},
             "egg_info": {"egg_base": str(pathlib.Path("build") / "setuptools")}},
)
