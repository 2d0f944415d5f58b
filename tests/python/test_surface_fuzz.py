"""A property test of the Python surface (beside tests/fuzz/'s libFuzzer harnesses): random
call sequences, with values good and bad, on Scenario, Simulation, Renderer, frames and
VideoWriter. Whatever the sequence, a call either works or raises particles.Error (TypeError for
an argument of a type the signature does not take, KeyboardInterrupt never); the process never
crashes; a refused call changes nothing; the state stays finite unless a SimulationError said so;
no file is left by a video that did not finish.

PARTICLES_SURFACE_FUZZ_SEQUENCES (default 40) sequences of 60 calls each, seeded 0, 1, …: the
same calls on every run; a failure names its seed and call.
"""

import math
import os
import random

import numpy as np
import pytest

import particles
from conftest import scenario_path

SEQUENCES = int(os.environ.get("PARTICLES_SURFACE_FUZZ_SEQUENCES", "40"))
CALLS = 60

NUMBERS = [0, 1, 2, 3, -1, 7, 2**31, 2**63, -(2**63), 0.5, -0.25, 1e-9, 1e300, -1e300, math.nan, math.inf, -math.inf]
TEXTS = ["", "cloth[0][0]", "cloth[24][12]", "link0", "hook", "nope", "cloth[99][0]", "\x00", "é", "[1, 2]", "dt"]
VALUES = NUMBERS + TEXTS + [None, True, False, (1.0, 2.0), [0.0], (math.nan, 0.0), np.zeros(2), object()]
KEYS = ["dt", "integrator", "duration", "implicit_solver", "forces[0].g", "forces[1].kd", "forces[9].ks",
        "grids[0].springs.structural.ks", "particles", "simulation.dt", "render.size", "nope", "", "[", "forces[-1]"]
SCENARIOS = ["cloth", "rigid_chain", "soft_body"]


def any_value(rng):
    return rng.choice(VALUES)


def frame_like(rng):
    h, w = rng.choice([(2, 2), (4, 6), (0, 4), (3, 3), (8, 8)])
    return rng.choice([np.zeros((h, w, 4), np.uint8), np.zeros((h, w, 3), np.uint8), np.zeros((h, w), np.uint8),
                       np.zeros((h, w, 4), np.float32), np.full((h, w, 4), 300, np.int32), "frame", None])


def state_of(sim):
    return (sim.steps, np.array(sim.positions), np.array(sim.velocities))


def run_sequence(seed, tmp_path):
    rng = random.Random(seed)
    scenario = particles.Scenario.load(scenario_path(rng.choice(SCENARIOS)), set={"dt": 0.005})
    sim = particles.Simulation(scenario, threads=rng.choice([1, 2]))
    renderer = particles.Renderer(size=(16, 12), msaa=1)
    video = None
    blew_up = False
    calls = {
        "scenario.set": lambda: scenario.set(rng.choice(KEYS), any_value(rng)),
        "Simulation(scenario)": lambda: particles.Simulation(scenario, threads=rng.choice([None, 1, 2, 0, -3, 5000, "2"])),
        "step": lambda: sim.step(rng.choice([0, 1, 3, -1, 2**40, 2.5, None])),
        "advance": lambda: sim.advance(rng.choice([0.0, 0.01, 0.02, -0.01, math.nan, math.inf, 1e300, "1"])),
        "position": lambda: sim.position(any_value(rng)),
        "set_position": lambda: sim.set_position(any_value(rng), any_value(rng)),
        "set_velocity": lambda: sim.set_velocity(rng.choice([0, 1, -1, 10**9, "cloth[0][0]", "x"]), any_value(rng)),
        "index": lambda: sim.particle_index(rng.choice(TEXTS)),
        "mouse": lambda: (sim.set_mouse_target(any_value(rng), mouse=rng.choice([0, 0, 1, -1])) if rng.random() < 0.7
                          else sim.release_mouse(rng.choice([0, 1]))),
        "mouse_target": lambda: sim.mouse_target(rng.choice([0, 1, -1])),
        "body_index": lambda: sim.body_index(rng.choice(TEXTS)),
        "threads": lambda: setattr(sim, "threads", rng.choice([1, 2, 0, 1025, None, "x"])),
        "read": lambda: (sim.energy(), sim.bodies, sim.particle_names, sim.constraint_error(), sim.penetration(), sim.time),
        "render": lambda: sim.render(size=rng.choice([(16, 12), (0, 0), (-1, 5), None, "x", (20000, 20000)])
                                     if rng.random() < 0.3 else (16, 12),
                                     msaa=rng.choice([1, 3, 4]), theme=rng.choice(["dark", "light", "x"])),
        "renderer.render": lambda: renderer.render(sim),
        "frame.png": lambda: particles._particles._encode_png(frame_like(rng)),
        "video": lambda: open_or_write_video(),
        "view": lambda: sim.positions.__setitem__((0, 0), 1.0),
    }
    names = sorted(calls)

    def open_or_write_video():
        nonlocal video
        if video is None or rng.random() < 0.2:
            if video is not None:
                video.abort()
            video = particles.VideoWriter(tmp_path / rng.choice(["v.mp4", "v.gif", "v.webm", "v.png", "v"]),
                                          fps=rng.choice([10, 0, 2000]))
        else:
            video.write(frame_like(rng))

    for call in range(CALLS):
        name = rng.choice(names)
        before = state_of(sim)
        where = f"seed {seed}, call {call}: {name}"
        try:
            calls[name]()
        except particles.SimulationError:
            blew_up = True
        except (particles.Error, TypeError) as e:
            assert str(e), where
            if name in ("step", "advance", "set_position", "set_velocity", "threads", "view"):
                after = state_of(sim)
                assert after[0] == before[0] and np.array_equal(after[1], before[1], equal_nan=True), where
        except ValueError as e:  # numpy's own: the view is read-only
            assert name == "view" and "read-only" in str(e), where
        if not blew_up:
            assert np.all(np.isfinite(sim.positions)) or name in ("set_position",), where
    if video is not None:
        video.abort()
    sim.close()
    assert not [p for p in tmp_path.iterdir() if p.suffix in (".mp4", ".gif", ".webm")]


@pytest.mark.parametrize("seed", range(SEQUENCES))
def test_random_call_sequences_raise_only_particles_errors(seed, tmp_path):
    run_sequence(seed, tmp_path)
