#!/usr/bin/env python3
"""Runs the `particles` commands the documentation shows, as a reader would copy them, so that a
page never shows a command that no longer works.

    doc_commands.py PARTICLES SOURCE_DIR SCRATCH PAGE...

Every line of every ```sh block of each PAGE (relative to SOURCE_DIR) is either a `particles`
command, which is run here in order, in SCRATCH (a new folder holding copies of the inputs the
pages name: scenarios/, golden/ and the style files of docs/gallery/), or one of the commands that
other tests run (ELSEWHERE below, each with the test that runs it). Any other line fails the
test, as does a command that exits otherwise than the page's comment says (0, unless the comment
says "exit N here").

Runs are shortened, never otherwise changed: a `render`, `run` or `stability` without --duration
is given one just long enough for its --at and --frames (else 0.1 s, six frames of the demos),
and the copies of the sweep files have their studies' `duration` set to 0.1 s. Commands are run as
argument lists, never through a shell; `> FILE` sends stdout to FILE.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

# Commands the pages show that this test does not run, and the test or stage that does.
ELSEWHERE = {
    "scripts/demo": "scripts/test, stage \"scripts/demo (the README's first command)\"",
    "scripts/test": "CI (.ci/run)",
    "scripts/make-gallery": "ctest docs:gallery (tests/docs/gallery_test.py)",
    "scripts/deps python && /usr/bin/python3 -m venv --system-site-packages .venv && .venv/bin/pip install --no-build-isolation .":
        "scripts/test, stage \"the Python module installed by pip into a venv\"",
    "tar -xJf particles-0.1.0-linux-x86_64.tar.xz && particles-0.1.0-linux-x86_64/bin/particles --version":
        "scripts/release-check (.ci/run's release stage), on bare Debian 12 and 13 roots",
    "python3 -m pip install particles-0.1.0-cp311-cp311-manylinux_2_36_x86_64.whl":
        "scripts/release-check (.ci/run's release stage), into a venv of a bare Debian 12 root",
    "sudo apt install ./particles_0.1.0-1~deb12_amd64.deb":
        "scripts/release-check (.ci/run's release stage), on a bare Debian 12 root",
    "cmake --install build --prefix ~/opt/particles":
        "ctest package:install-and-build (tests/package/package_test.sh)",
    "cmake -S examples/cpp -B example-build -DCMAKE_PREFIX_PATH=~/opt/particles && cmake --build example-build":
        "ctest package:install-and-build (tests/package/package_test.sh)",
}

# Files the pages' commands take as the reader's own: the manifest of the README's golden example.
READERS_FILES = {
    "mine/golden.yaml": """frames:
  - scenario: ../scenarios/springs.yaml
    times: [0.5, 2]
states:
  - scenario: ../scenarios/springs.yaml
    times: [0.5, 2]
""",
}

# The exit code a command's comment promises for this very run ("# exit 1 here: …"); else 0.
EXPECTED_EXIT = re.compile(r"#.*?\bexit (\d) here\b")


def sh_blocks(text):
    """The ```sh blocks of a markdown page: (line number of the block's first line, its lines)."""
    blocks, current, start = [], None, 0
    for number, line in enumerate(text.split("\n"), 1):
        if current is None and line.strip() == "```sh":
            current, start = [], number + 1
        elif current is not None and line.strip() == "```":
            blocks.append((start, current))
            current = None
        elif current is not None:
            current.append(line)
    return blocks


def commands(block_start, lines):
    """Whole commands of a block (continuation lines joined), with their line numbers and comments."""
    out, pending, first = [], "", 0
    for offset, line in enumerate(lines):
        if not pending:
            first = block_start + offset
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        whole = pending + line
        pending = ""
        if whole.strip():
            out.append((first, whole))
    return out


def duration_for(argv):
    """The --duration that keeps a shortened render's --at and --frames valid: in simulated seconds."""
    needed = 0.1
    if "--at" in argv:
        needed = max(needed, float(argv[argv.index("--at") + 1]) + 0.1)
    if "--frames" in argv:
        first, _, last = argv[argv.index("--frames") + 1].partition(":")
        frames = int(last) if last else int(first) + 30
        needed = max(needed, frames / 60 + 0.1)  # the demos' 60 fps
    return f"{needed:g}"


