"""Golden regression checks from Python: a manifest's frames and states against their references,
into a report folder, as `particles golden check` does (the same C++ function runs both)::

    report = particles.golden.check("golden/golden.yaml", output="golden-report")
    if not report:
        print(report.summary)      # open report.html (report.html) to see each failure
"""

import os

from ._particles import FrameCheck, GoldenReport, StateCheck, _golden_check

__all__ = ["FrameCheck", "GoldenReport", "StateCheck", "check"]


def check(manifest, output="golden-report", *, only=None, shard=None, gl="auto", gpu=False, raster=None,
          threshold=None, max_share=None, jobs=None):
    """Checks a golden manifest (golden/README.md) into the report folder `output`, replaced whole
    when done (only a new folder or an earlier report is replaced). Returns a GoldenReport: its
    frames and states, the counts, the summary line and report.html's path; true when every
    check passed.

    only: names of frames and states (a str or a list); shard: "K/N" or (K, N), the K-th of N
    parts; gl: auto, egl or osmesa (or a particles.GlBackend); gpu: draw on a GPU through EGL
    (golden/README.md, "On a GPU"); raster (a name or a particles.Raster),
    threshold, max_share: for entries that do not set their own; jobs: entries checked at once
    (None: half the CPUs). Raises ScenarioError for a manifest that cannot be used, ArgumentError
    for bad options or a folder that may not be replaced, OutputError when the report cannot be
    written. The GIL is released while it runs.
    """
    if isinstance(only, str):
        only = [only]
    return _golden_check(os.fspath(manifest), os.fspath(output), list(only or []), shard, gl, bool(gpu), raster,
                         threshold, max_share, 0 if jobs is None else jobs)
