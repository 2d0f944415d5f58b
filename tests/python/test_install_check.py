"""What `pip install .` says to a Python that lacks a piece of the build: pip's build backend
(python/build_backend.py) names each missing piece and the command that adds it in one line, before
setuptools (whose own word for a missing wheel is "error: invalid command 'bdist_wheel'") or CMake
start.

Each case is a real venv of the Python running the tests, made without pip (a fraction of a
second), and given the packages it should have as links on its PYTHONPATH to this Python's own.
pybind11's CMake config is looked for under the prefixes a case names: an empty folder for none,
/usr for Debian's pybind11-dev. No network, no build: the check fails, or passes and is not followed
by a build.
"""

import importlib.metadata
import importlib.util
import os
import pathlib
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

BACKEND = SOURCE_DIR / "python" / "build_backend.py"
DEBIAN_PYBIND11 = pathlib.Path("/usr/lib/cmake/pybind11/pybind11Config.cmake")
needs_debian_pybind11 = pytest.mark.skipif(not DEBIAN_PYBIND11.is_file(), reason="needs Debian's pybind11-dev")


def load_backend():
    """python/build_backend.py as a module, without python/ on sys.path (its particles/ has no
    compiled module)."""
    spec = importlib.util.spec_from_file_location("build_backend", BACKEND)
    module = importlib.util.module_from_spec(spec)
    dont_write_bytecode = sys.dont_write_bytecode
    spec.loader.exec_module(module)
    sys.dont_write_bytecode = dont_write_bytecode  # which the backend sets for pip's process
    return module


README_COMMAND = load_backend().README_COMMAND


def venv(path, system_site_packages=False):
    """A new venv of this Python, without pip (nor setuptools): its interpreter's path."""
    options = ["--system-site-packages"] if system_site_packages else []
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", *options, str(path)], check=True, timeout=120)
    return path / "bin" / "python"


def site_with(path, *names):
    """A folder holding links to this Python's packages `names` and their metadata, for PYTHONPATH:
    a venv that has these packages and no others. Skips the test when this Python lacks one."""
    path.mkdir()
    for name in names:
        spec = importlib.util.find_spec(name)
        if spec is None or not spec.submodule_search_locations:
            pytest.skip(f"{sys.executable} has no {name} to lend")
        package = pathlib.Path(spec.submodule_search_locations[0])
        (path / name).symlink_to(package)
        for metadata in [*package.parent.glob(f"{name}-*.dist-info"), *package.parent.glob(f"{name}-*.egg-info")]:
            (path / metadata.name).symlink_to(metadata)
    return path


def run_backend(python, code, tmp_path, pythonpath=None):
    """Runs `code` with python/build_backend.py imported as `backend`, in `python`, with the build
    tree an empty folder (a tree's cached pybind11_DIR counts as found) and no CMake search paths
    or user site-packages from the environment."""
    env = {key: value for key, value in os.environ.items()
           if key not in ("PYTHONPATH", "pybind11_DIR", "pybind11_ROOT", "CMAKE_PREFIX_PATH")}
    env.update(PARTICLES_BUILD_DIR=str(tmp_path / "tree"), PYTHONDONTWRITEBYTECODE="1", PYTHONNOUSERSITE="1")
    if pythonpath:
        env["PYTHONPATH"] = str(pythonpath)
    prelude = f"import sys; sys.path.insert(0, {str(BACKEND.parent)!r}); import build_backend as backend; "
    return subprocess.run([str(python), "-c", prelude + code], capture_output=True, text=True, env=env,
                          cwd=tmp_path, timeout=120)


def check(python, tmp_path, prefix, pythonpath=None):
    return run_backend(python, f"backend.check([{str(prefix)!r}])", tmp_path, pythonpath)