def shortened(argv):
    if len(argv) > 1 and argv[1] in ("render", "run", "stability") and "--duration" not in argv:
        scenario = argv[2]
        if scenario.endswith("cloth_million.yaml"):
            return argv + ["--duration", "0.02"]  # one frame of a million particles
        return argv + ["--duration", duration_for(argv)]
    return argv


def main():
    particles, source, scratch, pages = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    if os.path.exists(scratch):
        shutil.rmtree(scratch)
    os.makedirs(os.path.join(scratch, "docs"))
    for folder in ("scenarios", "golden"):
        shutil.copytree(os.path.join(source, folder), os.path.join(scratch, folder),
                        ignore=shutil.ignore_patterns("*.md", "CMakeLists.txt"))
    # The gallery's style files, without its pictures: the page's commands write them anew.
    shutil.copytree(os.path.join(source, "docs", "gallery"), os.path.join(scratch, "docs", "gallery"),
                    ignore=shutil.ignore_patterns("*.png"))
    for name, text in READERS_FILES.items():
        os.makedirs(os.path.dirname(os.path.join(scratch, name)), exist_ok=True)
        with open(os.path.join(scratch, name), "w", encoding="utf-8") as f:
            f.write(text)
    # The sweeps' studies shortened in the copy: 0.1 simulated seconds instead of 3.
    for folder, _, files in os.walk(os.path.join(scratch, "scenarios", "sweeps")):
        for name in files:
            path = os.path.join(folder, name)
            with open(path, encoding="utf-8") as f:
                text = f.read()
            with open(path, "w", encoding="utf-8") as f:
                f.write(re.sub(r"(?m)^(\s*duration:\s*)[0-9.]+", r"\g<1>0.1", text))
    failures, ran, elsewhere = [], 0, 0
    for page in pages:
        with open(os.path.join(source, page), encoding="utf-8") as f:
            text = f.read()
        for block_start, lines in sh_blocks(text):
            for line_number, command in commands(block_start, lines):
                where = f"{page}:{line_number}"
                words = shlex.split(command, comments=True)
                if not words:
                    continue
                if words[0] != "particles":
                    without_comment = " ".join(words)
                    if without_comment in ELSEWHERE:
                        elsewhere += 1
                        continue
                    failures.append(f"{where}: `{without_comment}` is neither a particles command nor one "
                                    "that another test runs (tests/docs/doc_commands.py, ELSEWHERE)")
                    continue
                expected = EXPECTED_EXIT.search(command)
                expected_exit = int(expected.group(1)) if expected else 0
                stdout_file = None
                if ">" in words:
                    stdout_file = os.path.join(scratch, words[words.index(">") + 1])
                    words = words[:words.index(">")]
                argv = shortened([particles] + words[1:] + (["--quiet"] if quiet_ok(words) else []))
                started = time.monotonic()
                with open(stdout_file or os.devnull, "wb") as out:
                    result = subprocess.run(argv, cwd=scratch, stdout=out, stderr=subprocess.PIPE)
                ran += 1
                seconds = time.monotonic() - started
                shown = shlex.join(["particles"] + argv[1:])
                print(f"{where}: exit {result.returncode} in {seconds:.1f} s: {shown}", flush=True)
                if result.returncode != expected_exit:
                    failures.append(f"{where}: `{shown}` exited {result.returncode}, not {expected_exit}:\n"
                                    + result.stderr.decode(errors="replace")[-2000:])
    print(f"{ran} commands run, {elsewhere} run by other tests")
    if ran == 0:
        failures.append("no command found in " + ", ".join(pages))
    for failure in failures:
        print("FAILED: " + failure, file=sys.stderr)
    return 1 if failures else 0


def quiet_ok(words):
    """Whether the command takes --quiet (every command but schema, --version and golden's)."""
    return len(words) > 1 and words[1] in ("run", "render", "stability", "sweep", "gather", "plot", "concat")


if __name__ == "__main__":
    sys.exit(main())
