"""particles: 2D particle systems and rigid bodies, simulated and drawn off screen.

The Python face of particles' C++ library: the same simulations as the `particles` command (the
same bits), rendered frames as numpy arrays, videos, and golden checks.

    import particles
    scenario = particles.Scenario.load("scenarios/cloth.yaml", set={"dt": 0.005})
    sim = particles.Simulation(scenario, threads=2)
    sim.advance(1.0)
    sim.positions          # (N, 2) float64, a read-only view of the state
    sim.render(size=(320, 240))   # a Frame: (h, w, 4) uint8, shown inline in a notebook

docs/api.md lists every class and function, in C++ and in Python.
"""

import numpy as _np

from . import _particles
from ._particles import (
    ArgumentError,
    Background,
    Energy,
    Error,
    GlBackend,
    Integrator,
    Outcome,
    OutputError,
    Raster,
    Renderer,
    Scenario,
    ScenarioError,
    Simulation,
    SimulationError,
    Theme,
    VideoWriter,
    __version__,
    default_threads,
)

__all__ = [
    "ArgumentError",
    "Background",
    "Energy",
    "Error",
    "Frame",
    "GlBackend",
    "Integrator",
    "Outcome",
    "OutputError",
    "Raster",
    "Renderer",
    "Scenario",
    "ScenarioError",
    "Simulation",
    "SimulationError",
    "Theme",
    "VideoWriter",
    "__version__",
    "default_threads",
    "golden",
]


class Frame(_np.ndarray):
    """A rendered frame: an (h, w, 4) uint8 RGBA numpy array, rows from the top.

    A notebook shows it as a picture (_repr_png_); save_png() writes it as a PNG file. Anything numpy does
    with an array works on it; slicing or arithmetic gives plain arrays back where the result is
    not a frame any more.
    """

    def _repr_png_(self):
        if self.ndim != 3 or self.shape[2] not in (3, 4) or self.dtype != _np.uint8:
            return None  # no longer a picture (a slice, a sum): numpy's own repr instead
        return _particles._encode_png(self, False)

    def encode_png(self, alpha=False):
        """The bytes of a PNG file of the frame (RGBA when alpha, else RGB): C++'s Image::encodePng."""
        return _particles._encode_png(self, alpha)

    def save_png(self, path, alpha=False):
        """Writes the frame as a PNG file (RGBA when alpha), whole or not at all: C++'s Image::savePng."""
        _particles._save_png(self, path, alpha)


_particles._set_frame_type(Frame)

from . import golden  # noqa: E402  (particles.golden.check)
