"""particles.Scenario and particles.Simulation: the same bits as `particles run --trace`, the
numpy views, bad input, threads and Ctrl-C, through the Python module."""

import _thread
import ast
import csv
import math
import pathlib
import signal
import threading
import time

import numpy as np
import pytest

import particles
from conftest import scenario_path

EXPLODES = """name: explodes
simulation: {integrator: euler, dt: 0.5, duration: 100}
particles:
  - {name: hook, pos: [0, 0], fixed: true}
  - {name: bob, pos: [1, 0]}
forces:
  - {type: spring, a: hook, b: bob, rest: 0.5, ks: 1000000}
"""


def last_rows(trace_path):
    """The last row of each name in a `particles run --trace` CSV, as the doubles it was written from."""
    rows = {}
    with open(trace_path, newline="") as f:
        for row in csv.DictReader(f):
            rows[row["name"]] = tuple(float(row[k]) for k in ("x", "y", "vx", "vy", "angle", "omega"))
    return rows


def test_scenario_loads_with_settings_and_set_chains():
    cloth = particles.Scenario.load(scenario_path("cloth"))
    assert (cloth.name, cloth.integrator, cloth.dt, cloth.particle_count, cloth.body_count) == ("cloth", "rk4", 0.01, 625, 0)
    changed = particles.Scenario.load(scenario_path("cloth"), set={"integrator": "midpoint", "dt": 0.002, "duration": 1})
    assert (changed.integrator, changed.dt, changed.duration, changed.steps) == ("midpoint", 0.002, 1.0, 500)
    assert changed.set("dt", 0.004).set("implicit_solver", "cg") is changed
    assert changed.dt == 0.004
    copy = changed.copy().set("dt", 0.001)
    assert (changed.dt, copy.dt) == (0.004, 0.001)
    assert "cloth" in changed.summary()
    assert "cloth" in repr(changed)


def test_a_bad_setting_is_a_scenario_error_with_its_place_and_the_scenario_stays():
    cloth = particles.Scenario.load(scenario_path("cloth"))
    with pytest.raises(particles.ScenarioError) as caught:
        cloth.set("forces[0].nope", 3)
    e = caught.value
    assert isinstance(e, ValueError) and isinstance(e, particles.Error)
    assert e.file.endswith("cloth.yaml") and "nope" in str(e)
    with pytest.raises(particles.ScenarioError):
        cloth.set("dt", -1.0)
    assert cloth.dt == 0.01
    with pytest.raises(particles.ArgumentError, match="must be a str, int, float, bool, None, a list"):
        cloth.set("dt", object())
    with pytest.raises(particles.ScenarioError, match="expected a number, got a list"):
        cloth.set("dt", [0.1])  # a list is written as one: the scenario says what it takes
    with pytest.raises(particles.ArgumentError, match="finite"):
        cloth.set("dt", float("nan"))
    with pytest.raises(particles.ScenarioError) as caught:
        particles.Scenario.from_text("name: x\nsimulation: {integrator: euler, dt: 0.1}\nparticles: 3\n", label="mine.yaml")
    assert caught.value.file == "mine.yaml" and caught.value.line == 3 and caught.value.column > 0
    with pytest.raises(particles.ScenarioError, match="nowhere.yaml"):
        particles.Scenario.load("nowhere.yaml")


@pytest.mark.parametrize("name,duration", [("cloth", "0.5"), ("soft_body", "3"), ("rigid_chain", "0.3"),
                                           ("cloth_stiff", "0.5")])