def the_line(result):
    """The one line a failed check writes, after asserting that it failed with one line alone."""
    assert result.returncode == 1, (result.returncode, result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("particles: "), result.stderr
    return lines[0]


@pytest.fixture
def empty_prefix(tmp_path):
    """A prefix with no pybind11Config.cmake under it: neither Debian's nor any other."""
    prefix = tmp_path / "empty-prefix"
    prefix.mkdir()
    return prefix


def test_a_bare_venv_hears_of_every_piece_from_the_hook_pip_calls_first(tmp_path, empty_prefix):
    python = venv(tmp_path / "venv")
    code = f"backend.cmake_prefixes = lambda: [{str(empty_prefix)!r}]; backend.prepare_metadata_for_build_wheel('.')"
    line = the_line(run_backend(python, code, tmp_path))
    assert f"{python} (a venv of " in line
    for piece in ("setuptools >= 61", "wheel", "pybind11 >= 2.10", "numpy >= 1.21"):
        assert piece in line
    assert f"run `{python} -m pip install 'setuptools>=61' wheel 'pybind11>=2.10' 'numpy>=1.21'`" in line
    assert f"or install as the README does: `{README_COMMAND}`" in line


@needs_debian_pybind11
def test_setuptools_without_wheel_is_told_to_add_wheel_not_left_with_bdist_wheel(tmp_path):
    setuptools = importlib.metadata.version("setuptools")
    if load_backend().version_tuple(setuptools) >= (70, 1):
        pytest.skip(f"setuptools {setuptools} has bdist_wheel of its own")
    python = venv(tmp_path / "venv")
    line = the_line(check(python, tmp_path, "/usr", site_with(tmp_path / "site", "setuptools", "numpy")))
    assert f"lacks wheel (setuptools {setuptools} has no bdist_wheel of its own), which installing" in line
    assert f"run `{python} -m pip install wheel` (from PyPI)" in line
    assert "bdist_wheel'" not in line


def test_pybind11_neither_as_a_package_nor_as_a_cmake_config_is_named(tmp_path, empty_prefix):
    python = venv(tmp_path / "venv", system_site_packages=True)  # Debian's setuptools, wheel, numpy
    line = the_line(check(python, tmp_path, empty_prefix))
    assert "lacks pybind11 >= 2.10 (neither its Python package nor a pybind11Config.cmake CMake finds)" in line
    assert f"run `{python} -m pip install 'pybind11>=2.10'` (from PyPI)" in line


@needs_debian_pybind11
def test_numpy_missing_where_the_build_installs_is_named(tmp_path):
    python = venv(tmp_path / "venv")
    line = the_line(check(python, tmp_path, "/usr", site_with(tmp_path / "site", "setuptools", "wheel")))
    assert "lacks numpy >= 1.21, which installing the module needs" in line
    assert f"run `{python} -m pip install 'numpy>=1.21'` (from PyPI)" in line


@needs_debian_pybind11
def test_debian_python_with_the_packages_of_scripts_deps_passes(tmp_path):
    python = venv(tmp_path / "venv", system_site_packages=True)
    result = check(python, tmp_path, "/usr")
    assert (result.returncode, result.stderr) == (0, "")


def test_a_pybind11_package_means_an_isolated_build_which_leaves_numpy_to_the_install(tmp_path, empty_prefix):
    # PyPI's pybind11 as the check and setup.py use it: its version in the metadata, get_cmake_dir().
    site = site_with(tmp_path / "site", "setuptools", "wheel")
    (site / "pybind11").mkdir()
    (site / "pybind11" / "__init__.py").write_text(f"def get_cmake_dir():\n    return {str(empty_prefix)!r}\n")
    metadata = site / "pybind11-2.13.6.dist-info"
    metadata.mkdir()
    (metadata / "METADATA").write_text("Metadata-Version: 2.1\nName: pybind11\nVersion: 2.13.6\n")
    python = venv(tmp_path / "venv")
    result = run_backend(python, f"backend.check([{str(empty_prefix)!r}]); print(backend.pybind11_package_cmake_dir())",
                         tmp_path, site)
    assert (result.returncode, result.stdout.strip(), result.stderr) == (0, str(empty_prefix), "")


def test_pip_shows_the_line_instead_of_invalid_command_bdist_wheel(tmp_path):
    if importlib.util.find_spec("pip") is None:
        pytest.skip(f"{sys.executable} has no pip")
    python = venv(tmp_path / "venv")  # pip runs its build hooks with this interpreter (--python)
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    env.update(PARTICLES_BUILD_DIR=str(tmp_path / "tree"), PYTHONDONTWRITEBYTECODE="1")
    result = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-build-isolation",
                             "--no-index", "--no-deps", str(SOURCE_DIR)], capture_output=True, text=True, env=env,
                            timeout=300)
    assert result.returncode != 0
    output = result.stdout + result.stderr
    assert f"particles: {python} (a venv of " in output and "which installing the module needs" in output, output
    assert "invalid command 'bdist_wheel'" not in output
    assert not (tmp_path / "tree" / "CMakeCache.txt").exists()  # stopped before CMake


def test_the_message_gives_the_readme_command_as_the_readme_and_install_guide_have_it():
    for page in ("README.md", "docs/install.md"):
        assert README_COMMAND in (SOURCE_DIR / page).read_text(encoding="utf-8"), page
