"""Random sequences of library calls as a careless program makes them: scenarios made and set,
simulations made on 1 to 3 threads, stepped, advanced, drawn, closed; video writers written to,
aborted, finished; a second Python thread calling into the same objects at once; fork() with the
child going on with them. Whatever the sequence, each call works or raises particles.Error (or
MemoryError, TypeError for a type the signature does not take); the process never crashes,
hangs or leaves a half-written file; a state stays finite unless a SimulationError said so.

    python3 api_sequences.py FOLDER SEED [SEED ...]      # each seed's sequence, in FOLDER

Exits 0 when every sequence held, 1 naming the seed, call and what broke. A crash is the
process's signal, a hang its caller's timeout (tests/python/test_api_sequences.py, scripts/fuzz).
"""

import math
import os
import pathlib
import random
import sys
import threading

import numpy as np

import particles

SOURCE_DIR = pathlib.Path(os.environ.get("PARTICLES_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CALLS = int(os.environ.get("PARTICLES_API_SEQUENCE_CALLS", "40"))
# The longest a thread or a forked child of a sequence may take: past it, the sequence hangs.
HANG_SECONDS = 120
ACCEPTED = (particles.Error, MemoryError, TypeError)
SCENARIOS = ["cloth", "rigid_chain", "rod_pendulum", "collisions"]
SETTINGS = [("dt", 0.004), ("dt", -1.0), ("integrator", "midpoint"), ("integrator", "backward_euler"),
            ("integrator", "nope"), ("duration", 2), ("render.size", [32, 24]), ("render.size", (48, np.int64(36))),
            ("forces[0].g", [0, -1]), ("nope", 1), ("dt", np.float32(0.003)), ("dt", math.nan), ("mouse", [])]


class Broken(Exception):
    """An invariant of the library that a sequence broke."""


class Sequence:
    def __init__(self, folder, seed):
        self.folder = pathlib.Path(folder)
        self.seed = seed
        self.rng = random.Random(seed)
        self.scenarios = []
        self.sims = []        # [Simulation, blew_up]
        self.writers = []     # [VideoWriter, path]
        self.finished = set()  # paths of videos whose finish() returned
        self.lock = threading.Lock()  # the lists above, shared with a second thread of the sequence

    def pick(self, items):
        with self.lock:
            return self.rng.choice(items) if items else None

    # --- the calls ---
    def new_scenario(self):
        name = self.rng.choice(SCENARIOS)
        scenario = particles.Scenario.load(SOURCE_DIR / "scenarios" / f"{name}.yaml",
                                           set={"render.size": [32, 24], "duration": 1})
        with self.lock:
            self.scenarios.append(scenario)

    def set_setting(self):
        scenario = self.pick(self.scenarios)
        if scenario is not None:
            scenario.set(*self.rng.choice(SETTINGS))

    def new_simulation(self):
        scenario = self.pick(self.scenarios)
        if scenario is not None:
            sim = particles.Simulation(scenario, threads=self.rng.choice([1, 2, 3, np.int64(2)]))
            with self.lock:
                self.sims.append([sim, False])

    def stepping(self, call):
        entry = self.pick(self.sims)
        if entry is None:
            return
        try:
            call(entry[0])
        except particles.SimulationError:
            entry[1] = True

    def step(self):
        self.stepping(lambda sim: sim.step(self.rng.choice([0, 1, 5, 20])))

    def advance(self):
        self.stepping(lambda sim: sim.advance(self.rng.choice([0.0, 1 / 30, 0.05, 0.2])))

    def advance_to(self):
        self.stepping(lambda sim: sim.advance_to(sim.time + self.rng.choice([-0.1, 0.0, 0.01, 0.1])))

    def render(self):
        entry = self.pick(self.sims)
        if entry is not None:
            frame = entry[0].render(size=(32, 24), raster=self.rng.choice(["cpu", "cpu", "auto"]))
            if frame.shape != (24, 32, 4):
                raise Broken(f"a 32x24 render gave {frame.shape}")

    def new_writer(self):
        path = self.folder / f"v{self.seed}_{self.rng.randrange(1000)}{self.rng.choice(['.mp4', '.webm', '.gif'])}"
        writer = particles.VideoWriter(path, fps=self.rng.choice([None, 10, 30]), preset="ultrafast")
        with self.lock:
            self.writers.append([writer, path])

    def write(self):
        entry, sim = self.pick(self.writers), self.pick(self.sims)
        if entry is not None:
            frame = sim[0].render(size=(32, 24), raster="cpu") if sim else np.zeros((24, 32, 4), np.uint8)
            entry[0].write(frame)

    def abort(self):
        entry = self.pick(self.writers)
        if entry is not None:
            entry[0].abort()

    def finish(self):
        entry = self.pick(self.writers)
        if entry is not None:
            entry[0].finish()
            with self.lock:
                self.finished.add(entry[1])

    def close(self):
        entry = self.pick(self.sims)
        if entry is not None:
            entry[0].close()

    def read(self):
        entry = self.pick(self.sims)
        if entry is None:
            return
        sim, blew_up = entry
        positions = sim.positions
        if not blew_up and not np.all(np.isfinite(positions)):
            raise Broken("a state that is not finite, with no SimulationError")
        sim.energy(), sim.particle_names[:1], sim.time, sim.steps

    def second_thread(self):
        """A few calls on another thread while this one makes a few: each works or is refused."""
        failures = []
        other = threading.Thread(target=lambda: self.calls(4, failures, nested=True), daemon=True)
        other.start()
        self.calls(4, failures, nested=True)
        other.join(HANG_SECONDS)
        if other.is_alive():
            raise Broken("a second thread's calls hung")
        if failures:
            raise failures[0]

    def fork(self):
        """The child goes on with the same objects for a few calls, then ends; it must end."""
        pid = os.fork()
        if pid == 0:
            code = 0
            inherited = {id(w) for w, _ in self.writers}
            try:
                failures = []
                self.calls(5, failures, nested=True)
                if failures:
                    raise failures[0]
                for entry in list(self.sims):
                    entry[0].close()
                for writer, path in list(self.writers):  # the child's own: aborted, or their files removed
                    if id(writer) not in inherited:
                        writer.abort()
                        if path in self.finished:
                            path.unlink(missing_ok=True)
            except Broken as e:
                print(f"seed {self.seed}: in a forked child: {e}", file=sys.stderr)
                code = 1
            except BaseException as e:  # an exception the library may not raise
                print(f"seed {self.seed}: in a forked child: {type(e).__name__}: {e}", file=sys.stderr)
                code = 2
            os._exit(code)
        deadline = HANG_SECONDS
        while deadline > 0:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            threading.Event().wait(0.05)
            deadline -= 0.05
        else:
            os.kill(pid, 9)
            os.waitpid(pid, 0)
            raise Broken("a forked child hung")
        if os.waitstatus_to_exitcode(status) != 0:
            raise Broken(f"a forked child ended with {os.waitstatus_to_exitcode(status)}")

    CALLS = ["new_scenario", "new_scenario", "set_setting", "new_simulation", "new_simulation", "step", "advance",
             "advance_to", "render", "new_writer", "write", "write", "abort", "finish", "close", "read", "read"]
    RARE = ["second_thread", "fork"]

    def calls(self, count, failures, nested=False):
        for _ in range(count):
            with self.lock:
                name = self.rng.choice(self.CALLS if nested or self.rng.random() < 0.9 else self.RARE)
            try:
                getattr(self, name)()
            except ACCEPTED:
                pass
            except Broken as e:
                failures.append(Broken(f"{name}: {e}"))
                return
            except Exception as e:  # noqa: BLE001 (anything else is a finding)
                failures.append(Broken(f"{name}: {type(e).__name__}: {e}"))
                return

    def run(self):
        failures = []
        self.calls(CALLS, failures)
        for writer, _ in self.writers:
            writer.abort()  # does nothing after finish
        for entry in self.sims:
            entry[0].close()
        if failures:
            raise failures[0]
        left = [p.name for p in self.folder.iterdir() if p.name.startswith(f"v{self.seed}_")]
        unfinished = [name for name in left if self.folder / name not in self.finished]
        if unfinished:
            raise Broken(f"files of videos that never finished: {unfinished}")


def main():
    folder, seeds = sys.argv[1], [int(s) for s in sys.argv[2:]]
    for seed in seeds:
        try:
            Sequence(folder, seed).run()
        except Broken as e:
            print(f"seed {seed}: {e}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