@pytest.mark.parametrize("threads", [1, 2])
def test_stepping_gives_the_bits_of_particles_run_trace(run_particles, tmp_path, name, duration, threads):
    run_particles("run", scenario_path(name), "--quiet", "--trace", "trace.csv", "--duration", duration,
                  "--threads", threads)
    rows = last_rows(tmp_path / "trace.csv")
    scenario = particles.Scenario.load(scenario_path(name), set={"duration": duration})
    sim = particles.Simulation(scenario, threads=threads)
    sim.step(scenario.steps // 2)
    sim.advance(scenario.duration - sim.time)  # the rest, as advance counts it
    assert sim.steps == scenario.steps
    assert len(rows) == sim.particle_count + sim.body_count
    positions, velocities = sim.positions, sim.velocities
    mismatched = [n for i, n in enumerate(sim.particle_names)
                  if rows[n][:4] != (positions[i, 0], positions[i, 1], velocities[i, 0], velocities[i, 1])]
    bodies = sim.bodies
    mismatched += [n for j, n in enumerate(sim.body_names)
                   if (rows[n][0], rows[n][1], rows[n][4], rows[n][5])
                   != (bodies["x"][j], bodies["y"][j], bodies["angle"][j], bodies["omega"][j])]
    assert mismatched == []


def test_positions_are_a_live_read_only_view_of_the_state_not_a_copy():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    view = sim.positions
    assert view.shape == (625, 2) and view.dtype == np.float64 and not view.flags.owndata
    pointer = view.__array_interface__["data"][0]
    before = view[-1].copy()
    sim.step(5)
    assert sim.positions.__array_interface__["data"][0] == pointer  # the state's own memory, every time
    assert not np.array_equal(view[-1], before)  # the old view shows the new state
    assert tuple(view[-1]) == sim.position(624)
    assert np.shares_memory(view, sim.positions)
    with pytest.raises(ValueError, match="read-only"):
        view[0, 0] = 1.0
    with pytest.raises(ValueError):
        view.flags.writeable = True
    with pytest.raises(ValueError):
        sim.velocities.setflags(write=True)


def test_a_view_outlives_close_and_the_simulation_refuses_calls_after_it():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    sim.step(3)
    view, last = sim.positions, np.array(sim.positions)
    sim.close()
    assert sim.closed
    del sim
    assert np.array_equal(view, last)  # the view keeps the state's memory
    with particles.Simulation(particles.Scenario.load(scenario_path("cloth"))) as other:
        other.step()
    for call in (lambda: other.step(), lambda: other.positions, lambda: other.time, lambda: other.render()):
        with pytest.raises(particles.ArgumentError, match="closed"):
            call()
    assert "closed" in repr(other)


def test_bad_arguments_are_errors_with_messages():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("rigid_chain")), threads=1)
    with pytest.raises(particles.ArgumentError, match="≥ 0"):
        sim.step(-1)
    for seconds in (float("nan"), 1e300, -1.0, float("inf")):
        with pytest.raises(particles.ArgumentError):
            sim.advance(seconds)
    with pytest.raises(particles.ArgumentError, match="out of range"):
        sim.position(sim.particle_count)
    with pytest.raises(particles.ArgumentError, match="out of range"):
        sim.position(-1)
    with pytest.raises(particles.ArgumentError, match="out of range"):
        sim.set_velocity(10**30, (0, 0))
    with pytest.raises(particles.ArgumentError, match="did you mean"):
        sim.particle_index(sim.particle_names[0] + "x")
    with pytest.raises(particles.ArgumentError):
        sim.body_index("nobody")
    with pytest.raises(particles.ArgumentError, match=r"\(x, y\)"):
        sim.set_position(0, (1.0, 2.0, 3.0))
    with pytest.raises(particles.ArgumentError, match="finite"):
        sim.set_position(0, (float("nan"), 0.0))
    with pytest.raises(particles.ArgumentError, match="threads"):
        sim.threads = 0
    with pytest.raises(particles.ArgumentError, match="threads"):
        particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=2000)
    assert sim.steps == 0


