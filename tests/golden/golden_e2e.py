#!/usr/bin/python3
"""`particles golden` end to end, as a user runs it (golden/README.md), in a scratch folder:

  1. `update` writes the references of two scenarios' frames and states;
  2. `check` passes;
  3. a spring constant changes: `check` exits 1, and report.html, junit.xml and results.json name
     the failing frames, the state failure names a particle; two shards merged equal the one run;
  4. `update --from` the report folder accepts them, and `check` passes again;
  5. a missing reference exits 1 with the command that creates it; `update --missing` creates it;
  6. hostile references (a FIFO, a huge file, a PNG with a bad header) exit 2, never hang;
  7. a bad manifest exits 2 naming file:line:column; -o onto the references is refused.

Usage: golden_e2e.py PARTICLES SOURCE_DIR SCRATCH_DIR
SCRATCH_DIR is emptied first and keeps the failing report of step 3 in SCRATCH_DIR/failing-report
(the browser and JUnit tests read it).
"""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

PARTICLES, SOURCE, SCRATCH = Path(sys.argv[1]).resolve(), Path(sys.argv[2]), Path(sys.argv[3]).resolve()
FAILED = []


def check(condition, what):
    print(("ok    " if condition else "FAIL  ") + what)
    if not condition:
        FAILED.append(what)
    return condition


def run(*args, timeout=300):
    p = subprocess.run([str(PARTICLES), "golden", *args], cwd=SCRATCH, capture_output=True, text=True,
                       timeout=timeout)
    print(f"$ particles golden {' '.join(args)}  → exit {p.returncode}")
    for line in (p.stdout + p.stderr).splitlines()[:40]:
        print("    " + line)
    return p


def results(folder):
    return json.loads((SCRATCH / folder / "results.json").read_text())


def by_name(res):
    return {r["name"]: r for r in res["frames"] + res["states"]}


if SCRATCH.exists():
    shutil.rmtree(SCRATCH)
(SCRATCH / "scenarios").mkdir(parents=True)
(SCRATCH / "golden").mkdir()
for name in ("springs.yaml", "rod_pendulum.yaml"):
    shutil.copy(SOURCE / "scenarios" / name, SCRATCH / "scenarios" / name)
MANIFEST = "golden/golden.yaml"
(SCRATCH / MANIFEST).write_text("""\
# Two scenarios' frames and states (tests/golden/golden_e2e.py).
defaults:
  render: {size: 160x120}
frames:
  - scenario: ../scenarios/springs.yaml
    times: [0.5, 2]
  - scenario: ../scenarios/rod_pendulum.yaml
    times: [1]
states:
  - scenario: ../scenarios/springs.yaml
    times: [0.5, 2]
  - scenario: ../scenarios/rod_pendulum.yaml
    times: [1]
""")
FRAMES = ["springs_t0.5", "springs_t2", "rod_pendulum_t1"]
STATES = ["springs", "rod_pendulum"]

# 1. References made.
p = run("update", MANIFEST)
check(p.returncode == 0, "update writes the references: exit 0")
for name in FRAMES:
    check((SCRATCH / "golden" / f"{name}.png").is_file(), f"golden/{name}.png written")
    check(f"created {name}" in p.stdout, f"update says it created {name}")
for name in STATES:
    check((SCRATCH / "golden" / f"{name}.csv").is_file(), f"golden/{name}.csv written")
state_text = (SCRATCH / "golden" / "springs.csv").read_text()
check(state_text.startswith("t,name,x,y,vx,vy,angle,omega\n") and "\n2,mass_a," in state_text,
      "the state file has the trace's columns, a row per point and time")
p = run("update", MANIFEST)
check(p.returncode == 0 and "5 unchanged" in p.stdout, "a second update changes nothing")

# 2. Passes.
p = run("check", MANIFEST, "-o", "report")
check(p.returncode == 0, "check passes on its own references: exit 0")
check("5 passed" in p.stdout, "the summary line counts 5 passed")
res = results("report")
check(all(r["outcome"] == "passed" for r in res["frames"] + res["states"]) and len(res["frames"]) == 3
      and len(res["states"]) == 2, "results.json: 3 frames and 2 states, all passed")

