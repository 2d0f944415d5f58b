"""The Python module's targets, each against the C++ API's own benchmark (bench/bench_api.cpp),
measured on this machine, printed as ratios:

  - sim.step() on the 25² cloth: per-step µs in Python ÷ in C++ (target ≤ 1.15), and what the
    call alone costs (sim.step(0)), which noise on a shared machine does not hide;
  - sim.render(size=(320, 240)) of the cloth: frames per second in Python ÷ in C++ (target ≥ 0.9);
  - two Python threads, each stepping its own 316² cloth on one thread: steps per second ÷ one
    thread's (target ≥ 1.7 on two or more free cores: the GIL is released while stepping).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_api.py build/particles_bench

Each number is the best of several repetitions (the least disturbed by other work on the machine).
"""

import json
import pathlib
import subprocess
import sys
import threading
import time

import particles

CLOTH = pathlib.Path(__file__).resolve().parents[1] / "scenarios" / "cloth.yaml"


def best_of(repeats, measure):
    return min(measure() for _ in range(repeats))


def python_step_us():
    sim = particles.Simulation(particles.Scenario.load(CLOTH), threads=1)
    sim.step(50)  # warm: the first steps allocate

    def measure(n=2000):
        started = time.perf_counter()
        for _ in range(n):
            sim.step()
        return (time.perf_counter() - started) / n * 1e6
    return best_of(5, measure)


def python_call_overhead_us():
    """What one sim.step(0) costs: the binding's own work per call (argument conversion, releasing
    and taking back the GIL, the Ctrl-C check), without a step. Steady where whole steps are not:
    on a shared machine two runs of the same 2000 steps differ by 15 %."""
    sim = particles.Simulation(particles.Scenario.load(CLOTH), threads=1)

    def measure(n=20000):
        started = time.perf_counter()
        for _ in range(n):
            sim.step(0)
        return (time.perf_counter() - started) / n * 1e6
    return best_of(5, measure)


def python_render_fps():
    sim = particles.Simulation(particles.Scenario.load(CLOTH), threads=1)
    sim.advance(2.5)
    sim.render(size=(320, 240))  # the GL context, once

    def measure(n=200):
        started = time.perf_counter()
        for _ in range(n):
            sim.render(size=(320, 240))
        return (time.perf_counter() - started) / n
    return 1.0 / best_of(3, measure)


def python_thread_scaling(steps=50):
    scenario = particles.Scenario.load(CLOTH, set={"grids[0].size": "[316, 316]"})
    sims = [particles.Simulation(scenario, threads=1) for _ in range(2)]
    for s in sims:
        s.step()

    def one():
        started = time.perf_counter()
        sims[0].step(steps)
        return time.perf_counter() - started

    def two():
        workers = [threading.Thread(target=s.step, args=(steps,)) for s in sims]
        started = time.perf_counter()
        for w in workers:
            w.start()
        for w in workers:
            w.join()
        return time.perf_counter() - started
    alone, together = min(one() for _ in range(4)), min(two() for _ in range(4))
    return (2 * steps / together) / (steps / alone), steps / alone


def cpp_baseline(bench_binary):
    out = subprocess.run([bench_binary, "--benchmark_filter=BM_Api", "--benchmark_format=json",
                          "--benchmark_repetitions=3", "--benchmark_report_aggregates_only=false"],
                         check=True, capture_output=True, text=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b.get("run_type") == "iteration"]

    def best(name, key):
        return [b[key] for b in runs if b["name"].startswith(name)]
    return {"step_us": min(best("BM_ApiStepCloth25", "us_per_step")) * 1e6,
            "render_fps": max(best("BM_ApiRenderCloth320x240", "fps")),
            "scaling": max(best("BM_ApiStepCloth316/real_time/threads:2", "steps_per_s"))
            / max(best("BM_ApiStepCloth316/real_time/threads:1", "steps_per_s"))}


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    cpp = cpp_baseline(sys.argv[1])
    step_us, overhead_us, fps = python_step_us(), python_call_overhead_us(), python_render_fps()
    scaling, one_thread = python_thread_scaling()
    print(f"sim.step(), 25² cloth:      Python {step_us:.1f} µs, C++ {cpp['step_us']:.1f} µs: "
          f"{step_us / cpp['step_us']:.3f}× (target ≤ 1.15)")
    print(f"  the call itself (step(0)): {overhead_us:.2f} µs: C++'s step + it = "
          f"{(cpp['step_us'] + overhead_us) / cpp['step_us']:.3f}× C++'s step")
    print(f"render 320×240, cloth:      Python {fps:.0f} fps, C++ {cpp['render_fps']:.0f} fps: "
          f"{fps / cpp['render_fps']:.3f}× (target ≥ 0.9)")
    print(f"two threads, 316² cloth:    {scaling:.2f}× one thread's {one_thread:.1f} steps/s (target ≥ 1.7); "
          f"two C++ threads here: {cpp['scaling']:.2f}×")


if __name__ == "__main__":
    main()
