# Type stubs of particles._particles, the C++ module (python/src/). `import particles` re-exports
# these names; docs/api.md describes each, and help() shows the same docstrings.
import enum
import os
from types import TracebackType
from typing import Literal, Mapping, Optional, Sequence, Tuple, Type, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, os.PathLike[str]]
# A str is YAML text as --set takes it; anything else is written as the YAML of that value.
SettingValue = Union[str, int, float, bool, None, Sequence["SettingValue"], Mapping[str, "SettingValue"], np.generic,
                     npt.NDArray[np.generic]]
# A scenario's `style` section (docs/scenarios.md, "Style") as a dict, key for key as YAML writes it:
# names, colours ("orange", "#4682b4") and lengths ("3px", "0.02m", or a number of metres) as str;
# None takes the scenario's key away (YAML's ~). C++'s particles::Style mirrors the same keys.
ColormapName = Literal["viridis", "magma", "inferno", "plasma", "cividis", "coolwarm", "gray", "viridis_r", "magma_r",
                       "inferno_r", "plasma_r", "cividis_r", "coolwarm_r", "gray_r"]
# "auto", [lo, hi], or {"min": lo, "max": hi, "scale": "linear" or "log"} ({"scale": "log"}: automatic).
StyleRange = Union[Literal["auto"], Sequence[float], Mapping[str, Union[float, Literal["linear", "log"]]]]
Length = Union[str, float]
ParticleStyle = TypedDict("ParticleStyle", {
    "color_by": Optional[Literal["speed", "velocity_x", "velocity_y", "acceleration", "kinetic_energy", "height",
                                 "mass"]],
    "colormap": Optional[ColormapName], "range": Optional[StyleRange], "radius": Optional[Length],
    "color": Optional[str]}, total=False)
SpringStyle = TypedDict("SpringStyle", {
    "color_by": Optional[Literal["strain", "tension", "energy"]], "colormap": Optional[ColormapName],
    "range": Optional[StyleRange], "width": Optional[Length], "color": Optional[str]}, total=False)
BodyStyle = TypedDict("BodyStyle", {
    "color": Optional[str], "outline": Optional[str], "color_by": Optional[Literal["speed", "angular_speed"]],
    "colormap": Optional[ColormapName], "range": Optional[StyleRange]}, total=False)
ColorbarStyle = TypedDict("ColorbarStyle", {
    "for": Optional[Literal["particles", "springs", "bodies"]], "label": Optional[str],
    "position": Optional[Literal["right", "left", "top", "bottom"]]}, total=False)
TrailStyle = TypedDict("TrailStyle", {"seconds": Union[float, Literal["all"], None], "width": Optional[Length],
                                      "color": Optional[str]}, total=False)
ArrowStyle = TypedDict("ArrowStyle", {"of": Literal["velocity", "force"], "scale": Optional[float],
                                      "max": Optional[Length], "color": Optional[str]}, total=False)
StyleSelection = TypedDict("StyleSelection", {
    "particles": Union[str, Sequence[str]], "bodies": Union[str, Sequence[str]], "color": Optional[str],
    "radius": Optional[Length], "trail": Optional[TrailStyle],
    "arrow": Union[Literal["velocity", "force"], ArrowStyle, None], "label": Optional[str]}, total=False)
StyleDict = TypedDict("StyleDict", {
    "particles": Optional[ParticleStyle], "springs": Optional[SpringStyle], "bodies": Optional[BodyStyle],
    "colorbar": Union[bool, ColorbarStyle, None], "title": Optional[str], "scale_bar": Optional[bool],
    "select": Optional[Sequence[StyleSelection]]}, total=False)
# A dict of the section's keys, a style file's text, or None (no style).
Style = Union[StyleDict, Mapping[str, object], str, None]
ParticleRef = Union[int, np.integer, str]
Index = Union[int, np.integer]

class Error(Exception): ...

class ScenarioError(Error, ValueError):
    file: str
    line: int
    column: int
    key_path: str
    message: str
    origin: str