# 3. A spring constant changed: the frames and the state of that scenario fail.
springs = SCRATCH / "scenarios" / "springs.yaml"
original_springs = springs.read_text()
springs.write_text(original_springs.replace("b: mass_a, rest: 0.5, ks: 50}", "b: mass_a, rest: 0.5, ks: 55}"))
check(springs.read_text() != original_springs, "the test changed mass_a's spring constant")
p = run("check", MANIFEST, "-o", "report")
check(p.returncode == 1, "check after the change: exit 1")
res = by_name(results("report"))
check(res["springs_t2"]["outcome"] == "failed", "results.json: springs_t2 failed")
check(res["rod_pendulum_t1"]["outcome"] == "passed", "results.json: rod_pendulum_t1 still passes")
state = res["springs"]
check(state["outcome"] == "failed", "results.json: the springs state failed")
first = state.get("first_beyond") or state.get("firstBeyond") or {}
check(first.get("point") == "mass_a", f"the state failure names the particle mass_a (got {first.get('point')})")
html = (SCRATCH / "report" / "report.html").read_text()
check("springs_t2" in html and "mass_a" in html, "report.html names the failing frame and the particle")
junit = (SCRATCH / "report" / "junit.xml").read_text()
check('name="springs_t2"' in junit and "<failure" in junit, "junit.xml has a failing testcase springs_t2")
for f in ("actual", "expected", "diff"):
    rel = res["springs_t2"]["files"][f]
    check(bool(rel) and (SCRATCH / "report" / rel).is_file(), f"the failing frame's {f} picture is in the folder")
check("failed springs_t2" in p.stdout, "check lists the failing frame on stdout")
shutil.copytree(SCRATCH / "report", SCRATCH / "failing-report")

# Two shards merged equal the one run.
p1 = run("check", MANIFEST, "--shard", "1/2", "-o", "shard-1")
p2 = run("check", MANIFEST, "--shard", "2/2", "-o", "shard-2")
check(p1.returncode in (0, 1) and p2.returncode in (0, 1), "the shards ran")
p = run("report", "shard-2", "shard-1", "-o", "merged")
check(p.returncode == 1, "the merged report fails as the one run did: exit 1")
one, merged = results("report"), results("merged")


def comparable(res):
    out = []
    for r in res["frames"] + res["states"]:
        r = dict(r)
        r.pop("seconds", None)
        out.append(r)
    return out


check(comparable(one) == comparable(merged), "two shards merged hold the same results as the one run")
check(len(merged["runs"]) == 2, "the merged report lists both runs")
for r in merged["frames"] + merged["states"]:
    for f in r["files"].values():
        if f:
            check((SCRATCH / "merged" / f).read_bytes() == (SCRATCH / "report" / f).read_bytes(),
                  f"merged {f} is the one run's")
p = run("report", "shard-1", "shard-1", "-o", "merged-twice")
check(p.returncode == 2, "merging a shard with itself is refused: exit 2")

# A folder checked with settings over the manifest's (another raster path) is set aside, not
# taken or counted against the others; a report folder may be nested in folders not yet there.
p = run("check", MANIFEST, "--raster", "tiles", "--max-share", "0.0005", "-o", "runs/tiles/report")
check(p.returncode == 1 and (SCRATCH / "runs" / "tiles" / "report" / "report.html").is_file(),
      "check -o into folders not there yet makes them")
before = (SCRATCH / "golden" / "springs_t2.png").read_bytes()
p = run("update", MANIFEST, "--from", "runs/tiles/report")
check(p.returncode == 0 and "ignored runs/tiles/report: checked with --raster tiles --max-share 0.0005" in p.stdout
      and (SCRATCH / "golden" / "springs_t2.png").read_bytes() == before,
      "update --from a folder checked with --raster tiles sets it aside and writes nothing")

# 4. Accepted from the report (the tiles folder beside it changes nothing).
p = run("update", MANIFEST, "--from", "runs/tiles/report", "--from", "report")
check(p.returncode == 0, "update --from the report: exit 0")
check("changed springs_t2" in p.stdout and "changed springs:" in p.stdout, "update --from names what changed")
check("rod_pendulum_t1" not in p.stdout.replace("unchanged", ""), "a passing frame is not rewritten")
p = run("check", MANIFEST, "-o", "report")
check(p.returncode == 0, "check passes after update --from: exit 0")

