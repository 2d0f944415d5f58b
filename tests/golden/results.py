#!/usr/bin/python3
"""The golden tests' results (golden/README.md, "The report"): DIR/results/NAME.txt, one per test,
written by tests/golden/check_frame.cmake, one `key=value` a line, a backslash and a line break in
a value written as \\\\ and \\n. Read by write_report.py and, through the `plan` command below, by
`scripts/update-golden --from DIR`.

usage: results.py plan DIR FRAMES_TXT [FRAME…]

`plan` says which golden frames the actual frames in DIR can replace, one tab-separated line each:
  accept  FRAME  FILE  TESTS   copy DIR/FILE over golden/FRAME.png (TESTS: the tests that rendered it)
  refuse  FRAME  WHY           the frame's results do not make one new golden frame
  note    TEST   WHY           a failing test that accepting cannot change
Only tests that render the golden's own command (golden_command=yes: golden/frames.txt's options,
any GL backend and thread count) and must match count; a frame whose tests disagree (one fails,
another passes, or their frames differ) is refused, never guessed.
"""
import os
import sys

FAILING_OUTCOMES = ("failed", "error", "unfinished")
REQUIRED_KEYS = ("test", "frame", "expect", "outcome")


def unescape(value):
    out, i = [], 0
    while i < len(value):
        if value[i] == "\\" and i + 1 < len(value):
            out.append("\n" if value[i + 1] == "n" else value[i + 1])
            i += 2
        else:
            out.append(value[i])
            i += 1
    return "".join(out)


def read_result(path):
    """The result in PATH as a dict; ValueError when it is not one."""
    result = {}
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f.read().splitlines(), 1):
            key, equals, value = line.partition("=")
            if not equals or not key:
                raise ValueError(f"line {number} is not key=value: {line!r}")
            result[key] = unescape(value)
    missing = [k for k in REQUIRED_KEYS if k not in result]
    if missing:
        raise ValueError(f"no {', '.join(missing)}")
    return result


def read_results(directory):
    """(results sorted by test name, [(path, why) for files that are not results])."""
    folder = os.path.join(directory, "results")
    results, unreadable = [], []
    names = sorted(os.listdir(folder)) if os.path.isdir(folder) else []
    for name in names:
        if not name.endswith(".txt"):
            continue  # a .partial that a killed test left half written
        path = os.path.join(folder, name)
        try:
            results.append(read_result(path))
        except (OSError, UnicodeDecodeError, ValueError) as error:
            unreadable.append((path, str(error)))
    results.sort(key=lambda r: r["test"])
    return results, unreadable


def golden_frames(frames_txt):
    """The frame names listed in golden/frames.txt."""
    names = []
    with open(frames_txt, encoding="utf-8") as f:
        for line in f:
            words = line.split()
            if words and not words[0].startswith("#") and words[0] != "options:":
                names.append(words[0])
    return names


def kept_file(directory, result, key):
    """The plain file name the result gives under KEY if it is a regular file in DIRECTORY, else None."""
    name = result.get(key, "")
    if not name or "/" in name or name in (".", ".."):
        return None
    return name if os.path.isfile(os.path.join(directory, name)) else None


def renders_golden(result):
    """Whether the test renders the golden's own command and must match: its frame is a candidate golden."""
    return result.get("golden_command") == "yes" and result["expect"] == "match"


def same_bytes(paths):
    with open(paths[0], "rb") as f:
        first = f.read()
    for path in paths[1:]:
        with open(path, "rb") as f:
            if f.read() != first:
                return False
    return True


def plan_frame(directory, frame, own):
    """("accept", FILE, TESTS) or ("refuse", WHY) for one frame, from the results of its own command."""
    not_compared = [r["test"] for r in own if r["outcome"] in ("error", "unfinished")]
    if not_compared:
        return ("refuse", f"{', '.join(not_compared)} did not compare a frame: nothing to accept from")
    failing = [r for r in own if r["outcome"] == "failed"]
    passing = [r["test"] for r in own if r["outcome"] == "passed"]
    if not failing:
        return ("refuse", "no test of its own command fails in this folder")
    if passing:
        return ("refuse", f"{', '.join(r['test'] for r in failing)} fail but {', '.join(passing)} pass: "
                "the backends or thread counts disagree")
    files = [kept_file(directory, r, "actual") for r in failing]
    if None in files:
        lost = [r["test"] for r, f in zip(failing, files) if f is None]
        return ("refuse", f"the actual frame of {', '.join(lost)} is not in the folder")
    if not same_bytes([os.path.join(directory, f) for f in files]):
        return ("refuse", f"the actual frames of {', '.join(r['test'] for r in failing)} differ from each other")
    # Identical, so any one will do: the first by test name, for a stable message.
    return ("accept", files[0], " ".join(r["test"] for r in failing))


def plan(directory, frames_txt, wanted):
    results, unreadable = read_results(directory)
    lines = [("refuse", "?", f"unreadable result {path}: {why}") for path, why in unreadable]
    known = golden_frames(frames_txt)
    if wanted:
        frames = list(wanted)
    else:  # every frame with a failing test of its own command
        frames = sorted({r["frame"] for r in results if renders_golden(r) and r["outcome"] in FAILING_OUTCOMES})
    for frame in frames:
        if frame not in known:
            lines.append(("refuse", frame, "not a frame of golden/frames.txt"))
            continue
        own = [r for r in results if r["frame"] == frame and renders_golden(r)]
        verdict = plan_frame(directory, frame, own)
        lines.append((verdict[0], frame) + verdict[1:])
        for r in results:
            if r["frame"] == frame and r not in own and r["outcome"] in FAILING_OUTCOMES:
                lines.append(("note", r["test"], "fails too; not a candidate for the golden (its render is not the "
                              "golden's own command: a perturbation, another raster path), so see that it passes "
                              "once the frame is accepted"))
    return lines


def main():
    if len(sys.argv) < 4 or sys.argv[1] != "plan":
        sys.exit("usage: results.py plan DIR FRAMES_TXT [FRAME…]")
    for line in plan(sys.argv[2], sys.argv[3], sys.argv[4:]):
        print("\t".join(field.replace("\t", " ").replace("\n", " ") for field in line))


if __name__ == "__main__":
    main()
