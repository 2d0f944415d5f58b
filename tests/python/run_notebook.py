"""Executes a notebook with the interpreter running this script as its kernel, from the notebook's
own folder, and fails on the first cell that raises; then checks that it showed frames (PNG
outputs). Used by CTest's python:notebook and scripts/test's installed-package stage.

    python3 tests/python/run_notebook.py examples/python/cloth.ipynb [min_pngs]
"""

import json
import os
import pathlib
import sys
import tempfile

import nbclient
import nbformat


def main():
    notebook = pathlib.Path(sys.argv[1]).resolve()
    min_pngs = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    nb = nbformat.read(notebook, as_version=4)
    with tempfile.TemporaryDirectory() as jupyter:
        # The kernel is this interpreter (a venv's python sees the package pip put there), not the
        # system-wide kernel spec's /usr/bin/python3: JUPYTER_PATH's specs come first.
        spec = pathlib.Path(jupyter) / "kernels" / "python3"
        spec.mkdir(parents=True)
        (spec / "kernel.json").write_text(json.dumps({
            "argv": [sys.executable, "-Xfrozen_modules=off", "-m", "ipykernel_launcher", "-f", "{connection_file}"],
            "display_name": "Python 3", "language": "python"}))
        os.environ["JUPYTER_PATH"] = jupyter + os.pathsep + os.environ.get("JUPYTER_PATH", "")
        os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # the kernel's debugger: no note on frozen modules
        client = nbclient.NotebookClient(nb, kernel_name="python3", timeout=600,
                                         resources={"metadata": {"path": str(notebook.parent)}})
        client.execute()
    pngs = sum(1 for cell in nb.cells if cell.cell_type == "code" for out in cell.get("outputs", [])
               if "image/png" in out.get("data", {}))
    if pngs < min_pngs:
        sys.exit(f"{notebook}: ran, but showed {pngs} PNG outputs, expected at least {min_pngs}")
    print(f"{notebook.name}: every cell ran, {pngs} pictures shown")


if __name__ == "__main__":
    main()