def test_reading_and_changing_the_state():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("rigid_chain")), threads=2)
    assert sim.threads == 2
    sim.threads = 1
    bodies = sim.bodies
    assert bodies.dtype.names == ("x", "y", "angle", "omega") and len(bodies) == sim.body_count > 0
    assert sim.body_index(sim.body_names[-1]) == sim.body_count - 1
    name = sim.particle_names[-1]
    sim.set_position(name, (0.25, -0.5))
    sim.set_velocity(sim.particle_index(name), [1.0, 0.0])
    assert sim.position(name) == (0.25, -0.5) and sim.velocity(name) == (1.0, 0.0)
    e = sim.energy()
    assert math.isclose(e.total, e.kinetic + e.potential) and "kinetic=" in repr(e)
    sim.advance(0.1)
    assert sim.time == pytest.approx(0.1) and sim.constraint_error() >= 0.0 and sim.penetration() >= 0.0


def test_a_blow_up_is_a_simulation_error_naming_step_time_integrator_and_dt():
    sim = particles.Simulation(particles.Scenario.from_text(EXPLODES), threads=1)
    with pytest.raises(particles.SimulationError) as caught:
        sim.advance(100)
    e = caught.value
    assert isinstance(e, RuntimeError)
    assert e.integrator == "euler" and e.dt == 0.5 and e.step >= 1 and e.time == pytest.approx(e.step * 0.5)
    assert f"step {e.step}" in str(e)
    assert sim.steps == e.step - 1  # the last good state


def test_a_second_thread_driving_the_same_simulation_is_refused():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth"), set={"dt": 0.001}), threads=1)
    started = threading.Event()
    failures = []

    def long_advance():
        started.set()
        try:
            sim.advance(20.0)
        except particles.Error as e:
            failures.append(e)

    worker = threading.Thread(target=long_advance)
    worker.start()
    started.wait()
    time.sleep(0.2)  # the worker's advance has the simulation by now: refused is this thread's call
    refused = None
    deadline = time.monotonic() + 60
    while refused is None and worker.is_alive() and time.monotonic() < deadline:
        try:
            sim.step()
        except particles.Error as e:
            refused = e
        time.sleep(0.01)
    worker.join()
    assert failures == []
    assert refused is not None and "another thread" in str(refused)


def test_two_threads_step_their_own_simulations_at_once_to_the_serial_bits():
    scenario = particles.Scenario.load(scenario_path("cloth"), set={"duration": 1})
    serial = particles.Simulation(scenario, threads=1)
    serial.advance(1.0)
    sims = [particles.Simulation(scenario, threads=1) for _ in range(2)]
    workers = [threading.Thread(target=s.advance, args=(1.0,)) for s in sims]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    for s in sims:
        assert np.array_equal(s.positions, serial.positions) and np.array_equal(s.velocities, serial.velocities)


def test_ctrl_c_stops_a_long_advance_at_a_whole_step():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth"), set={"dt": 0.001}), threads=1)
    # Python's own SIGINT handler, as an interactive interpreter has: a process that a shell
    # started in the background inherits SIGINT ignored, and then interrupt_main does nothing.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        timer = threading.Timer(0.3, _thread.interrupt_main)
        timer.start()
        started = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            sim.advance(300.0)  # 300,000 steps, several seconds: a lost interrupt fails in seconds
        timer.join()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - started < 30
    steps = sim.steps
    assert 0 < steps < 300_000
    assert sim.time == pytest.approx(steps * 0.001)
    sim.step()  # still usable
    assert sim.steps == steps + 1


def test_default_threads_follows_particles_threads(monkeypatch):
    monkeypatch.setenv("PARTICLES_THREADS", "3")
    assert particles.default_threads() == 3
    assert particles.Simulation(particles.Scenario.load(scenario_path("cloth"))).threads == 3
    monkeypatch.setenv("PARTICLES_THREADS", "many")
    with pytest.raises(particles.ArgumentError, match="PARTICLES_THREADS"):
        particles.default_threads()