class SimulationError(Error, RuntimeError):
    step: int
    time: float
    integrator: IntegratorName
    dt: float
    reason: str

class OutputError(Error, OSError): ...
class ArgumentError(Error, ValueError): ...

def default_threads() -> int: ...

class Scenario:
    @staticmethod
    def load(path: PathLike, *, set: Optional[Mapping[str, SettingValue]] = None, style: Style = None) -> Scenario: ...
    @staticmethod
    def from_text(yaml: str, label: str = "<text>", *, set: Optional[Mapping[str, SettingValue]] = None,
                  style: Style = None) -> Scenario: ...
    def set(self, path: str, value: SettingValue) -> Scenario: ...
    def set_style(self, style: Style) -> Scenario: ...
    def copy(self) -> Scenario: ...
    def __copy__(self) -> Scenario: ...
    def __deepcopy__(self, memo: object) -> Scenario: ...
    def summary(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def file(self) -> str: ...
    @property
    def integrator(self) -> IntegratorName: ...
    @property
    def dt(self) -> float: ...
    @property
    def duration(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def fps(self) -> float: ...
    @property
    def particle_count(self) -> int: ...
    @property
    def body_count(self) -> int: ...

class Energy:
    @property
    def kinetic(self) -> float: ...
    @property
    def potential(self) -> float: ...
    @property
    def total(self) -> float: ...

# The closed sets of choices (include/particles/choices.hpp): each taken as its name or as a member.
class Integrator(enum.Enum):
    euler: Integrator
    midpoint: Integrator
    rk4: Integrator
    symplectic_euler: Integrator
    verlet: Integrator
    backward_euler: Integrator
    bdf2: Integrator

class Theme(enum.Enum):
    dark: Theme
    light: Theme

class Background(enum.Enum):
    theme: Background
    transparent: Background

class Raster(enum.Enum):
    auto: Raster
    triangles: Raster
    tiles: Raster
    resident: Raster
    cpu: Raster

class GlBackend(enum.Enum):
    auto: GlBackend
    egl: GlBackend
    osmesa: GlBackend

class Outcome(enum.Enum):
    passed: Outcome
    failed: Outcome
    missing: Outcome
    error: Outcome

ThemeChoice = Union[Literal["dark", "light"], Theme]
BackgroundChoice = Union[Literal["theme", "transparent"], Background]
RasterChoice = Union[Literal["auto", "triangles", "tiles", "resident", "cpu"], Raster]
GlBackendChoice = Union[Literal["auto", "egl", "osmesa"], GlBackend]
IntegratorName = Literal["euler", "midpoint", "rk4", "symplectic_euler", "verlet", "backward_euler", "bdf2"]
OutcomeName = Literal["passed", "failed", "missing", "error"]

class Simulation:
    def __init__(self, scenario: Scenario, threads: Optional[Index] = None) -> None: ...
    def step(self, n: Index = 1) -> None: ...
    def advance(self, seconds: float) -> None: ...
    def advance_to(self, t: float) -> None: ...
    @property
    def time(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def dt(self) -> float: ...
    @property
    def integrator(self) -> IntegratorName: ...
    @property
    def threads(self) -> int: ...
    @threads.setter
    def threads(self, threads: Optional[Index]) -> None: ...
    @property
    def particle_count(self) -> int: ...
    @property
    def body_count(self) -> int: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...  # (N, 2), read-only view
    @property
    def velocities(self) -> npt.NDArray[np.float64]: ...  # (N, 2), read-only view
    @property
    def bodies(self) -> np.ndarray: ...  # structured: x, y, angle, omega
    def body(self, body: Index) -> Tuple[float, float, float, float]: ...  # x, y, angle, omega
    def set_threads(self, threads: Optional[Index]) -> None: ...
    def position(self, particle: ParticleRef) -> Tuple[float, float]: ...
    def velocity(self, particle: ParticleRef) -> Tuple[float, float]: ...
    def set_position(self, particle: ParticleRef, xy: Sequence[float]) -> None: ...
    def set_velocity(self, particle: ParticleRef, velocity: Sequence[float]) -> None: ...
    @property
    def mouse_count(self) -> int: ...
    def set_mouse_target(self, xy: Sequence[float], mouse: Index = 0) -> None: ...
    def release_mouse(self, mouse: Index = 0) -> None: ...
    def mouse_target(self, mouse: Index = 0) -> Optional[Tuple[float, float]]: ...
    def energy(self) -> Energy: ...
    def constraint_error(self) -> float: ...
    def penetration(self) -> float: ...
    @property
    def particle_names(self) -> list[str]: ...
    @property
    def body_names(self) -> list[str]: ...
    def particle_index(self, name: str) -> int: ...
    def body_index(self, name: str) -> int: ...
    def render(self, *, size: Optional[Tuple[int, int]] = None, theme: ThemeChoice = "dark", msaa: Index = 4,
               background: BackgroundChoice = "theme", raster: RasterChoice = "auto", gl: GlBackendChoice = "auto",
               gpu: bool = False) -> npt.NDArray[np.uint8]: ...  # a particles.Frame, (h, w, 4)
    def close(self) -> None: ...
    @property
    def closed(self) -> bool: ...
    def __enter__(self) -> Simulation: ...
    def __exit__(self, exc_type: Optional[Type[BaseException]], exc: Optional[BaseException],
                 traceback: Optional[TracebackType]) -> bool: ...

class Renderer:
    def __init__(self, *, size: Optional[Tuple[int, int]] = None, theme: ThemeChoice = "dark", msaa: Index = 4,
                 background: BackgroundChoice = "theme", raster: RasterChoice = "auto",
                 gl: GlBackendChoice = "auto", gpu: bool = False) -> None: ...
    def render(self, simulation: Simulation) -> npt.NDArray[np.uint8]: ...  # a particles.Frame
    @property
    def gl_description(self) -> str: ...

class VideoWriter:
    def __init__(self, path: PathLike, *, fps: Optional[Index] = None, crf: Optional[Index] = None,
                 preset: str = "medium", keyint_seconds: float = 2.0, alpha: bool = False,
                 verbose: bool = False) -> None: ...
    def write(self, frame: npt.ArrayLike) -> None: ...  # (h, w, 4) or (h, w, 3) uint8
    def finish(self) -> None: ...
    def abort(self) -> None: ...
    @property
    def frames(self) -> int: ...
    @property
    def path(self) -> str: ...
    def __enter__(self) -> VideoWriter: ...
    def __exit__(self, exc_type: Optional[Type[BaseException]], exc: Optional[BaseException],
                 traceback: Optional[TracebackType]) -> bool: ...

def _set_frame_type(type: type) -> None: ...
def _encode_png(frame: npt.ArrayLike, alpha: bool = False) -> bytes: ...
def _save_png(frame: npt.ArrayLike, path: PathLike, alpha: bool = False) -> None: ...

class FrameCheck:
    name: str
    scenario: str
    time: str
    control: bool
    outcome: OutcomeName
    message: str
    differing: int
    pixels: int
    largest: int
    actual: str
    expected: str
    diff: str
    reproduce: list[str]

class StateCheck:
    name: str
    scenario: str
    times: list[str]
    outcome: OutcomeName
    message: str
    values: int
    point: str
    quantity: str
    expected: float
    actual: float
    difference: float
    tolerance: float
    reproduce: list[str]

class GoldenReport:
    frames: list[FrameCheck]
    states: list[StateCheck]
    passed: int
    failed: int
    missing: int
    errors: int
    bad_reference: bool
    html: str
    summary: str
    @property
    def all_passed(self) -> bool: ...
    def __bool__(self) -> bool: ...

def _golden_check(manifest: str, output: str, only: list[str], shard: Union[None, str, Tuple[int, int]],
                  gl: GlBackendChoice, gpu: bool, raster: Optional[RasterChoice], threshold: Optional[int],
                  max_share: Optional[float], jobs: int) -> GoldenReport: ...