# Folders that disagree are refused: a report of the old scenario against one of the new.
springs.write_text(original_springs)
p = run("check", MANIFEST, "-o", "report-old")
springs.write_text(original_springs.replace("ks: 50}", "ks: 52}", 1))
p = run("check", MANIFEST, "-o", "report-other")
before = (SCRATCH / "golden" / "springs_t2.png").read_bytes()
p = run("update", MANIFEST, "--from", "report-old", "--from", "report-other")
check(p.returncode == 1 and "refused springs_t2" in p.stdout, "update --from folders that disagree refuses: exit 1")
check((SCRATCH / "golden" / "springs_t2.png").read_bytes() == before, "a refused reference is left as it was")
springs.write_text(original_springs.replace("b: mass_a, rest: 0.5, ks: 50}", "b: mass_a, rest: 0.5, ks: 55}"))

# 5. A missing reference.
(SCRATCH / "golden" / "rod_pendulum_t1.png").unlink()
p = run("check", MANIFEST, "-o", "report")
check(p.returncode == 1, "a missing reference: exit 1")
check("golden update golden/golden.yaml --missing" in p.stdout, "the message names the command that creates it")
check(by_name(results("report"))["rod_pendulum_t1"]["outcome"] == "missing", "results.json: outcome missing")
p = run("update", MANIFEST, "--missing")
check(p.returncode == 0 and "created rod_pendulum_t1" in p.stdout and "1 created, 0 changed, 0 unchanged" in p.stdout,
      "update --missing creates only the missing reference")
p = run("check", MANIFEST, "-o", "report")
check(p.returncode == 0, "check passes again")

# 6. Hostile references: exit 2, reported, never waited on or trusted.
reference = SCRATCH / "golden" / "rod_pendulum_t1.png"
good = reference.read_bytes()
reference.unlink()
os.mkfifo(reference)
p = run("check", MANIFEST, "-o", "report", timeout=120)
check(p.returncode == 2 and "FIFO" in p.stdout + p.stderr, "a FIFO as reference: exit 2, named, not waited on")
reference.unlink()
with open(reference, "wb") as f:
    f.truncate(70 * 1024 * 1024)
p = run("check", MANIFEST, "-o", "report", timeout=120)
check(p.returncode == 2 and "input limit" in p.stdout + p.stderr, "a 70 MiB reference: exit 2, over the input limit")
reference.write_bytes(b"\x89PNG\r\n\x1a\n" + b"\x00\x00\x00\x0dIHDR" + b"\xff" * 40)
p = run("check", MANIFEST, "-o", "report", timeout=120)
check(p.returncode == 2 and by_name(results("report"))["rod_pendulum_t1"]["outcome"] == "error",
      "a PNG with a bad header: exit 2, the check's outcome is error")
# A reference of another size is a failure (the frame changed size), told from its header alone.
subprocess.run([str(PARTICLES), "render", "scenarios/rod_pendulum.yaml", "-o", str(reference), "--at", "1",
                "--size", "80x60", "-q"], cwd=SCRATCH, check=True, timeout=120)
p = run("check", MANIFEST, "-o", "report", timeout=120)
r = by_name(results("report"))["rod_pendulum_t1"]
check(p.returncode == 1 and r["outcome"] == "failed" and "80" in r["message"] and "160" in r["message"],
      "a reference of another size: exit 1, failed, both sizes named")
reference.write_bytes(good)

# 7. Bad input.
(SCRATCH / "golden" / "bad.yaml").write_text("frames:\n  - scenario: ../scenarios/springs.yaml\n    tims: [1]\n")
p = run("check", "golden/bad.yaml", "-o", "report")
check(p.returncode == 2 and "golden/bad.yaml:3:5" in p.stderr, "a misspelt key: exit 2 naming file:line:column")
p = run("check", MANIFEST, "-o", "golden")
check(p.returncode == 2 and (SCRATCH / "golden" / "springs.csv").is_file(), "-o onto the references is refused")
p = run("check", MANIFEST, "--only", "springs_t3", "-o", "report")
check(p.returncode == 2 and "springs_t2" in p.stderr, "--only an unknown name: exit 2 with the closest name")

print(f"\n{len(FAILED)} failed" if FAILED else "\nall passed")
sys.exit(1 if FAILED else 0)