# What pybind11 gives every enum (particles.Theme.light.name, .value), as Python's enum.Enum does.
ENUM_OWN = ("name", "value")


def test_every_public_name_has_a_docstring():
    for name in particles.__all__:
        obj = getattr(particles, name)
        if name == "__version__":
            assert obj.count(".") == 2
            continue
        assert obj.__doc__, name
        for attr, member in vars(obj).items() if isinstance(obj, type) else ():
            if attr in ENUM_OWN and hasattr(obj, "__members__"):
                continue
            if not attr.startswith("_") and (callable(member) or isinstance(member, property)):
                assert getattr(obj, attr).__doc__, f"{name}.{attr}"


def test_the_type_stubs_name_every_class_method_and_property():
    stubs_path = pathlib.Path(particles._particles.__file__).with_name("_particles.pyi")
    assert (stubs_path.parent / "py.typed").is_file()
    stubs = ast.parse(stubs_path.read_text(encoding="utf-8"))
    stubbed = {node.name: {m.name for m in node.body if isinstance(m, ast.FunctionDef)}
               | {a.target.id for a in node.body if isinstance(a, ast.AnnAssign)}
               for node in stubs.body if isinstance(node, ast.ClassDef)}
    functions = {node.name for node in stubs.body if isinstance(node, ast.FunctionDef)}
    for name in particles.__all__:
        obj = getattr(particles, name)
        if name in ("Frame", "__version__", "golden"):  # Python's own, with inline types
            continue
        if not isinstance(obj, type):
            assert name in functions, name
            continue
        assert name in stubbed, name
        for attr in vars(obj):
            if not attr.startswith("_") and not (attr in ENUM_OWN and hasattr(obj, "__members__")):
                assert attr in stubbed[name], f"{name}.{attr}"


def test_moving_the_mouse_is_the_scripted_mouse_held_at_that_target():
    cloth = particles.Scenario.load(scenario_path("cloth"))
    moved = particles.Simulation(cloth, threads=1)
    scripted = particles.Simulation(cloth.copy().set("mouse[0].from", 0).set("mouse[0].to", 1e9)
                                    .set("mouse[0].path", "[[1, -1]]"), threads=1)
    assert moved.mouse_count == 1 and moved.mouse_target() is None  # its window opens at t = 1.5
    moved.set_mouse_target((1, -1))
    assert moved.mouse_target() == (1.0, -1.0)
    moved.advance(1.0)
    scripted.advance(1.0)
    assert np.array_equal(moved.positions, scripted.positions) and np.array_equal(moved.velocities, scripted.velocities)
    moved.set_mouse_target([0.5, -1.2])  # moves on from where it is
    moved.advance(0.5)
    assert moved.position("cloth[24][12]") != scripted.position("cloth[24][12]")
    moved.release_mouse()
    assert moved.mouse_target() is None
    before = moved.energy().potential
    with pytest.raises(particles.ArgumentError, match="out of range"):
        moved.set_mouse_target((0, 0), mouse=1)
    with pytest.raises(particles.ArgumentError, match="finite"):
        moved.set_mouse_target((math.nan, 0))
    assert moved.energy().potential == before
    given = particles.Simulation(particles.Scenario.from_text(
        "name: swing\nsimulation: {integrator: rk4, dt: 0.01}\nparticles:\n  - {name: bob, pos: [1, 0]}\n"
        "mouse:\n  - {grab: bob, from: 0, to: 1, path: [[0, 0]], ks: 5}\n"))
    given.set_mouse_target((2.0, 0.0))
    given.advance(0.5)
    assert given.position("bob")[0] > 1.0
    none = particles.Simulation(particles.Scenario.from_text(
        "name: lone\nsimulation: {integrator: rk4, dt: 0.01}\nparticles:\n  - {name: bob, pos: [1, 0]}\n"))
    with pytest.raises(particles.ArgumentError, match="has none"):
        none.set_mouse_target((0, 0))
