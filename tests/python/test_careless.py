"""The module under careless or hostile use: objects never initialised, calls racing from two
threads, daemon threads at exit, fork(), FIFOs, huge values, bytes that are not UTF-8, numpy's
scalars where ints are expected. Each case is what a user would type; none may crash, hang or
drift.
"""

import os
import pathlib
import resource
import subprocess
import sys
import textwrap
import threading
import time
import types

import numpy as np
import pytest

import particles
from particles import _particles
from conftest import BINARY, SOURCE_DIR, scenario_path

# A child Python that is expected to finish: much longer than any of them takes, so that a hang
# fails the test instead of blocking the suite.
CHILD_TIMEOUT = 300


def run_python(code, *args, timeout=CHILD_TIMEOUT):
    """Runs `code` in a new interpreter (the same particles), returns the CompletedProcess."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code), *map(str, args)], capture_output=True,
                          text=True, timeout=timeout, env={**os.environ, "PYTHONFAULTHANDLER": "1"})


def small_cloth(**settings):
    return particles.Scenario.load(scenario_path("cloth"), set={"render.size": [64, 48], **settings})


# --- objects made by __new__ without __init__ ---------------------------------------------------

CLASSES = [_particles.Scenario, _particles.Simulation, _particles.Renderer, _particles.VideoWriter, _particles.Energy,
           _particles.FrameCheck, _particles.StateCheck, _particles.GoldenReport]


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_an_object_made_by_new_alone_refuses_every_call_with_an_argument_error(cls):
    made = cls.__new__(cls)
    refused = 0
    for name in dir(cls):
        if name.startswith("__") and name not in ("__repr__", "__enter__", "__exit__", "__bool__", "__copy__"):
            continue
        attribute = getattr(cls, name)
        try:
            if isinstance(attribute, property):
                attribute.fget(made)
            elif name == "__exit__":
                made.__exit__(None, None, None)
            elif callable(attribute) and not isinstance(attribute, type):
                getattr(made, name)()
            else:
                continue
        except particles.ArgumentError as e:
            assert "never initialised" in str(e) or "was closed" in str(e)
            refused += 1
        except TypeError:
            pass  # a method that needs arguments: pybind11 refuses the call before any C++ runs
    assert refused > 0


# --- threads ----------------------------------------------------------------------------------

def test_abort_from_another_thread_while_finish_runs_never_crashes_and_leaves_one_outcome(tmp_path):
    frame = np.zeros((360, 640, 4), np.uint8)
    for attempt in range(6):
        path = tmp_path / f"race{attempt}.mp4"
        video = particles.VideoWriter(path, fps=30, preset="ultrafast")
        for i in range(20):
            frame[..., 0] = i * 10
            video.write(frame)
        outcome = {}

        def finish():
            try:
                video.finish()
                outcome["finish"] = "done"
            except particles.ArgumentError as e:
                outcome["finish"] = str(e)

        finisher = threading.Thread(target=finish)
        finisher.start()
        time.sleep(0.002 * attempt)
        video.abort()
        finisher.join()
        # Either finish came first (the file is whole, abort did nothing) or abort did (no file).
        if outcome["finish"] == "done":
            assert path.stat().st_size > 0
        else:
            assert "aborted" in outcome["finish"] and not path.exists()
        assert [p.name for p in tmp_path.iterdir() if ".partial" in p.name] == []


def test_write_racing_abort_gets_a_message_that_names_no_internal_class(tmp_path):
    video = particles.VideoWriter(tmp_path / "w.webm", fps=30)
    frame = np.zeros((48, 64, 4), np.uint8)
    errors = []

    def writer():
        try:
            for _ in range(1_000_000):  # until abort() stops it
                video.write(frame)
        except particles.Error as e:
            errors.append(str(e))

    thread = threading.Thread(target=writer)
    thread.start()
    time.sleep(0.05)
    video.abort()
    thread.join()
    assert errors and "aborted" in errors[0] and "FramePipeline" not in errors[0]
    assert not (tmp_path / "w.webm").exists()


def test_abort_before_the_first_frame_stops_the_writer_for_good(tmp_path):
    video = particles.VideoWriter(tmp_path / "never.mp4")
    video.abort()
    with pytest.raises(particles.ArgumentError, match="aborted"):
        video.write(np.zeros((48, 64, 4), np.uint8))
    with pytest.raises(particles.ArgumentError, match="aborted"):
        video.finish()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("work", ["advance", "render", "write"])
def test_a_daemon_thread_inside_a_long_call_at_exit_is_a_normal_exit(work, tmp_path):
    result = run_python(f"""
        import sys, threading, time
        import numpy as np
        import particles
        scenario = particles.Scenario.load(sys.argv[1], set={{"render.size": [64, 48]}})
        sim = particles.Simulation(scenario, threads=2)
        video = particles.VideoWriter(sys.argv[2], fps=30)
        started = threading.Event()
        def work():
            started.set()
            while True:
                if "{work}" == "advance":
                    sim.advance(1000.0)
                elif "{work}" == "render":
                    sim.render()
                else:
                    video.write(np.zeros((480, 640, 4), np.uint8))
        threading.Thread(target=work, daemon=True).start()
        started.wait()
        time.sleep(0.3)
        print("main thread done")
        """, scenario_path("cloth"), tmp_path / "daemon.mp4")
    assert result.returncode == 0, result.stderr
    assert "main thread done" in result.stdout and "terminate called" not in result.stderr


# --- fork -------------------------------------------------------------------------------------

def test_a_forked_child_of_a_threaded_simulation_steps_closes_and_exits():
    result = run_python("""
        import os, sys
        import particles
        sim = particles.Simulation(particles.Scenario.load(sys.argv[1]), threads=2)
        sim.advance(0.5)
        before = sim.positions.copy()
        pid = os.fork()
        if pid == 0:
            sim.advance(0.5)   # on workers of the child's own
            child_steps = sim.steps
            sim.close()
            os._exit(0 if child_steps == 100 else 3)
        _, status = os.waitpid(pid, 0)
        sim.advance(0.5)       # the parent's workers are as they were
        print(os.waitstatus_to_exitcode(status), sim.steps)
        """, scenario_path("cloth"))
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["0", "100"]


def test_a_forked_child_of_a_process_that_drew_with_gl_is_told_why_not_and_draws_on_the_cpu():
    # Mesa's rasteriser threads stay in the parent: GL in the child is refused at once, not a hang.
    result = run_python("""
        import os, sys
        import numpy as np
        import particles
        sim = particles.Simulation(particles.Scenario.load(sys.argv[1], set={"render.size": [64, 48]}))
        parent = sim.render(raster="triangles")
        on_cpu = sim.render(raster="cpu")
        pid = os.fork()
        if pid == 0:
            try:
                sim.render(raster="triangles")
                os._exit(3)
            except particles.Error as e:
                if "forked" not in str(e):
                    os._exit(4)
            os._exit(0 if np.array_equal(sim.render(raster="cpu"), on_cpu) else 5)
        _, status = os.waitpid(pid, 0)
        print(os.waitstatus_to_exitcode(status))
        print(np.array_equal(sim.render(raster="triangles"), parent))
        """, scenario_path("cloth"))
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["0", "True"]


# --- FIFOs ------------------------------------------------------------------------------------

def test_a_fifo_with_no_writer_is_refused_at_once_and_other_threads_run_meanwhile(tmp_path):
    fifo = tmp_path / "scenario.yaml"
    os.mkfifo(fifo)
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    thread = threading.Thread(target=ticker)
    thread.start()
    try:
        with pytest.raises(particles.ScenarioError, match="no writer") as caught:
            particles.Scenario.load(fifo)
        assert caught.value.file == str(fifo)
    finally:
        stop.set()
        thread.join()
    result = subprocess.run([str(BINARY), "check", str(fifo)], capture_output=True, text=True, timeout=CHILD_TIMEOUT)
    assert result.returncode == 2 and "no writer" in result.stderr


def test_a_fifo_with_a_writer_is_read_to_its_end(tmp_path):
    fifo = tmp_path / "scenario.yaml"
    os.mkfifo(fifo)
    text = pathlib.Path(scenario_path("rod_pendulum")).read_bytes()
    keeper = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # a reader, so that the writer's open returns
    writer = os.open(fifo, os.O_WRONLY)
    os.write(writer, text[:10])
    loaded = {}
    thread = threading.Thread(target=lambda: loaded.update(scenario=particles.Scenario.load(fifo)))
    thread.start()
    # The load reads on while the writer holds the FIFO open, up to the writer's close.
    os.write(writer, text[10:])
    os.close(writer)
    thread.join()
    os.close(keeper)
    assert loaded["scenario"].name == "rod_pendulum"


# --- memory, time and message size ------------------------------------------------------------

def measured(code):
    """CPU seconds and peak resident MiB of `code` run in a child interpreter, and its result."""
    result = run_python("""
        import resource, subprocess, sys
        child = subprocess.run([sys.executable, "-c", sys.argv[1]], capture_output=True, text=True)
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        print(usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, child.returncode)
        print(child.stderr, file=sys.stderr)
        """, textwrap.dedent(code))
    cpu, peak, code = result.stdout.split()
    return float(cpu), float(peak), int(code), result.stderr


BASELINE = "import particles\n"


def test_a_long_flow_list_is_refused_within_the_hostile_input_bounds():
    # The bounds of tests/test_hostile_input.cpp: 2 s of CPU and 200 MiB, on top of the interpreter's own.
    base_cpu, base_peak, _, _ = measured(BASELINE)
    cpu, peak, code, stderr = measured(BASELINE + textwrap.dedent("""
        try:
            particles.Scenario.from_text("name: a\\ndescription: [" + "1," * 2_000_000 + "1]\\n")
        except particles.ScenarioError as e:
            assert "more than 250000" in str(e) and "--limit nodes" in str(e), e
        else:
            raise SystemExit(3)
        """))
    assert code == 0, stderr
    assert cpu - base_cpu <= 2.0 and peak - base_peak <= 200.0, (cpu, base_cpu, peak, base_peak)


def test_from_text_has_the_file_limit():
    with pytest.raises(particles.ScenarioError, match="more than a scenario's limit of 64 MiB"):
        particles.Scenario.from_text("#" * (64 * 1024 * 1024 + 1))


def test_an_unknown_long_name_is_answered_quickly_on_the_large_cloth():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth"), set={"grids[0].size": [316, 316],
                                                                                     "mouse": "[]"}))
    start = time.process_time()
    with pytest.raises(particles.ArgumentError) as caught:
        sim.particle_index("x" * 2000)
    # A bound on the work, not a speed: the full comparison took 20 s of CPU.
    assert time.process_time() - start < 5.0
    assert len(str(caught.value)) < 400


HUGE = "1" * (10 * 1024 * 1024)


@pytest.mark.parametrize("call", [
    lambda: small_cloth().set("dt", HUGE),
    lambda: small_cloth().set(HUGE, 1),
    lambda: particles.Renderer(theme=HUGE),
    lambda: particles.Renderer(raster=HUGE),
    lambda: particles.Simulation(small_cloth()).particle_index(HUGE),
    lambda: particles.golden.check(str(SOURCE_DIR / "golden" / "golden.yaml"), "/nonexistent/report", only=[HUGE]),
    lambda: particles.VideoWriter("x.mp4", preset=HUGE),
], ids=["set-value", "set-path", "theme", "raster", "particle_index", "golden-only", "preset"])
def test_a_message_quotes_at_most_about_80_bytes_of_a_value_with_its_size(call):
    with pytest.raises(particles.Error) as caught:
        call()
    message = str(caught.value)
    assert len(message) < 1000, message[:300]
    assert "10485760 bytes" in message, message[:300]


def test_control_characters_in_a_value_reach_python_messages_escaped():
    with pytest.raises(particles.ArgumentError) as caught:
        particles.Renderer(theme="dark\x1b[2J\x07")
    assert "\x1b" not in str(caught.value) and "\\x1b[2J\\x07" in str(caught.value)


def test_the_command_line_quotes_a_long_set_value_briefly(tmp_path):
    value = "7" * 100_000  # under the kernel's 128 KiB for one argument
    result = subprocess.run([str(BINARY), "check", scenario_path("cloth"), "--set", "dt=" + value], capture_output=True,
                            text=True, timeout=CHILD_TIMEOUT)
    assert result.returncode == 2 and len(result.stderr) < 1000 and "100003 bytes" in result.stderr, result.stderr[:300]


# --- wrong results ----------------------------------------------------------------------------

def test_advance_once_per_frame_lands_on_the_frames_of_render(tmp_path, run_particles):
    # dt = 0.007 is no divisor of 1/30: without the clock's remainder, 90 frames ended at 2.52 s.
    scenario = small_cloth(dt=0.007)
    sim = particles.Simulation(scenario)
    for _ in range(90):
        sim.advance(1 / 30)
    assert sim.steps == int(3.0 / 0.007 + 1e-9) and sim.time == pytest.approx(3.0, abs=0.007)

    # The documented loop (README, docs/api.md, video_writer.hpp) against `particles render`'s frames.
    run_particles("render", scenario_path("cloth"), "-o", "frames/", "--fps", "30", "--duration", "0.5",
                  "--set", "render.size=[64, 48]", "--dt", "0.007", "--raster", "cpu", "--quiet")
    sim = particles.Simulation(scenario)
    renderer = particles.Renderer(raster="cpu")
    for k in range(15):
        ours = renderer.render(sim)
        ours.save_png(tmp_path / f"ours_{k:06d}.png")
        theirs = (tmp_path / "frames" / f"frame_{k:06d}.png").read_bytes()
        assert (tmp_path / f"ours_{k:06d}.png").read_bytes() == theirs, f"frame {k}"
        sim.advance(1 / 30)

    exact = particles.Simulation(scenario)
    exact.advance_to(15 / 30)  # where the loop's clock is now
    assert exact.steps == sim.steps and exact.time == sim.time
    with pytest.raises(particles.ArgumentError, match="not before"):
        exact.advance_to(0.1)


def test_a_report_folder_given_with_a_trailing_slash_is_written(tmp_path):
    manifest, _ = golden_manifest(tmp_path)
    particles.golden.check(manifest, str(tmp_path / "report") + "/")
    report = particles.golden.check(manifest, str(tmp_path / "report") + "//")  # and replaced
    assert report.missing == 1 and (tmp_path / "report" / "report.html").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["golden.yaml", "report", "s.yaml"]


def golden_manifest(folder):
    (folder / "s.yaml").write_text("name: s\nparticles:\n  - {name: a, pos: [0, 0]}\nsimulation: {duration: 0.1}\n")
    (folder / "golden.yaml").write_text("states:\n  - {scenario: s.yaml, times: [0.1]}\n")
    return str(folder / "golden.yaml"), str(folder / "s.yaml")


def test_checks_into_one_folder_from_several_threads_all_succeed_and_leave_nothing_behind(tmp_path):
    manifest, _ = golden_manifest(tmp_path)
    errors, reports = [], []

    def check():
        try:
            reports.append(particles.golden.check(manifest, str(tmp_path / "report")))
        except particles.Error as e:
            errors.append(str(e))

    threads = [threading.Thread(target=check) for _ in range(9)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == [] and len(reports) == 9
    assert sorted(p.name for p in tmp_path.iterdir()) == ["golden.yaml", "report", "s.yaml"]
    assert (tmp_path / "report" / "results.json").exists()


def test_a_gif_writer_takes_the_gif_default_rate_and_refuses_more_than_gif_shows(tmp_path):
    with particles.VideoWriter(tmp_path / "a.gif") as video:
        video.write(np.zeros((48, 64, 4), np.uint8))
        video.write(np.full((48, 64, 4), 255, np.uint8))
    assert (tmp_path / "a.gif").stat().st_size > 0
    with pytest.raises(particles.ArgumentError) as caught:
        particles.VideoWriter(tmp_path / "b.gif", fps=60)
    assert "fps for GIF must be 1 to 50" in str(caught.value) and "--fps" not in str(caught.value)


def test_a_latin1_scenario_reads_with_its_bytes_shown_and_errors_keep_their_place(tmp_path):
    path = tmp_path / "caf\xe9.yaml"
    path.write_bytes(b"name: caf\xe9\ndescription: cr\xe8me br\xfbl\xe9e\nparticles:\n  - {name: a, pos: [0, 0]}\n")
    scenario = particles.Scenario.load(path)
    assert scenario.name == "caf\\xe9" and scenario.description.startswith("cr\\xe8me")
    assert "caf\\xe9" in repr(scenario) and "caf\\xe9" in scenario.summary()
    bad = tmp_path / "bad.yaml"
    bad.write_bytes(b"name: x\nparticles:\n  - {name: a, pos: [0, 0], m\xe4ss: 1}\n")
    with pytest.raises(particles.ScenarioError) as caught:
        particles.Scenario.load(bad)
    assert caught.value.line == 3 and "m\\xe4ss" in str(caught.value) and caught.value.file == str(bad)


# --- exception types and numpy's scalars --------------------------------------------------------

def test_bad_writer_settings_are_argument_errors(tmp_path):
    for crf in (10**20, True, 1.5):
        with pytest.raises(particles.ArgumentError):
            particles.VideoWriter(tmp_path / "w.mp4", crf=crf)
    video = particles.VideoWriter(tmp_path / "wide.mp4")
    with pytest.raises(particles.ArgumentError, match="at most 16384 px a side"):
        video.write(np.zeros((2, 16386, 4), np.uint8))


def test_golden_outputs_that_may_not_be_written_are_argument_errors(tmp_path):
    manifest, _ = golden_manifest(tmp_path)
    for output in ("", ".", str(tmp_path)):
        with pytest.raises(particles.ArgumentError):
            particles.golden.check(manifest, output)


def test_a_frame_numpy_cannot_copy_is_a_memory_error():
    huge = np.broadcast_to(np.zeros((1, 1, 4), np.uint8), (2**20, 2**20, 4))
    with pytest.raises(MemoryError):
        particles.Frame.encode_png(huge)
    with pytest.raises(MemoryError):
        particles.VideoWriter("never.mp4").write(huge)


def test_numpy_integers_and_any_mapping_are_taken_where_ints_and_dicts_are():
    sim = particles.Simulation(small_cloth(), threads=np.int64(2))
    nearest = np.argmin(np.hypot(*(sim.positions - [0.0, 0.0]).T))
    assert sim.position(nearest) == tuple(sim.positions[nearest])
    sim.set_position(np.int32(3), (np.float32(0.5), np.int16(1)))
    sim.set_velocity(np.uint8(3), np.array([0.25, 0.0]))
    assert sim.position(3) == (0.5, 1.0) and sim.velocity(3) == (0.25, 0.0)
    sim.threads = np.int8(1)
    sim.step(np.int64(2))
    for flag in (True, 2.0):
        with pytest.raises(particles.ArgumentError):
            sim.position(flag)
    settings = types.MappingProxyType({"grids[0].size": [20, 30], "dt": np.float32(0.003), "duration": np.int64(2)})
    scenario = particles.Scenario.load(scenario_path("cloth"), set=settings)
    assert scenario.particle_count == 600 and scenario.dt == float(np.float32(0.003)) and scenario.duration == 2.0
    tricky = 0.1 + 0.2  # 0.30000000000000004: read back exactly
    assert scenario.copy().set("dt", tricky).dt == tricky
    nested = scenario.copy().set("render.size", (np.int64(80), 60)).set("mouse", [{"grab": "cloth[19][10]", "from": 0,
                                                                               "to": 1, "path": [[0.0, 0.5]],
                                                                               "ks": 2}])
    assert nested.summary()


def test_closing_and_views_after_careless_calls_stay_usable():
    sim = particles.Simulation(small_cloth())
    view = sim.positions
    sim.close()
    sim.close()
    assert view.shape[1] == 2 and not view.flags.writeable
    with pytest.raises(particles.ArgumentError, match="closed"):
        sim.step()


def test_choices_are_taken_as_names_or_as_enum_members_and_returned_as_names():
    scenario = small_cloth().set("integrator", particles.Integrator.backward_euler)
    assert scenario.integrator == "backward_euler"
    sim = particles.Simulation(scenario)
    by_name = sim.render(theme="light", raster="cpu", background="transparent")
    by_member = sim.render(theme=particles.Theme.light, raster=particles.Raster.cpu,
                           background=particles.Background.transparent)
    assert np.array_equal(by_name, by_member)
    assert particles.Renderer(gl=particles.GlBackend.auto, raster=particles.Raster.auto) is not None
    assert [m for m in particles.Raster.__members__] == ["auto", "triangles", "tiles", "resident", "cpu"]
    for bad in ({"theme": "sepia"}, {"theme": particles.Raster.cpu}, {"raster": 3}, {"gl": "vulkan"}):
        with pytest.raises(particles.ArgumentError, match="takes"):
            particles.Renderer(**bad)


def test_the_command_line_checks_into_a_report_folder_given_with_a_trailing_slash(tmp_path):
    manifest, _ = golden_manifest(tmp_path)
    for _ in range(2):  # written, then replaced
        result = subprocess.run([str(BINARY), "golden", "check", manifest, "-o", str(tmp_path / "report") + "/"],
                                capture_output=True, text=True, timeout=CHILD_TIMEOUT)
        assert "cannot replace" not in result.stderr and result.returncode in (0, 1), result.stderr
    assert (tmp_path / "report" / "report.html").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["golden.yaml", "report", "s.yaml"]
